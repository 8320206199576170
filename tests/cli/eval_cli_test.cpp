// `fleetmerge eval` end to end: a CutFleet case of the Intel lab map written as a case folder
// (`fleetmerge bench cut-fleet`: robot maps, truth.yaml, job.yaml), `fleetmerge merge job.yaml`,
// then `fleetmerge eval` on its report: every truly overlapping pair merged within the fine
// tolerance, as JSON and as a table. Bad input exits 1 naming the file (synthetic case).
// `fleetmerge bench sampling` writes its CSVs and plot.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "sim/cut_fleet_case.hpp"
#include "sim/synthetic_office.hpp"
#include "tests/support/fleetmerge_cli.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ShellQuote;

using testing::Fleetmerge;

// The Intel lab cut into 4 robots and merged, through the CLI, then evaluated three ways (one
// test, so that the case is cut and merged once).
TEST(EvalCliTest, MergedIntelCutFleetScoresEveryPairWithinTheFineTolerance) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path d = testing::MakeTempDir("eval_cli") / "intel";
  const auto cut =
      Fleetmerge("bench cut-fleet " + ShellQuote(*testing::SharedMapsDir() / "intel_lab.yaml") +
                 " " + ShellQuote(d) + " --robots 4 --seed 1");
  ASSERT_EQ(cut.exit_code, 0) << cut.both();
  const auto merge = Fleetmerge("merge --quiet " + ShellQuote(d / "job.yaml"));
  ASSERT_EQ(merge.exit_code, 0) << merge.both();
  const std::string files =
      ShellQuote(d / "merged" / "report.json") + " " + ShellQuote(d / "truth.yaml");

  auto eval = Fleetmerge("eval --json " + files);
  ASSERT_EQ(eval.exit_code, 0) << eval.both();
  const json result = json::parse(eval.out);
  const json& s = result["summary"];
  EXPECT_EQ(s["maps"], 4);
  EXPECT_EQ(s["scored_pairs"], 6);  // 2 x 2 tiles grown by 30 %: every pair overlaps
  EXPECT_EQ(s["merged_pairs"], 6);
  EXPECT_EQ(s["fine_pairs"], 6) << result.dump(2);
  EXPECT_EQ(s["false_merges"], 0);
  EXPECT_TRUE(s["missed_maps"].empty());
  EXPECT_LT(s["max_yaw_error_deg"].get<double>(), 0.25);
  for (const json& p : result["pairs"]) {
    EXPECT_TRUE(p["merged"].get<bool>());
    EXPECT_LT(p["translation_error_m"].get<double>(), 0.1) << p;
  }

  // The table.
  eval = Fleetmerge("eval " + files);
  ASSERT_EQ(eval.exit_code, 0) << eval.both();
  EXPECT_NE(eval.out.find("robot1 - robot2"), std::string::npos) << eval.out;
  EXPECT_NE(eval.out.find("success coarse (1.0 deg, 3.0 cells): 6/6 = 100.0 %"), std::string::npos)
      << eval.out;
  EXPECT_NE(eval.out.find("false merges: 0"), std::string::npos) << eval.out;
  EXPECT_NE(eval.out.find("missed maps: 0"), std::string::npos) << eval.out;

  // A minimum overlap above every pair's: nothing truly overlaps.
  eval = Fleetmerge("eval --json --min-overlap-cells 100000000 " + files);
  ASSERT_EQ(eval.exit_code, 0) << eval.both();
  EXPECT_EQ(json::parse(eval.out)["summary"]["scored_pairs"], 0);
}

TEST(EvalCliTest, BadInputExitsOneNamingTheFile) {
  const fs::path d = testing::MakeTempDir("eval_cli_bad") / "case";
  WriteCutFleetCase(GenerateOfficeFloor(OfficeOptions{}, 5), "office", "synthetic office 5", 2, 5,
                    d);
  // A valid report of the two maps, each alone.
  json report = {{"maps", json::array()}, {"components", json::array()}};
  for (int k = 0; k < 2; ++k) {
    const std::string name = "robot" + std::to_string(k + 1);
    report["maps"].push_back(
        {{"name", name}, {"component", k}, {"pose", {{"x", 0}, {"y", 0}, {"yaw", 0}}}});
    report["components"].push_back({{"id", k}, {"maps", {name}}});
  }
  std::ofstream(d / "report.json") << report.dump();
  auto eval = Fleetmerge("eval --json " + ShellQuote(d / "report.json") + " " +
                         ShellQuote(d / "truth.yaml"));
  ASSERT_EQ(eval.exit_code, 0) << eval.both();  // evaluated: nothing merged, both maps missed
  EXPECT_EQ(json::parse(eval.out)["summary"]["missed_maps"], json({"robot1", "robot2"}));

  eval = Fleetmerge("eval " + ShellQuote(d / "absent.json") + " " + ShellQuote(d / "truth.yaml"));
  EXPECT_EQ(eval.exit_code, 1);
  EXPECT_NE(eval.err.find("absent.json: cannot open report"), std::string::npos) << eval.err;

  // The truth names a map file that is not there.
  const fs::path bad = d / "bad_truth";
  fs::create_directories(bad);
  fs::copy_file(d / "truth.yaml", bad / "truth.yaml");
  eval = Fleetmerge("eval " + ShellQuote(d / "report.json") + " " + ShellQuote(bad / "truth.yaml"));
  EXPECT_EQ(eval.exit_code, 1);
  EXPECT_NE(eval.err.find((bad / "robot1.yaml").string()), std::string::npos) << eval.err;

  // The two files the wrong way round: the report read as the truth says so.
  eval = Fleetmerge("eval " + ShellQuote(d / "truth.yaml") + " " + ShellQuote(d / "report.json"));
  EXPECT_EQ(eval.exit_code, 1);
  EXPECT_NE(eval.err.find((d / "report.json").string() +
                          ": expected a truth file; this is a report.json of `fleetmerge merge` "
                          "(`fleetmerge eval REPORT TRUTH` takes the report first)"),
            std::string::npos)
      << eval.err;

  // The job file as the report: not JSON.
  eval = Fleetmerge("eval " + ShellQuote(d / "job.yaml") + " " + ShellQuote(d / "truth.yaml"));
  EXPECT_EQ(eval.exit_code, 1);
  EXPECT_NE(eval.err.find("job.yaml: malformed JSON"), std::string::npos) << eval.err;

  // A report of other maps.
  report["maps"][1]["name"] = "robot7";
  report["components"][1]["maps"][0] = "robot7";
  std::ofstream(d / "report.json") << report.dump();
  eval = Fleetmerge("eval " + ShellQuote(d / "report.json") + " " + ShellQuote(d / "truth.yaml"));
  EXPECT_EQ(eval.exit_code, 1);
  EXPECT_NE(eval.err.find("map 'robot2' of " + (d / "truth.yaml").string() + " is not in " +
                          (d / "report.json").string()),
            std::string::npos)
      << eval.err;
}

TEST(EvalCliTest, BenchSamplingWritesOneRowPerSettingAndTrialAndThePlot) {
  // A synthetic office cut into 4 robots: the bookkeeping only (pose accuracy is tested in
  // sampling_experiment_test on a real map).
  const fs::path d = testing::MakeTempDir("bench_sampling") / "case";
  WriteCutFleetCase(GenerateOfficeFloor(OfficeOptions{}, 5), "office", "synthetic office 5", 4, 5,
                    d);
  const auto bench = Fleetmerge("bench sampling --quiet --trials 2 --out " + ShellQuote(d / "out") +
                                " " + ShellQuote(d));
  ASSERT_EQ(bench.exit_code, 0) << bench.both();
  std::ifstream trials(d / "out" / "sampling_trials.csv");
  std::string line;
  std::getline(trials, line);
  EXPECT_EQ(line.rfind("setting,kept_fraction,trial,map_a,map_b,time_ms,best_omega,", 0), 0u);
  int rows = 0;
  while (std::getline(trials, line)) ++rows;
  EXPECT_EQ(rows, 40 * 2);
  std::ifstream summary(d / "out" / "sampling_summary.csv");
  rows = -1;  // the header
  while (std::getline(summary, line)) ++rows;
  EXPECT_EQ(rows, 40);
  const cv::Mat plot = cv::imread((d / "out" / "sampling.png").string());
  EXPECT_EQ(plot.cols, 960);
  EXPECT_GT(plot.rows, 600);
  EXPECT_NE(bench.out.find("every:20"), std::string::npos) << bench.out;

  // A case whose maps do not overlap enough: an error, exit 1.
  const auto none = Fleetmerge("bench sampling --quiet --trials 1 --min-overlap-cells 100000000 " +
                               ShellQuote(d));
  EXPECT_EQ(none.exit_code, 1);
  EXPECT_NE(none.err.find("no pair of maps overlaps by at least 100000000 cells"),
            std::string::npos)
      << none.err;
}

}  // namespace
}  // namespace fleetmerge
