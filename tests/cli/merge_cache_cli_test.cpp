// `fleetmerge merge --cache DIR` and the job key `cache:` end to end: a re-run takes its pairs
// from the cache (printed, and in report.json) with the same result; a cache folder that is a
// file fails the job naming it; a cache entry of garbage is rebuilt.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/folder_lock.hpp"
#include "tests/support/files.hpp"
#include "tests/support/fleetmerge_cli.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::Fleetmerge;
using testing::ReadFile;
using testing::ShellQuote;
using testing::WriteFile;

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

class MergeCacheCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::MakeTempDir("merge_cache_cli");
    ASSERT_EQ(Fleetmerge("example " + ShellQuote(dir_ / "ex")).exit_code, 0);
  }
  testing::CommandResult Merge(const fs::path& out, const std::string& extra) const {
    return Fleetmerge("merge --quiet --out " + ShellQuote(out) + " " + extra + " " +
                      ShellQuote(dir_ / "ex" / "robot_a.yaml") + " " +
                      ShellQuote(dir_ / "ex" / "robot_b.yaml"));
  }
  // report.json without what differs between runs of one job (times, the cache's counts).
  static json Comparable(json report) {
    report.erase("timing_ms");
    report.erase("cache");
    return report;
  }
  fs::path dir_;
};

TEST_F(MergeCacheCliTest, ARerunTakesThePairFromTheCache) {
  const fs::path cache = dir_ / "cache";
  const auto plain = Merge(dir_ / "plain", "");
  ASSERT_EQ(plain.exit_code, 0) << plain.both();
  EXPECT_FALSE(Contains(plain.out, "from the cache"));
  const auto cold = Merge(dir_ / "cold", "--cache " + ShellQuote(cache));
  ASSERT_EQ(cold.exit_code, 0) << cold.both();
  EXPECT_TRUE(Contains(cold.out, "merge: pairs: 0 from the cache, 1 computed")) << cold.out;
  const auto warm = Merge(dir_ / "warm", "--cache " + ShellQuote(cache));
  ASSERT_EQ(warm.exit_code, 0) << warm.both();
  EXPECT_TRUE(Contains(warm.out, "merge: pairs: 1 from the cache, 0 computed")) << warm.out;
  const json plain_report = json::parse(ReadFile(dir_ / "plain" / "report.json"));
  const json warm_report = json::parse(ReadFile(dir_ / "warm" / "report.json"));
  EXPECT_FALSE(plain_report.contains("cache"));
  EXPECT_EQ(warm_report["cache"]["dir"], cache.generic_string());
  EXPECT_EQ(warm_report["cache"]["pairs_cached"], 1);
  EXPECT_EQ(warm_report["cache"]["pairs_computed"], 0);
  EXPECT_EQ(warm_report["cache"]["maps_prepared"], 0);
  EXPECT_EQ(warm_report["cache"]["max_mb"], 1024);
  // The same poses, pairs and hypotheses (report.json writes doubles exactly), the same cells.
  EXPECT_EQ(Comparable(warm_report), Comparable(plain_report));
  EXPECT_EQ(ReadFile(dir_ / "warm" / "merged_0.pgm"), ReadFile(dir_ / "plain" / "merged_0.pgm"));
}

TEST_F(MergeCacheCliTest, AJobFilesCacheIsRelativeToItAndTheFlagOverridesIt) {
  fs::create_directories(dir_ / "jobs");
  WriteFile(dir_ / "jobs" / "job.yaml",
            "maps: [../ex/robot_a.yaml, ../ex/robot_b.yaml]\noutput: out\ncache: site_cache\n"
            "cache_max_mb: 5\n");
  const auto first = Fleetmerge("merge --quiet " + ShellQuote(dir_ / "jobs" / "job.yaml"));
  ASSERT_EQ(first.exit_code, 0) << first.both();
  EXPECT_TRUE(Contains(first.out, "pairs: 0 from the cache, 1 computed")) << first.out;
  EXPECT_TRUE(fs::is_directory(dir_ / "jobs" / "site_cache"));
  const json report = json::parse(ReadFile(dir_ / "jobs" / "out" / "report.json"));
  EXPECT_EQ(report["cache"]["max_mb"], 5);
  const auto second = Fleetmerge("merge --quiet " + ShellQuote(dir_ / "jobs" / "job.yaml"));
  EXPECT_TRUE(Contains(second.out, "pairs: 1 from the cache, 0 computed")) << second.out;
  const fs::path other = dir_ / "other_cache";
  const auto flag = Fleetmerge("merge --quiet --cache " + ShellQuote(other) + " " +
                               ShellQuote(dir_ / "jobs" / "job.yaml"));
  ASSERT_EQ(flag.exit_code, 0) << flag.both();
  EXPECT_TRUE(Contains(flag.out, "pairs: 0 from the cache, 1 computed")) << flag.out;
  EXPECT_TRUE(fs::is_directory(other));
}

// A job file's cache_max_mb without cache: is refused, naming it, unless --cache gives the cache.
TEST_F(MergeCacheCliTest, AJobFilesSizeBoundNeedsACacheFromTheFileOrTheFlag) {
  WriteFile(dir_ / "job.yaml",
            "maps: [ex/robot_a.yaml, ex/robot_b.yaml]\noutput: out\ncache_max_mb: 5\n");
  const auto alone = Fleetmerge("merge --quiet " + ShellQuote(dir_ / "job.yaml"));
  EXPECT_EQ(alone.exit_code, 1);
  EXPECT_TRUE(Contains(alone.err,
                       "job.yaml: line 3: key 'cache_max_mb': a size bound without a "
                       "cache"))
      << alone.err;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  const auto flag = Fleetmerge("merge --quiet --cache " + ShellQuote(dir_ / "cache") + " " +
                               ShellQuote(dir_ / "job.yaml"));
  ASSERT_EQ(flag.exit_code, 0) << flag.both();
  EXPECT_EQ(json::parse(ReadFile(dir_ / "out" / "report.json"))["cache"]["max_mb"], 5);
}

// A job file without `seed:` and `merge --out` of the same maps share their pairs.
TEST_F(MergeCacheCliTest, AJobFileAndAMapListShareTheirPairs) {
  const fs::path cache = dir_ / "cache";
  WriteFile(dir_ / "job.yaml",
            "maps: [ex/robot_a.yaml, ex/robot_b.yaml]\noutput: job_out\ncache: cache\n");
  const auto job = Fleetmerge("merge --quiet " + ShellQuote(dir_ / "job.yaml"));
  ASSERT_EQ(job.exit_code, 0) << job.both();
  EXPECT_TRUE(Contains(job.out, "pairs: 0 from the cache, 1 computed")) << job.out;
  const auto list = Merge(dir_ / "list_out", "--cache " + ShellQuote(cache));
  ASSERT_EQ(list.exit_code, 0) << list.both();
  EXPECT_TRUE(Contains(list.out, "pairs: 1 from the cache, 0 computed")) << list.out;
}

TEST_F(MergeCacheCliTest, TwoJobsSharingACacheAtOnceTakeTurns) {
  // Two merges into different folders started together: the second waits for the cache's lock,
  // then finds the first's pair. Either way exactly one of them computes it.
  const fs::path cache = dir_ / "cache";
  std::string both;
  for (const char* out : {"one", "two"}) {
    both += std::string(FLEETMERGE_EXECUTABLE) + " merge --quiet --cache " + ShellQuote(cache) +
            " --out " + ShellQuote(dir_ / out) + " " + ShellQuote(dir_ / "ex" / "robot_a.yaml") +
            " " + ShellQuote(dir_ / "ex" / "robot_b.yaml") + " >" +
            ShellQuote(dir_ / (std::string(out) + ".log")) + " 2>&1 & ";
  }
  ASSERT_EQ(testing::RunCommand(both + "wait").exit_code, 0);
  int computed = 0, cached = 0;
  for (const char* out : {"one", "two"}) {
    const std::string log = ReadFile(dir_ / (std::string(out) + ".log"));
    ASSERT_TRUE(fs::exists(dir_ / out / "report.json")) << log;
    const json report = json::parse(ReadFile(dir_ / out / "report.json"));
    computed += report["cache"]["pairs_computed"].get<int>();
    cached += report["cache"]["pairs_cached"].get<int>();
    EXPECT_EQ(report["cache"]["entries_rejected"], 0) << log;
  }
  EXPECT_EQ(computed, 1);
  EXPECT_EQ(cached, 1);
  EXPECT_EQ(Comparable(json::parse(ReadFile(dir_ / "one" / "report.json"))),
            Comparable(json::parse(ReadFile(dir_ / "two" / "report.json"))));
}

TEST_F(MergeCacheCliTest, ACacheFolderThatIsAFileFailsTheJobNamingIt) {
  const fs::path file = dir_ / "not_a_folder";
  WriteFile(file, "precious");
  const auto run = Merge(dir_ / "out", "--cache " + ShellQuote(file));
  EXPECT_EQ(run.exit_code, 1) << run.both();
  EXPECT_TRUE(Contains(run.err, "cache folder " + file.string() + " exists and is not a folder"))
      << run.err;
  EXPECT_EQ(ReadFile(file), "precious");
  EXPECT_FALSE(fs::exists(dir_ / "out" / "report.json"));
}

// `--cache` naming the folder of the job's maps: refused before anything is written there (a
// CACHEDIR.TAG would make backups skip the maps).
TEST_F(MergeCacheCliTest, AFolderOfMapsIsNotMadeACache) {
  const fs::path maps = dir_ / "ex";
  const auto run = Merge(dir_ / "out", "--cache " + ShellQuote(maps));
  EXPECT_EQ(run.exit_code, 1) << run.both();
  EXPECT_TRUE(Contains(
      run.err, "cache folder " + maps.string() + " is not empty and is not a fleetmerge cache"))
      << run.err;
  EXPECT_FALSE(fs::exists(maps / "CACHEDIR.TAG"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "report.json"));
}

TEST_F(MergeCacheCliTest, ASizeBoundWithoutACacheIsAnError) {
  const auto run = Merge(dir_ / "out", "--cache-max-mb 64");
  EXPECT_EQ(run.exit_code, 1) << run.both();
  EXPECT_TRUE(Contains(run.err, "--cache-max-mb 64: no job uses a cache; give --cache DIR"))
      << run.err;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(MergeCacheCliTest, ACacheInsideTheOutputFolderIsRefused) {
  for (const fs::path& cache : {dir_ / "out" / "cache", dir_ / "out"}) {
    // "out/" is the folder "out" too.
    const auto run = Merge(dir_ / "out/", "--cache " + ShellQuote(cache));
    EXPECT_EQ(run.exit_code, 1) << run.both();
    EXPECT_TRUE(Contains(run.err, "cache folder " + cache.string() +
                                      " is inside the output folder " + (dir_ / "out/").string()))
        << run.err;
    EXPECT_FALSE(fs::exists(cache / "CACHEDIR.TAG"));
  }
}

TEST_F(MergeCacheCliTest, AGarbageEntryIsRebuilt) {
  const fs::path cache = dir_ / "cache";
  ASSERT_EQ(Merge(dir_ / "out", "--cache " + ShellQuote(cache)).exit_code, 0);
  int entries = 0;  // the pair and its two maps' preparations
  for (const auto& f : fs::directory_iterator(cache)) {
    if (f.path().extension() != ".entry") continue;
    WriteFile(f.path(), "garbage, not a cache entry");
    ++entries;
  }
  ASSERT_EQ(entries, 3);
  const auto rebuilt = Merge(dir_ / "out", "--cache " + ShellQuote(cache));
  ASSERT_EQ(rebuilt.exit_code, 0) << rebuilt.both();
  EXPECT_TRUE(Contains(rebuilt.out,
                       "pairs: 0 from the cache, 1 computed; maps' preparations: 0 from the "
                       "cache, 2 made; 3 bad cache entries rebuilt\n"))
      << rebuilt.out;
  const json report = json::parse(ReadFile(dir_ / "out" / "report.json"));
  EXPECT_EQ(report["cache"]["entries_rejected"], 3);
  EXPECT_EQ(report["cache"]["preparations_kept"], 0);
  const auto again = Merge(dir_ / "out", "--cache " + ShellQuote(cache));
  EXPECT_TRUE(Contains(again.out, "pairs: 1 from the cache, 0 computed\n")) << again.out;
}

// A folder or a FIFO in an entry's place is a bad entry like garbage: the job succeeds (before,
// a folder failed it with "basic_filebuf::underflow error reading the file: Is a directory" and a
// FIFO made it wait forever holding the cache's lock).
TEST_F(MergeCacheCliTest, AFolderOrAFifoInAnEntrysPlaceIsRebuilt) {
  const fs::path cache = dir_ / "cache";
  ASSERT_EQ(Merge(dir_ / "out", "--cache " + ShellQuote(cache)).exit_code, 0);
  std::vector<fs::path> entries;  // the pair and its two maps' preparations
  for (const auto& f : fs::directory_iterator(cache)) {
    if (f.path().extension() == ".entry") entries.push_back(f.path());
  }
  ASSERT_EQ(entries.size(), 3u);
  for (const std::string what : {"folder", "fifo"}) {
    for (const fs::path& entry : entries) {
      fs::remove(entry);
      if (what == "folder") {
        fs::create_directory(entry);
      } else {
        ASSERT_EQ(::mkfifo(entry.c_str(), 0644), 0);
      }
    }
    const auto rebuilt = Merge(dir_ / "out", "--cache " + ShellQuote(cache));
    ASSERT_EQ(rebuilt.exit_code, 0) << what << ": " << rebuilt.both();
    EXPECT_TRUE(Contains(rebuilt.out,
                         "pairs: 0 from the cache, 1 computed; maps' preparations: 0 from the "
                         "cache, 2 made; 3 bad cache entries rebuilt\n"))
        << what << ": " << rebuilt.out;
    for (const fs::path& entry : entries) {
      EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(entry))) << what;
    }
  }
}

// 24 maps make 276 pairs and 24 maps' preparations, more than the smallest bound (1 MiB: ~250
// entries of a 4 KiB block): the job keeps them all (its re-run takes every pair from the cache)
// and warns. The maps are one small room (40 x 40 cells) at 24 origins: a pair's entry does not
// depend on the maps' size, and 276 pairs of larger maps would cost a minute under the
// sanitizers.
TEST_F(MergeCacheCliTest, ABoundBelowTheJobsPairsKeepsThemAndWarns) {
  constexpr int kCells = 40;
  std::string pgm = "P5\n" + std::to_string(kCells) + " " + std::to_string(kCells) + "\n255\n";
  for (int y = 0; y < kCells; ++y) {
    for (int x = 0; x < kCells; ++x) {
      const bool wall = x == 2 || y == 2 || x == kCells - 3 || y == kCells - 3 ||
                        (x == 20 && y < 28) || (y == 12 && x > 26);
      const bool inside = x > 2 && y > 2 && x < kCells - 3 && y < kCells - 3;
      pgm += static_cast<char>(wall ? 0 : inside ? 254 : 205);
    }
  }
  WriteFile(dir_ / "room.pgm", pgm);
  std::string maps;
  for (int k = 1; k <= 24; ++k) {  // one image, 24 origins: 24 different maps to the cache
    const fs::path path = dir_ / ("r" + std::to_string(k) + ".yaml");
    WriteFile(path, "image: room.pgm\nresolution: 0.05\norigin: [" + std::to_string(k) +
                        ", 0, 0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n");
    maps += " " + ShellQuote(path);
  }
  const fs::path cache = dir_ / "cache";
  const std::string merge = "merge --quiet --out " + ShellQuote(dir_ / "out") + " --cache " +
                            ShellQuote(cache) + " --cache-max-mb 1" + maps;
  const auto first = Fleetmerge(merge);
  ASSERT_EQ(first.exit_code, 0) << first.both();
  EXPECT_TRUE(Contains(first.out,
                       "pairs: 0 from the cache, 276 computed; maps' preparations: 0 from the "
                       "cache, 24 made\n"))
      << first.out;
  EXPECT_TRUE(Contains(first.err,
                       "fleetmerge: warning: job 'merge': the cache's size bound (1 MiB, "
                       "--cache-max-mb / cache_max_mb) is below this job's 300 entries, its "
                       "pairs and maps' preparations ("))
      << first.err;
  const json report = json::parse(ReadFile(dir_ / "out" / "report.json"));
  EXPECT_EQ(report["cache"]["bound_below_job"], true);
  EXPECT_EQ(report["cache"]["entries_in_use"], 300);  // 276 pairs, 24 maps' preparations
  EXPECT_EQ(report["cache"]["entries_evicted"], 0);
  // The re-run takes every pair and prepares no map: the maps' preparations are the older
  // entries the bound evicts, not the pairs it used.
  const auto again = Fleetmerge(merge);
  EXPECT_TRUE(Contains(again.out,
                       "pairs: 276 from the cache, 0 computed; 24 older cache entries evicted\n"))
      << again.out;
}

// `--cache ""` is an error naming the flag, not a silent way to turn the cache off (a job file's
// too).
TEST_F(MergeCacheCliTest, AnEmptyCacheNameIsAnError) {
  const auto run = Merge(dir_ / "out", "--cache ''");
  EXPECT_EQ(run.exit_code, 1) << run.both();
  EXPECT_TRUE(Contains(run.err, "--cache: empty folder name")) << run.err;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// A job waiting for the cache says so even with --quiet (a quiet cron job must not stall without
// a word), and names a map list's job shortly; --lock-wait bounds the wait for the cache too.
TEST_F(MergeCacheCliTest, AQuietJobStillSaysItWaitsForTheCache) {
  const fs::path cache = dir_ / "cache";
  fs::create_directories(cache);
  {
    FolderLock held(cache, "job 'test holder'", 0, "cache folder", {},
                    LockFilePlace::kInsideFolder);
    const auto run = Merge(dir_ / "out", "--lock-wait 0.5 --cache " + ShellQuote(cache));
    EXPECT_EQ(run.exit_code, 1) << run.both();
    EXPECT_TRUE(Contains(run.err, "merge: waiting up to 0.5 s for cache folder " + cache.string() +
                                      ", in use by job 'test holder' (pid "))
        << run.err;
    EXPECT_TRUE(Contains(run.err, "is in use by job 'test holder'")) << run.err;
  }
  EXPECT_TRUE(Contains(Fleetmerge("merge --help").out, "same output folder or cache folder"));
}

}  // namespace
}  // namespace fleetmerge
