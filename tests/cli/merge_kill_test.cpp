// `fleetmerge merge` killed with SIGKILL at random moments: the output folder must always hold
// either no result set or one complete, loadable set (manifest, report.json that parses, every
// merged map loads), an old complete set must survive a killed rerun unchanged, and what killed
// runs leave beside the folder must not break the next run. Seeded: the kill delays are
// reproducible; about 25 runs of a two-map job (~5-10 s on this 2-core machine). Also runs
// writing one folder at once (they take turns under the folder's lock, io/folder_lock.hpp) and a
// run killed while holding that lock (~7 s more).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "io/folder_lock.hpp"
#include "io/map_io.hpp"
#include "io/result_folder.hpp"
#include "tests/support/files.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using testing::ReadFile;

// Starts `fleetmerge args...` with its output discarded (stderr to `err_file` if given); returns
// its pid.
pid_t Start(const std::vector<std::string>& args, const fs::path& err_file = {}) {
  std::vector<char*> argv;
  std::string exe = FLEETMERGE_EXECUTABLE;
  argv.push_back(exe.data());
  std::vector<std::string> copy = args;
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    freopen("/dev/null", "w", stdout);
    freopen(err_file.empty() ? "/dev/null" : err_file.c_str(), "w", stderr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

int Wait(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

// The folder's files (subfolders' too: merged_bag/metadata.yaml) and their bytes.
std::map<std::string, std::string> Snapshot(const fs::path& folder) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.is_directory()) continue;
    files[entry.path().lexically_relative(folder).generic_string()] = ReadFile(entry.path());
  }
  return files;
}

// A complete result set: exactly the manifest's files, report.json parses and names merged maps
// that load.
void ExpectCompleteSet(const fs::path& out, const std::string& when) {
  SCOPED_TRACE(when);
  ResultManifest manifest;
  ASSERT_NO_THROW(manifest = ReadResultManifest(out));
  std::set<std::string> expected(manifest.files.begin(), manifest.files.end());
  EXPECT_EQ(expected.count("report.html"), 1u) << "the page is part of every set";
  expected.insert(kManifestName);
  std::set<std::string> present;
  for (const auto& [file, bytes] : Snapshot(out)) present.insert(file);
  EXPECT_EQ(present, expected);
  nlohmann::json report;
  ASSERT_NO_THROW(report = nlohmann::json::parse(ReadFile(out / "report.json")));
  for (const auto& component : report.at("components")) {
    if (!component.contains("merged_map")) continue;
    const fs::path yaml = out / component["merged_map"].get<std::string>();
    EXPECT_NO_THROW(LoadMap(yaml)) << yaml;
  }
}

class MergeKillTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::MakeTempDir("merge_kill");
    ASSERT_EQ(Wait(Start({"example", (dir_ / "maps").string()})), 0);
    out_ = dir_ / "out";
  }
  // `--omega-threshold 1.01` is refused by the CLI, 1.0 merges nothing: an old set that differs
  // from the new one (report only, no merged map) for the same job.
  std::vector<std::string> Args(bool merge_nothing) const {
    std::vector<std::string> args = {"merge", "--quiet", "--threads", "1", "--out", out_.string()};
    if (merge_nothing) args.insert(args.end(), {"--omega-threshold", "1.0"});
    args.push_back((dir_ / "maps" / "robot_a.yaml").string());
    args.push_back((dir_ / "maps" / "robot_b.yaml").string());
    return args;
  }
  // Runs to completion; the run's wall time.
  double FullRun(bool merge_nothing) {
    const auto start = Clock::now();
    EXPECT_EQ(Wait(Start(Args(merge_nothing))), 0);
    return std::chrono::duration<double>(Clock::now() - start).count();
  }
  // The entries beside the output folder that runs leave (staging, set-aside sets, the lock).
  std::vector<std::string> Leftovers() const {
    std::vector<std::string> left;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string name = e.path().filename().string();
      if (name.find(".out.fleetmerge-") != std::string::npos) left.push_back(name);
    }
    return left;
  }
  // Starts a run and kills it after a random share of `duration_s` (up to 1.5 times it).
  void KillRun(bool merge_nothing, double duration_s, std::mt19937& random) {
    std::uniform_real_distribution<double> delay_s(0.0, 1.5 * duration_s);
    const pid_t pid = Start(Args(merge_nothing));
    std::this_thread::sleep_for(std::chrono::duration<double>(delay_s(random)));
    kill(pid, SIGKILL);
    Wait(pid);
  }
  fs::path dir_, out_;
};

TEST_F(MergeKillTest, OutputIsNoneOrCompleteAndOldResultsSurvive) {
  std::mt19937 random(20261123);
  const double duration_s = FullRun(false);
  fs::remove_all(out_);
  int complete = 0, none = 0, old_kept = 0, replaced = 0;
  // A fresh folder: nothing, or a complete set.
  for (int k = 0; k < 8; ++k) {
    fs::remove_all(out_);
    KillRun(false, duration_s, random);
    if (!fs::exists(out_)) {
      ++none;
      continue;
    }
    ExpectCompleteSet(out_, "fresh, kill " + std::to_string(k));
    ++complete;
  }
  // An old complete set (nothing merged) under killed reruns that would merge.
  FullRun(true);
  std::map<std::string, std::string> old_set = Snapshot(out_);
  ASSERT_EQ(old_set.count("merged_0.yaml"), 0u);
  for (int k = 0; k < 12; ++k) {
    KillRun(false, duration_s, random);
    ASSERT_TRUE(fs::exists(out_)) << "the old set vanished, kill " << k;
    ExpectCompleteSet(out_, "rerun, kill " + std::to_string(k));
    if (Snapshot(out_) == old_set) {
      ++old_kept;
    } else {
      EXPECT_TRUE(fs::exists(out_ / "merged_0.yaml")) << "neither the old nor the new set";
      ++replaced;
      FullRun(true);  // back to an old set (new timings in its report) for the next kill
      old_set = Snapshot(out_);
    }
  }
  // Leftovers of killed runs do not break the next run, which removes them.
  FullRun(false);
  ExpectCompleteSet(out_, "final run");
  EXPECT_EQ(Leftovers(), std::vector<std::string>{});
  std::cout << "[ kills    ] run " << duration_s * 1e3 << " ms; fresh folder: " << none << " none, "
            << complete << " complete; old set: " << old_kept << " kept, " << replaced
            << " replaced by the complete new set\n";
}

// The lock's tests are their own suite: scripts/test_sanitizers.sh skips MergeKillTest.* (kills
// at other moments), not these.
class MergeLockTest : public MergeKillTest {};

// Issue 22's daily jobs: several `merge --force` runs into one output folder at once. Each takes
// the folder's lock (io/folder_lock.hpp) before touching anything beside it, so they take turns:
// all succeed, one complete set is left and nothing beside it.
TEST_F(MergeLockTest, ConcurrentForcedRunsIntoOneFolderTakeTurns) {
  constexpr int kRuns = 4;
  std::vector<std::string> args = Args(false);
  args.insert(args.begin() + 1, "--force");
  // Started at once, as cron starts them.
  std::vector<pid_t> pids;
  for (int r = 0; r < kRuns; ++r) pids.push_back(Start(args));
  for (pid_t pid : pids) EXPECT_EQ(Wait(pid), 0);
  ExpectCompleteSet(out_, "after runs started at once");
  EXPECT_EQ(Leftovers(), std::vector<std::string>{});

  // Made to contend: the test holds the lock until every run is waiting for it, then releases
  // it and they all race for it.
  args.erase(std::find(args.begin(), args.end(), "--quiet"));  // the waiting notice is shown
  std::optional<FolderLock> held(std::in_place, out_, "job 'test holder'", 0);
  pids.clear();
  for (int r = 0; r < kRuns; ++r) {
    pids.push_back(Start(args, dir_ / ("err" + std::to_string(r) + ".txt")));
  }
  int waiting = 0;
  for (const auto start = Clock::now(); Clock::now() - start < std::chrono::seconds(60);) {
    waiting = 0;
    for (int r = 0; r < kRuns; ++r) {
      const std::string err = ReadFile(dir_ / ("err" + std::to_string(r) + ".txt"));
      waiting += err.find("merge: waiting up to 300 s for output folder " + out_.string() +
                          ", in use by job 'test holder' (pid " + std::to_string(getpid())) !=
                 std::string::npos;
    }
    if (waiting == kRuns) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_EQ(waiting, kRuns) << "every run says it waits, and for whom";
  held.reset();
  for (pid_t pid : pids) EXPECT_EQ(Wait(pid), 0);
  ExpectCompleteSet(out_, "after contending runs");
  EXPECT_EQ(Leftovers(), std::vector<std::string>{});
}

// With --lock-wait 0 a run finding the folder in use fails at once, naming the folder and the
// job holding it, and touches nothing.
TEST_F(MergeLockTest, LockWaitZeroFailsAtOnceNamingTheHolder) {
  FullRun(false);
  const std::map<std::string, std::string> old_set = Snapshot(out_);
  std::vector<std::string> args = Args(false);
  args.insert(args.begin() + 1, {"--force", "--lock-wait", "0"});
  {
    FolderLock held(out_, "job 'test holder'", 0);
    std::vector<pid_t> pids;
    const auto start = Clock::now();
    for (int r = 0; r < 4; ++r) {
      pids.push_back(Start(args, dir_ / ("err" + std::to_string(r) + ".txt")));
    }
    for (pid_t pid : pids) EXPECT_EQ(Wait(pid), 1);
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    EXPECT_LT(seconds, 30.0) << "no waiting (the runs still load their maps first)";
    for (int r = 0; r < 4; ++r) {
      const std::string err = ReadFile(dir_ / ("err" + std::to_string(r) + ".txt"));
      EXPECT_NE(
          err.find("fleetmerge: job 'merge' failed: output folder " + out_.string() +
                   " is in use by job 'test holder' (pid " + std::to_string(getpid()) + " on "),
          std::string::npos)
          << err;
      EXPECT_NE(err.find("1 of 1 job(s) failed"), std::string::npos) << err;
    }
    EXPECT_EQ(Snapshot(out_), old_set);
  }
  // Runs started at once with --lock-wait 0: one wins (or several, one after the other); the
  // others fail naming the winner; the folder holds one complete set.
  std::vector<pid_t> pids;
  for (int r = 0; r < 4; ++r) {
    pids.push_back(Start(args, dir_ / ("race" + std::to_string(r) + ".txt")));
  }
  int succeeded = 0;
  for (int r = 0; r < 4; ++r) {
    const int code = Wait(pids[r]);
    succeeded += code == 0;
    if (code == 0) continue;
    EXPECT_EQ(code, 1);
    const std::string err = ReadFile(dir_ / ("race" + std::to_string(r) + ".txt"));
    // A map list's job is named by its first map and how many more, not by every map.
    EXPECT_NE(err.find("output folder " + out_.string() + " is in use by job 'merge' of " +
                       fs::weakly_canonical(dir_ / "maps" / "robot_a.yaml").string() +
                       " and 1 more map (pid "),
              std::string::npos)
        << err;
  }
  EXPECT_GE(succeeded, 1);
  std::cout << "[ race     ] --lock-wait 0, 4 runs at once: " << succeeded << " succeeded\n";
  ExpectCompleteSet(out_, "after the race");
  EXPECT_EQ(Leftovers(), std::vector<std::string>{});
}

// A run killed with SIGKILL while it holds the folder's lock (mid-merge) leaves its lock file,
// which does not block the next run, even with --lock-wait 0.
TEST_F(MergeLockTest, RunKilledHoldingTheLockDoesNotBlock) {
  const fs::path lock_file = FolderLockPath(out_);
  bool killed_holding = false;
  for (int attempt = 0; attempt < 10 && !killed_holding; ++attempt) {
    fs::remove_all(out_);
    const pid_t pid = Start(Args(false));
    for (const auto start = Clock::now(); Clock::now() - start < std::chrono::seconds(30);) {
      const std::optional<FolderLockHolder> holder = ParseFolderLockFile(ReadFile(lock_file));
      if (holder && holder->pid == pid) {
        kill(pid, SIGKILL);
        killed_holding = true;  // unless it released the lock just before the kill (below)
        break;
      }
      if (waitpid(pid, nullptr, WNOHANG) == pid) break;  // finished before we saw its lock
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    Wait(pid);
    killed_holding = killed_holding && fs::exists(lock_file);  // SIGKILL leaves the file
  }
  ASSERT_TRUE(killed_holding) << "no run was caught holding its lock";
  std::vector<std::string> args = Args(false);
  args.insert(args.begin() + 1, {"--lock-wait", "0"});
  EXPECT_EQ(Wait(Start(args)), 0);
  ExpectCompleteSet(out_, "after the killed holder");
  EXPECT_EQ(Leftovers(), std::vector<std::string>{});
}

}  // namespace
}  // namespace fleetmerge
