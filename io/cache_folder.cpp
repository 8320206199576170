#include "io/cache_folder.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <tuple>
#include <vector>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/raw_bytes.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

constexpr char kMagic[16] = {'f', 'l', 'e', 'e', 't', 'm', 'e', 'r',
                             'g', 'e', ' ', 'c', 'a', 'c', 'h', 'e'};
constexpr std::uint32_t kByteOrderMark = 0x01020304;
constexpr const char* kEntryExtension = ".entry";
constexpr const char* kCacheDirTagName = "CACHEDIR.TAG";
constexpr const char* kCacheDirSignature = "Signature: 8a477f597d28d172789f06886806bc55\n";
// The tag's second line marks the folder as fleetmerge's (every fleetmerge wrote it).
constexpr const char* kCacheDirTagMark = "# This file marks a fleetmerge cache folder";
// Tells backup and archiving tools that the folder holds a cache (https://bford.info/cachedir/).
constexpr const char* kCacheDirTag =
    "Signature: 8a477f597d28d172789f06886806bc55\n"
    "# This file marks a fleetmerge cache folder (fleetmerge merge --cache): re-runs reuse its\n"
    "# entries; it may be deleted at any time.\n";

// The payload of `bytes` when it is a sound entry for `key` and `version`.
std::optional<std::string> ParseEntry(const std::string& bytes, const ContentDigest& key,
                                      const std::string& version) {
  constexpr std::size_t kChecksumSize = sizeof(ContentDigest);
  if (bytes.size() < sizeof kMagic + kChecksumSize) return std::nullopt;
  const std::size_t body_size = bytes.size() - kChecksumSize;
  ContentHash hash;
  hash.Update(bytes.data(), body_size);
  const ContentDigest checksum = hash.Finish();
  if (std::memcmp(checksum.data(), bytes.data() + body_size, kChecksumSize) != 0) {
    return std::nullopt;  // truncated, corrupt, or not an entry at all
  }
  RawBytesReader reader(bytes);
  char magic[sizeof kMagic];
  std::uint32_t format = 0, byte_order = 0, version_size = 0;
  std::string entry_version;
  ContentDigest entry_key{};
  std::uint64_t payload_size = 0;
  std::string payload;
  if (!reader.Read(magic) || std::memcmp(magic, kMagic, sizeof kMagic) != 0 ||
      !reader.Read(format) || format != CacheFolder::kFormatVersion || !reader.Read(byte_order) ||
      byte_order != kByteOrderMark || !reader.Read(version_size) ||
      !reader.ReadBytes(version_size, entry_version) || entry_version != version ||
      !reader.Read(entry_key) || entry_key != key || !reader.Read(payload_size) ||
      payload_size > body_size || !reader.ReadBytes(payload_size, payload) ||
      reader.offset() != body_size) {
    return std::nullopt;
  }
  return payload;
}

constexpr std::size_t kKeyDigits = 2 * sizeof(ContentDigest);
// Entries hold a pair's few hypotheses (~330 bytes) or a map's kept preparation (about a byte a
// cell of its distance fields: 13.5-17 MB for scripts/large_site_benchmark.sh's 4000 x 4000 site,
// ~130 MB for a map of max_map_cells' default 10^8 cells): a file beyond this is no entry, and is
// not read whole into memory.
constexpr std::size_t kLargestEntryBytes = std::size_t(1) << 30;
// Format 1 named its entries by 64 hex digits (SHA-256 keys): no reader finds them any more.
constexpr std::size_t kFormat1KeyDigits = 64;

bool IsEntryName(const std::string& name, std::size_t key_digits = kKeyDigits) {
  const std::size_t ext = std::strlen(kEntryExtension);
  if (name.size() != key_digits + ext || name.compare(key_digits, ext, kEntryExtension) != 0) {
    return false;
  }
  return std::all_of(name.begin(), name.begin() + key_digits,
                     [](char c) { return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'); });
}

// `.<entry name>.tmp.<random>`: WriteFileAtomically's temporary file of an entry.
bool IsEntryTempName(const std::string& name) {
  const std::size_t entry = kKeyDigits + std::strlen(kEntryExtension);
  if (name.size() < 1 + entry + 5 || name[0] != '.') return false;
  return IsEntryName(name.substr(1, entry)) && name.compare(1 + entry, 5, ".tmp.") == 0;
}

// What `path` takes on its file system (its allocated blocks; not followed if a link), 0 when it
// is gone. A ~330-byte entry takes a whole block (4 KiB on ext4), so file sizes would let the
// folder grow to ~12 times its bound.
std::int64_t DiskBytes(const fs::path& path) {
  struct stat info {};
  if (::lstat(path.c_str(), &info) != 0) return 0;
  return static_cast<std::int64_t>(info.st_blocks) * 512;  // st_blocks counts 512-byte units
}

// Up to `limit` bytes of `path` when it is a regular file (not followed if a link; a FIFO is
// never opened, so never waited on), nullopt otherwise or when it cannot be read.
std::optional<std::string> ReadRegularFile(const fs::path& path, std::size_t limit) {
  struct stat info {};
  if (::lstat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode)) return std::nullopt;
  // O_NONBLOCK: should a FIFO take the file's place after the check, open does not wait for a
  // writer (and fstat then refuses it).
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return std::nullopt;
  std::optional<std::string> bytes;
  if (::fstat(fd, &info) == 0 && S_ISREG(info.st_mode)) {
    bytes.emplace();
    bytes->reserve(std::min(static_cast<std::size_t>(std::max<off_t>(info.st_size, 0)), limit));
    char buffer[1 << 16];
    while (bytes->size() < limit) {
      const ssize_t n = ::read(fd, buffer, std::min(sizeof buffer, limit - bytes->size()));
      if (n == 0) break;
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        bytes.reset();
        break;
      }
      bytes->append(buffer, static_cast<std::size_t>(n));
    }
  }
  ::close(fd);
  return bytes;
}

bool IsFleetmergeCache(const fs::path& dir) {
  const std::optional<std::string> tag = ReadRegularFile(dir / kCacheDirTagName, 4096);
  return tag && tag->rfind(kCacheDirSignature, 0) == 0 &&
         tag->find(kCacheDirTagMark) != std::string::npos;
}

// Throws unless `dir` (an existing folder) may become a cache: it is empty or a fleetmerge
// cache. Anything else is someone's files, which the CACHEDIR.TAG written next would hide from
// backups made with --exclude-caches (and which the eviction would sit beside).
void CheckEmptyOrCache(const fs::path& dir, const std::string& shown) {
  if (IsFleetmergeCache(dir)) return;
  const std::string tag_temp = std::string(".") + kCacheDirTagName + ".tmp.";
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    // A job creating this cache at this moment: its lock, its tag being written.
    if (name == FolderLockPath(dir, LockFilePlace::kInsideFolder).filename() ||
        name.rfind(tag_temp, 0) == 0) {
      continue;
    }
    throw Error("cache folder " + shown +
                " is not empty and is not a fleetmerge cache (it holds '" + name +
                "' and no CACHEDIR.TAG written by fleetmerge); give a new or empty folder, " +
                "or a fleetmerge cache folder (fleetmerge marks its cache with CACHEDIR.TAG, " +
                "which makes backup tools skip the whole folder)");
  }
  if (ec) throw Error("cache folder " + shown + ": cannot list it: " + ec.message());
}

// Throws when one of `inputs` lies inside `dir` (checked through links).
void CheckHoldsNoInput(const fs::path& dir, const std::string& shown,
                       const std::vector<fs::path>& inputs) {
  std::error_code ec;
  const fs::path folder = fs::weakly_canonical(dir, ec);
  if (ec) return;
  for (const fs::path& input : inputs) {
    if (input.empty()) continue;
    const fs::path file = fs::weakly_canonical(input, ec);
    if (ec) continue;
    const fs::path relative = file.lexically_relative(folder);
    if (relative.empty() || *relative.begin() == "..") continue;
    throw Error("cache folder " + shown + " holds the job's input file " + input.string() +
                "; the cache folder is fleetmerge's (CACHEDIR.TAG makes backup tools skip it): " +
                "give the cache a folder of its own");
  }
}

}  // namespace

std::string CacheEntryBytes(const ContentDigest& key, const std::string& version,
                            const std::string& payload) {
  std::string bytes(kMagic, sizeof kMagic);
  AppendRaw(bytes, CacheFolder::kFormatVersion);
  AppendRaw(bytes, kByteOrderMark);
  AppendRaw(bytes, static_cast<std::uint32_t>(version.size()));
  bytes += version;
  AppendRaw(bytes, key);
  AppendRaw(bytes, static_cast<std::uint64_t>(payload.size()));
  bytes += payload;
  AppendRaw(bytes, ContentHashOf(bytes));
  return bytes;
}

CacheFolder::CacheFolder(const fs::path& dir, const std::string& version,
                         const CacheFolderOptions& options)
    // One folder, one lock, however it is spelled (a link to the folder included).
    : dir_(ResolvedFolder(dir)),
      shown_(dir.string()),
      version_(version),
      max_bytes_(options.max_bytes) {
  std::error_code ec;
  if (fs::exists(dir_, ec) && !fs::is_directory(dir_, ec)) {
    throw Error("cache folder " + shown_ + " exists and is not a folder");
  }
  if (fs::is_directory(dir_, ec)) CheckEmptyOrCache(dir_, shown_);
  CheckHoldsNoInput(dir_, shown_, options.inputs);
  // The lock file lives inside the folder (the folder is fleetmerge's; its parent may be
  // another user's), so the folder is made first.
  fs::create_directories(dir_, ec);
  if (ec) throw Error("cache folder " + shown_ + ": cannot create it: " + ec.message());
  if (::access(dir_.c_str(), W_OK | X_OK) != 0) {
    throw Error("cache folder " + shown_ + " is not writable: " + std::strerror(errno));
  }
  lock_.emplace(dir_, options.job, options.lock_wait_s, "cache folder", options.lock_notice,
                LockFilePlace::kInsideFolder);
  // Written (atomically) at every opening: that also proves the folder writable now, rather
  // than after a job's worth of pairs.
  try {
    WriteFileAtomically(dir_ / kCacheDirTagName, kCacheDirTag);
  } catch (const Error& e) {
    throw Error("cache folder " + shown_ + " is not writable: " + e.what());
  }
}

fs::path CacheFolder::EntryPath(const ContentDigest& key) const {
  return dir_ / (ToHex(key) + kEntryExtension);
}

void CacheFolder::Unlock() { lock_.reset(); }

void CacheFolder::CheckLocked() const {
  if (!lock_) throw Error("internal: cache folder " + dir_.string() + " used after Unlock");
}

std::optional<std::string> CacheFolder::Read(const ContentDigest& key) {
  CheckLocked();
  const fs::path path = EntryPath(key);
  struct stat info {};
  if (::lstat(path.c_str(), &info) != 0) return std::nullopt;  // absent
  // A folder, FIFO, link or anything else at the entry's name, and a file that cannot be read,
  // is a bad entry like a corrupt one: the job goes on without it (a FIFO is never opened: it
  // would wait for a writer forever, holding the cache's lock).
  const std::optional<std::string> bytes = ReadRegularFile(path, kLargestEntryBytes);
  std::optional<std::string> payload = bytes ? ParseEntry(*bytes, key, version_) : std::nullopt;
  std::error_code ec;
  if (!payload) {
    ++rejected_;
    fs::remove(path, ec);  // a file, link, FIFO or empty folder (never what a folder holds)
    return std::nullopt;
  }
  // Used now: the last to be evicted by later jobs (a failure only makes it look older to them).
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);
  MarkUsed(key);
  return payload;
}

void CacheFolder::Discard(const ContentDigest& key) {
  CheckLocked();
  ++rejected_;
  std::error_code ec;
  fs::remove(EntryPath(key), ec);
}

void CacheFolder::MarkUsed(const ContentDigest& key) {
  const std::lock_guard<std::mutex> lock(used_mutex_);
  used_.insert(EntryPath(key).filename().string());
}

void CacheFolder::Write(const ContentDigest& key, const std::string& payload) {
  CheckLocked();
  const std::string bytes = CacheEntryBytes(key, version_, payload);
  if (bytes.size() > kLargestEntryBytes) {  // Read would refuse it
    throw Error(EntryPath(key).string() + ": an entry of " + std::to_string(bytes.size()) +
                " bytes, more than an entry may hold (" + std::to_string(kLargestEntryBytes) + ")");
  }
  WriteFileAtomically(EntryPath(key), bytes, {}, AtomicWrite::kNoSync);
  MarkUsed(key);
}

CacheEviction CacheFolder::Evict() {
  CheckLocked();
  const std::lock_guard<std::mutex> lock(used_mutex_);
  struct Entry {
    fs::file_time_type used;
    fs::path path;
    std::int64_t bytes;
  };
  std::vector<Entry> entries;
  // The folder's own blocks and its other files (CACHEDIR.TAG, the lock) count too: the bound is
  // on what the folder takes on disk.
  std::int64_t total = DiskBytes(dir_);
  CacheEviction eviction;
  int& removed = eviction.removed;
  std::error_code ec;
  for (fs::directory_iterator it(dir_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    std::error_code entry_ec;
    if (IsEntryTempName(name)) {  // the folder is locked: nobody is writing it
      fs::remove(it->path(), entry_ec);
      continue;
    }
    if (IsEntryName(name, kFormat1KeyDigits)) {  // an older fleetmerge's: never read again
      removed += fs::remove(it->path(), entry_ec) ? 1 : 0;
      continue;
    }
    const std::int64_t bytes = DiskBytes(it->path());
    total += bytes;
    if (!IsEntryName(name) || !it->is_regular_file(entry_ec) || it->is_symlink(entry_ec)) continue;
    const fs::file_time_type used = it->last_write_time(entry_ec);
    if (entry_ec) continue;
    if (used_.count(name) != 0) {  // this job's: counted, never a candidate
      ++eviction.in_use;
      eviction.in_use_bytes += bytes;
      continue;
    }
    entries.push_back({used, it->path(), bytes});
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return std::tie(a.used, a.path) < std::tie(b.used, b.path);
  });
  for (const Entry& entry : entries) {
    if (total <= max_bytes_) break;
    std::error_code remove_ec;
    if (fs::remove(entry.path, remove_ec)) {
      total -= entry.bytes;
      ++removed;
    }
  }
  eviction.over_bound = eviction.in_use_bytes > max_bytes_;
  return eviction;
}

}  // namespace fleetmerge
