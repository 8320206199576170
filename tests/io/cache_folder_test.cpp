// CacheFolder (io/cache_folder.hpp): entries round-trip; bad entries (garbage, truncated,
// another key's, another version's, another format's) are rejected and removed; the size bound
// evicts the least recently used; a folder that is a file, lies under a file or is not writable
// is a clear error naming it; a second job waits for the folder's lock.
#include "io/cache_folder.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <string>
#include <thread>

#include "core/error.hpp"
#include "tests/io/io_test_util.hpp"
#include "tests/support/error_of.hpp"
#include "tests/support/files.hpp"
#include "tests/support/shared_data.hpp"
#include "tests/support/unprivileged.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;

using fleetmerge::testing::ErrorOf;

using ft::Contains;

ContentDigest Key(const std::string& name) { return ContentHashOf(name); }

// What `path` takes on disk: its allocated blocks, as du counts them.
std::int64_t DiskBytes(const fs::path& path) {
  struct stat info {};
  if (::lstat(path.c_str(), &info) != 0) return 0;
  return static_cast<std::int64_t>(info.st_blocks) * 512;
}

// The folder's own blocks and its files' (it holds no subfolders).
std::int64_t FolderDiskBytes(const fs::path& dir) {
  std::int64_t total = DiskBytes(dir);
  for (const auto& f : fs::directory_iterator(dir)) total += DiskBytes(f.path());
  return total;
}

class CacheFolderTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = ft::MakeTempDir("cache_folder") / "cache"; }
  CacheFolderOptions Options(std::int64_t max_bytes = std::int64_t(1) << 30) const {
    CacheFolderOptions options;
    options.max_bytes = max_bytes;
    options.job = "test job";
    return options;
  }
  fs::path dir_;
};

TEST_F(CacheFolderTest, EntriesRoundTripAcrossOpenings) {
  {
    CacheFolder cache(dir_, "1.2.3", Options());
    EXPECT_FALSE(cache.Read(Key("a")));
    cache.Write(Key("a"), std::string("payload\0with a zero", 19));
    cache.Write(Key("b"), "");
    cache.Write(Key("large"), std::string(20 << 20, 'x'));  // a large site map's preparation
    EXPECT_EQ(cache.rejected(), 0);
  }
  CacheFolder cache(dir_, "1.2.3", Options());
  EXPECT_EQ(cache.Read(Key("a")).value_or("absent"), std::string("payload\0with a zero", 19));
  EXPECT_EQ(cache.Read(Key("b")).value_or("absent"), "");
  EXPECT_EQ(cache.Read(Key("large")).value_or("absent"), std::string(20 << 20, 'x'));
  EXPECT_FALSE(cache.Read(Key("c")));
  EXPECT_EQ(cache.rejected(), 0);
  EXPECT_TRUE(fs::exists(dir_ / "CACHEDIR.TAG"));
}

TEST_F(CacheFolderTest, BadEntriesAreRejectedAndRemoved) {
  CacheFolder cache(dir_, "1.2.3", Options());
  const std::string payload(300, 'p');
  const std::string good = CacheEntryBytes(Key("k"), "1.2.3", payload);
  const fs::path path = cache.EntryPath(Key("k"));
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"garbage", "not an entry at all"},
      {"empty", ""},
      {"truncated", good.substr(0, good.size() - 1)},
      {"a byte flipped",
       [&] {
         std::string b = good;
         b[60] ^= 4;
         return b;
       }()},
      {"another key's", CacheEntryBytes(Key("other"), "1.2.3", payload)},
      {"another version's", CacheEntryBytes(Key("k"), "1.2.4", payload)},
      {"another format's", [&] {  // a sound checksum over a format version 2 header
         std::string b = good.substr(0, good.size() - 32);
         b[16] = 2;
         const ContentDigest sum = ContentHashOf(b);
         return b + std::string(sum.begin(), sum.end());
       }()}};
  int rejected = 0;
  for (const auto& [what, bytes] : bad) {
    ft::WriteFile(path, bytes);
    EXPECT_FALSE(cache.Read(Key("k"))) << what;
    EXPECT_EQ(cache.rejected(), ++rejected) << what;
    EXPECT_FALSE(fs::exists(path)) << what << " is removed";
  }
  ft::WriteFile(path, good);
  EXPECT_EQ(cache.Read(Key("k")).value_or(""), payload);
}

// Only a regular file can be an entry: a folder (which made ifstream fail with "Is a directory",
// naming no file), a FIFO (which made the job wait forever, holding the lock) or a link is a bad
// entry, counted and removed, never opened; the entry is then written anew.
TEST_F(CacheFolderTest, AnythingButARegularFileIsABadEntry) {
  CacheFolder cache(dir_, "v", Options());
  const fs::path elsewhere = dir_.parent_path() / "elsewhere.entry";
  ft::WriteFile(elsewhere, CacheEntryBytes(Key("k"), "v", "payload"));
  const std::vector<std::pair<std::string, std::function<void(const fs::path&)>>> makers = {
      {"an empty folder", [](const fs::path& p) { fs::create_directory(p); }},
      {"a FIFO", [](const fs::path& p) { ASSERT_EQ(::mkfifo(p.c_str(), 0644), 0); }},
      {"a link to a sound entry", [&](const fs::path& p) { fs::create_symlink(elsewhere, p); }},
      {"a dangling link", [&](const fs::path& p) { fs::create_symlink(dir_ / "gone", p); }}};
  int rejected = 0;
  for (const auto& [what, make] : makers) {
    const fs::path path = cache.EntryPath(Key("k"));
    make(path);
    EXPECT_FALSE(cache.Read(Key("k"))) << what;
    EXPECT_EQ(cache.rejected(), ++rejected) << what;
    EXPECT_FALSE(fs::exists(fs::symlink_status(path))) << what << " is removed";
    cache.Write(Key("k"), "payload");
    EXPECT_EQ(cache.Read(Key("k")).value_or("absent"), "payload") << what;
    fs::remove(path);
  }
  EXPECT_EQ(ft::ReadFile(elsewhere), CacheEntryBytes(Key("k"), "v", "payload"));  // untouched
  // A folder with files in it is not emptied (not fleetmerge's to delete); the job goes on.
  fs::create_directories(cache.EntryPath(Key("k")) / "inside");
  EXPECT_FALSE(cache.Read(Key("k")));
  EXPECT_EQ(cache.rejected(), ++rejected);
  EXPECT_TRUE(fs::exists(cache.EntryPath(Key("k")) / "inside"));
}

TEST_F(CacheFolderTest, EvictsTheLeastRecentlyUsedBeyondTheBound) {
  const std::string payload(1000, 'x');
  std::int64_t entry_bytes = 0, folder_bytes = 0;  // on disk
  {
    CacheFolder cache(dir_, "v", Options());
    for (int k = 0; k < 6; ++k) cache.Write(Key(std::to_string(k)), payload);
    ft::WriteFile(dir_ / "notes.txt", "a user's file, not an entry");
    entry_bytes = DiskBytes(cache.EntryPath(Key("0")));
    folder_bytes = FolderDiskBytes(dir_);
  }
  // Ages 0 (oldest) .. 5, an hour apart; then entry 0 is read: the most recently used.
  const auto now = fs::file_time_type::clock::now();
  for (int k = 0; k < 6; ++k) {
    fs::last_write_time(dir_ / (ToHex(Key(std::to_string(k))) + ".entry"),
                        now - std::chrono::hours(10 - k));
  }
  // A killed job's temporary file is removed by the eviction too.
  const fs::path temp = dir_ / ("." + ToHex(Key("9")) + ".entry.tmp.1234abcd");
  ft::WriteFile(temp, "half");
  // Room for all but three entries (and half of one).
  CacheFolder cache(dir_, "v", Options(folder_bytes - 3 * entry_bytes + entry_bytes / 2));
  ASSERT_TRUE(cache.Read(Key("0")));
  EXPECT_EQ(cache.Evict().removed, 3);
  EXPECT_TRUE(cache.Read(Key("0")));   // used last
  EXPECT_FALSE(cache.Read(Key("1")));  // the oldest unused ones went
  EXPECT_FALSE(cache.Read(Key("2")));
  EXPECT_FALSE(cache.Read(Key("3")));
  EXPECT_TRUE(cache.Read(Key("4")));
  EXPECT_TRUE(cache.Read(Key("5")));
  EXPECT_FALSE(fs::exists(temp));
  EXPECT_TRUE(fs::exists(dir_ / "notes.txt"));
  EXPECT_EQ(cache.Evict().removed, 0);
}

// An entry of ~370 bytes takes a whole block of the file system (4 KiB on ext4): the bound
// limits the blocks, so that the folder never takes more than its bound on disk.
TEST_F(CacheFolderTest, TheBoundLimitsWhatTheFolderTakesOnDisk) {
  const std::int64_t bound = 64 << 10;
  {
    CacheFolder cache(dir_, "v", Options());
    for (int k = 0; k < 40; ++k) cache.Write(Key(std::to_string(k)), std::string(300, 'x'));
  }
  CacheFolder cache(dir_, "v", Options(bound));
  EXPECT_GT(cache.Evict().removed, 0);
  EXPECT_LE(FolderDiskBytes(dir_), bound);
  int left = 0;
  for (int k = 0; k < 40; ++k) left += cache.Read(Key(std::to_string(k))).has_value();
  EXPECT_GT(left, 0);
}

// Entries whose times lie in the future (a clock that was ahead, a cache copied with its times)
// look more recently used than the ones this job just wrote; the job's own are kept anyway and
// the others go.
TEST_F(CacheFolderTest, EvictionNeverRemovesTheEntriesThisOpeningUsed) {
  const std::string payload(1000, 'x');
  std::int64_t folder_bytes = 0;  // with four entries, on disk
  {
    CacheFolder cache(dir_, "v", Options());
    for (int k = 0; k < 4; ++k) cache.Write(Key("future " + std::to_string(k)), payload);
    folder_bytes = FolderDiskBytes(dir_);
  }
  const auto later = fs::file_time_type::clock::now() + std::chrono::hours(24);
  for (int k = 0; k < 4; ++k) {
    fs::last_write_time(dir_ / (ToHex(Key("future " + std::to_string(k))) + ".entry"), later);
  }
  CacheFolder cache(dir_, "v", Options(folder_bytes));  // room for four entries
  ASSERT_TRUE(cache.Read(Key("future 0")));
  for (int k = 0; k < 3; ++k) cache.Write(Key("new " + std::to_string(k)), payload);
  const CacheEviction eviction = cache.Evict();
  EXPECT_EQ(eviction.removed, 3);
  EXPECT_EQ(eviction.in_use, 4);
  EXPECT_FALSE(eviction.over_bound);
  EXPECT_TRUE(cache.Read(Key("future 0")));
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(cache.Read(Key("new " + std::to_string(k)))) << k;
  for (int k = 1; k < 4; ++k) EXPECT_FALSE(cache.Read(Key("future " + std::to_string(k)))) << k;
}

// A bound below what one job needs keeps the job's entries all the same (its re-run finds them),
// and says so; the other entries go.
TEST_F(CacheFolderTest, ABoundBelowOneJobsEntriesKeepsThemAndSaysSo) {
  const std::string payload(1000, 'x');
  {
    CacheFolder cache(dir_, "v", Options());
    cache.Write(Key("another job's"), payload);
  }
  CacheFolder cache(dir_, "v", Options(1));
  for (int k = 0; k < 5; ++k) cache.Write(Key(std::to_string(k)), payload);
  const CacheEviction eviction = cache.Evict();
  EXPECT_EQ(eviction.removed, 1);
  EXPECT_EQ(eviction.in_use, 5);
  EXPECT_TRUE(eviction.over_bound);
  EXPECT_GE(eviction.in_use_bytes,
            5 * static_cast<std::int64_t>(CacheEntryBytes(Key("0"), "v", payload).size()));
  for (int k = 0; k < 5; ++k) EXPECT_TRUE(cache.Read(Key(std::to_string(k)))) << k;
  EXPECT_FALSE(cache.Read(Key("another job's")));
}

// A cache an older fleetmerge filled (format 1: entries named by 64 hex digits, SHA-256 keys)
// is never read by this one, so its entries go at the first eviction, whatever the bound.
TEST_F(CacheFolderTest, EvictionRemovesTheEntriesOfTheOlderFormat) {
  { CacheFolder cache(dir_, "v", Options()); }
  const fs::path old_entry = dir_ / (std::string(64, 'a') + ".entry");
  ft::WriteFile(old_entry, "fleetmerge cache of format 1");
  ft::WriteFile(dir_ / "notes.txt", "a user's file, not an entry");
  CacheFolder cache(dir_, "v", Options());
  cache.Write(Key("new"), "payload");
  EXPECT_EQ(cache.Evict().removed, 1);
  EXPECT_FALSE(fs::exists(old_entry));
  EXPECT_EQ(cache.Read(Key("new")).value_or("absent"), "payload");
  EXPECT_TRUE(fs::exists(dir_ / "notes.txt"));
}

TEST_F(CacheFolderTest, AFolderThatIsAFileIsAnErrorNamingIt) {
  fs::create_directories(dir_.parent_path());
  ft::WriteFile(dir_, "a file");
  const std::string error = ErrorOf([&] { CacheFolder cache(dir_, "v", Options()); });
  EXPECT_TRUE(Contains(error, "cache folder " + dir_.string() + " exists and is not a folder"))
      << error;
  EXPECT_EQ(ft::ReadFile(dir_), "a file");  // untouched
}

TEST_F(CacheFolderTest, AFolderUnderAFileIsAnErrorNamingIt) {
  fs::create_directories(dir_.parent_path());
  ft::WriteFile(dir_.parent_path() / "plain", "");
  const fs::path under = dir_.parent_path() / "plain" / "cache";
  const std::string error = ErrorOf([&] { CacheFolder cache(under, "v", Options()); });
  EXPECT_TRUE(Contains(error, "cache folder " + under.string())) << error;
}

// A folder of someone's files (say the job's maps) is not made a cache: its CACHEDIR.TAG would
// make backups made with --exclude-caches skip those files. An empty folder and a fleetmerge cache
// are taken.
TEST_F(CacheFolderTest, ANonEmptyFolderThatIsNoCacheIsRefused) {
  fs::create_directories(dir_);
  ft::WriteFile(dir_ / "robot1.yaml", "image: robot1.pgm");
  const std::string error = ErrorOf([&] { CacheFolder cache(dir_, "v", Options()); });
  EXPECT_TRUE(Contains(error, "cache folder " + dir_.string() +
                                  " is not empty and is not a fleetmerge cache (it holds "
                                  "'robot1.yaml'"))
      << error;
  EXPECT_TRUE(Contains(error, "give a new or empty folder, or a fleetmerge cache folder")) << error;
  EXPECT_FALSE(fs::exists(dir_ / "CACHEDIR.TAG"));
  // Another program's cache (its own CACHEDIR.TAG) is not fleetmerge's either.
  ft::WriteFile(dir_ / "CACHEDIR.TAG", "Signature: 8a477f597d28d172789f06886806bc55\n");
  EXPECT_TRUE(Contains(ErrorOf([&] { CacheFolder cache(dir_, "v", Options()); }),
                       "is not a fleetmerge cache"));
  const fs::path empty = dir_.parent_path() / "empty";
  fs::create_directories(empty);
  { CacheFolder cache(empty, "v", Options()); }
  ft::WriteFile(empty / "notes.txt", "a user's note in a fleetmerge cache");
  CacheFolder cache(empty, "v", Options());  // now a fleetmerge cache
  EXPECT_TRUE(fs::exists(empty / "CACHEDIR.TAG"));
}

TEST_F(CacheFolderTest, AFolderHoldingAnInputIsRefused) {
  { CacheFolder cache(dir_, "v", Options()); }
  fs::create_directories(dir_ / "maps");
  ft::WriteFile(dir_ / "maps" / "robot1.pgm", "P5 1 1 255 x");
  CacheFolderOptions options = Options();
  options.inputs = {dir_.parent_path() / "job.yaml", dir_ / "maps" / ".." / "maps" / "robot1.pgm"};
  const std::string error = ErrorOf([&] { CacheFolder cache(dir_, "v", options); });
  EXPECT_TRUE(Contains(error, "cache folder " + dir_.string() + " holds the job's input file " +
                                  options.inputs[1].string()))
      << error;
}

// As root (CI's fresh machines) the folder is `nobody`'s and the cache is opened as `nobody`:
// root writes any folder.
TEST_F(CacheFolderTest, AnUnwritableFolderIsAnErrorNamingIt) {
  const auto user = ft::UserWithoutPrivileges();
  if (!user) GTEST_SKIP() << "running as root on a system without the user nobody";
  fs::create_directories(dir_);
  ft::GiveTo(dir_, *user);
  fs::permissions(dir_, fs::perms::owner_read | fs::perms::owner_exec);
  const auto error = ft::ErrorAs(*user, dir_, [&] { CacheFolder cache(dir_, "v", Options()); });
  fs::permissions(dir_, fs::perms::owner_all);
  if (!error) GTEST_SKIP() << "user " << user->uid << " cannot reach " << dir_;
  EXPECT_TRUE(Contains(*error, "cache folder " + dir_.string() + " is not writable")) << *error;
}

// `--cache real` and `--cache link` (link -> real) are one cache: the second waits for the first.
TEST_F(CacheFolderTest, ALinkToTheFolderIsTheSameCache) {
  fs::create_directories(dir_);
  const fs::path link = dir_.parent_path() / "link";
  fs::create_directory_symlink(dir_, link);
  CacheFolder first(dir_, "v", Options());
  const std::string error = ErrorOf([&] { CacheFolder second(link, "v", Options()); });
  EXPECT_TRUE(Contains(error, "is in use by test job")) << error;
}

// The cache's lock file is inside the folder, so a cache whose parent only root may write
// (/var/cache/fleetmerge of a service user) works.
TEST_F(CacheFolderTest, TheLockLivesInsideTheFolder) {
  {
    CacheFolder cache(dir_, "v", Options());
    EXPECT_TRUE(fs::exists(dir_ / ".fleetmerge-lock"));
    EXPECT_FALSE(fs::exists(dir_.parent_path() / ".cache.fleetmerge-lock"));
  }
  EXPECT_FALSE(fs::exists(dir_ / ".fleetmerge-lock"));  // removed on release
}

TEST_F(CacheFolderTest, AFolderWhoseParentIsReadOnlyIsUsable) {
  { CacheFolder cache(dir_, "v", Options()); }
  const auto user = ft::UserWithoutPrivileges();
  if (!user) GTEST_SKIP() << "running as root on a system without the user nobody";
  ft::GiveTo(dir_, *user);  // the cache is the user's, its parent is not theirs to write
  const fs::perms read_only = fs::perms::owner_read | fs::perms::owner_exec |
                              fs::perms::group_read | fs::perms::group_exec |
                              fs::perms::others_read | fs::perms::others_exec;
  fs::permissions(dir_.parent_path(), read_only);
  const auto error = ft::ErrorAs(*user, dir_, [&] {
    CacheFolder cache(dir_, "v", Options());
    cache.Write(Key("a"), "an entry");
  });
  fs::permissions(dir_.parent_path(), fs::perms::owner_all);
  if (!error) GTEST_SKIP() << "user " << user->uid << " cannot reach " << dir_;
  EXPECT_EQ(*error, "");
}

TEST_F(CacheFolderTest, ASecondJobWaitsForTheLockOrFailsNamingTheHolder) {
  std::optional<CacheFolder> first;
  first.emplace(dir_, "v", Options());
  first->Write(Key("a"), "from the first job");
  const std::string error = ErrorOf([&] { CacheFolder second(dir_, "v", Options()); });
  EXPECT_TRUE(Contains(error, "cache folder")) << error;
  EXPECT_TRUE(Contains(error, "test job")) << error;
  std::thread release([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    first.reset();
  });
  CacheFolderOptions wait = Options();
  wait.lock_wait_s = 30;
  CacheFolder second(dir_, "v", wait);  // waits for the first, then sees its entry
  release.join();
  EXPECT_EQ(second.Read(Key("a")).value_or(""), "from the first job");
}

}  // namespace
}  // namespace fleetmerge
