// `fleetmerge merge` killed with SIGKILL at random moments: the output folder must always hold
// either no result set or one complete, loadable set (manifest, report.json that parses, every
// merged map loads), an old complete set must survive a killed rerun unchanged, and what killed
// runs leave beside the folder must not break the next run. Seeded: the kill delays are
// reproducible; about 25 runs of a two-map job (~5-10 s on this 2-core machine).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <string>
#include <thread>

#include "io/map_io.hpp"
#include "io/result_folder.hpp"
#include "tests/support/files.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using testing::ReadFile;

// Starts `fleetmerge args...` with its output discarded; returns its pid.
pid_t Start(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  std::string exe = FLEETMERGE_EXECUTABLE;
  argv.push_back(exe.data());
  std::vector<std::string> copy = args;
  for (std::string& a : copy) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    freopen("/dev/null", "w", stdout);
    freopen("/dev/null", "w", stderr);
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
  for (const auto& e : fs::directory_iterator(dir_)) {
    EXPECT_EQ(e.path().filename().string().find(".out.fleetmerge-"), std::string::npos)
        << "left over: " << e.path();
  }
  std::cout << "[ kills    ] run " << duration_s * 1e3 << " ms; fresh folder: " << none << " none, "
            << complete << " complete; old set: " << old_kept << " kept, " << replaced
            << " replaced by the complete new set\n";
}

}  // namespace
}  // namespace fleetmerge
