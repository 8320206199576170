// A folder of cache entries that re-runs share (the pair cache, pipeline/pair_cache.hpp, keeps
// its pairs' hypotheses and its maps' preparations here). Each entry is one file, `<key>.entry`,
// named by the 32 hex digits of its key (io/content_hash.hpp: the hash of everything its content
// depends on) and written atomically (io/atomic_file.hpp). Its bytes:
//
//   "fleetmerge cache" (16 bytes)  format magic
//   u32 kFormatVersion             this layout
//   u32 0x01020304                 byte order of the machine that wrote it
//   u32 n, n bytes                 the fleetmerge version that wrote it
//   16 bytes                       the key (must equal the file name's)
//   u64 n, n bytes                 the payload
//   16 bytes                       the content hash of all the bytes above
//
// An entry is trusted only when all of that checks out: a truncated, corrupt or foreign file
// (another key's entry under this name, another version's, another byte order's), a file that
// cannot be read, and anything at an entry's name that is not a regular file (a folder, a FIFO,
// a link) is counted, removed and reported as absent, so its caller computes it again and
// writes it anew: no entry can fail or stall a job.
//
// One job at a time: the folder is locked (io/folder_lock.hpp, label "cache folder", by
// `.fleetmerge-lock` inside it) from the constructor to Unlock (or the destructor). A second job
// sharing the cache waits for the first and then finds the first job's entries. Entries read are
// marked as used (their modification time), and Evict removes the least recently used until the
// folder fits its size bound. The entries this opening read or wrote are never evicted, whatever
// their times say (a clock that was ahead, a cache copied with its times) and whatever the bound:
// evicting them would make the job's re-run compute them again, the very work the cache is there to
// save.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "io/content_hash.hpp"
#include "io/folder_lock.hpp"

namespace fleetmerge {

struct CacheFolderOptions {
  std::int64_t max_bytes = std::int64_t(1024) << 20;  // on disk (allocated blocks)
  double lock_wait_s = 0.0;  // for another job using the folder (0: fail at once)
  FolderLock::WaitNotice lock_notice;
  std::string job;  // who holds the lock (named to a waiting job)
  // The job's input files (maps, job file): none may lie inside the folder.
  std::vector<std::filesystem::path> inputs;
};

// What an eviction did.
struct CacheEviction {
  int removed = 0;  // entries removed (never one of this opening's)
  int in_use = 0;   // entries this opening read or wrote, all kept
  std::int64_t in_use_bytes = 0;
  bool over_bound = false;  // the entries in use alone take more than the bound
};

class CacheFolder {
 public:
  static constexpr std::uint32_t kFormatVersion = 2;  // 2: 128-bit XXH3 keys and checksums

  // Creates `dir` (and its parents) if needed and locks it. Entries are valid only for
  // `version` (fleetmerge's): others are never trusted. Throws fleetmerge::Error naming `dir`
  // when it is not a folder, is a folder neither empty nor a fleetmerge cache (marked by its
  // CACHEDIR.TAG), holds one of options.inputs, cannot be created, or is not writable, or when
  // another job holds it beyond options.lock_wait_s.
  CacheFolder(const std::filesystem::path& dir, const std::string& version,
              const CacheFolderOptions& options);
  CacheFolder(const CacheFolder&) = delete;
  CacheFolder& operator=(const CacheFolder&) = delete;

  // The payload stored under `key`; nullopt when there is none or it is not to be trusted (then
  // the file is removed and counted in rejected()). Safe to call from several threads.
  std::optional<std::string> Read(const ContentDigest& key);
  // Removes the entry under `key`, counted in rejected(): for a caller that found its payload
  // unusable.
  void Discard(const ContentDigest& key);
  // Stores `payload` under `key`, replacing any entry. Throws fleetmerge::Error naming the file
  // when it cannot be written. Safe to call from several threads.
  void Write(const ContentDigest& key, const std::string& payload);
  // Removes the least recently used entries (and temporary files of killed jobs, and entries of
  // the older format 1) until the folder takes at most options.max_bytes on disk (its files'
  // allocated blocks, the folder's own included), but never an entry
  // this opening read or wrote: when those alone take more, they are all kept (over_bound).
  CacheEviction Evict();

  // Releases the folder's lock: another job may use it now. Read, Write and Evict must not be
  // called afterwards (they throw fleetmerge::Error).
  void Unlock();

  std::filesystem::path EntryPath(const ContentDigest& key) const;
  const std::filesystem::path& dir() const { return dir_; }  // links resolved
  int rejected() const { return rejected_; }

 private:
  void CheckLocked() const;
  void MarkUsed(const ContentDigest& key);
  std::filesystem::path dir_;  // links resolved (ResolvedFolder)
  std::string shown_;          // as the caller named it, for messages
  std::string version_;
  std::int64_t max_bytes_;
  std::optional<FolderLock> lock_;
  std::atomic<int> rejected_{0};
  std::mutex used_mutex_;
  std::set<std::string> used_;  // file names of the entries read or written
};

// The entry file's bytes for `payload` (exposed for tests that forge entries).
std::string CacheEntryBytes(const ContentDigest& key, const std::string& version,
                            const std::string& payload);

}  // namespace fleetmerge
