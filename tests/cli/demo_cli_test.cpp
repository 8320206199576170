// `fleetmerge demo` end to end: it writes a simulated case, merges and evaluates it, and every
// output it lists exists and loads; the default seed's evaluation merges every truly overlapping
// pair within the coarse tolerance with no false merge (the demo's own judgement is checked
// against evaluation.json, not trusted). A rerun replaces the previous demo's case and leaves the
// user's files in DIR alone; a DIR/case holding anything else is refused and left untouched.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>

#include "io/map_io.hpp"
#include "io/truth_file.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ShellQuote;

testing::CommandResult Demo(const fs::path& out_dir) {
  return testing::RunCommand(std::string(FLEETMERGE_EXECUTABLE) + " demo --out " +
                             ShellQuote(out_dir));
}

// The "  label: path" lines after "outputs:" (a label may repeat per merged component; the
// default case has one).
std::map<std::string, fs::path> ListedOutputs(const std::string& out) {
  std::map<std::string, fs::path> listed;
  std::istringstream lines(out.substr(out.find("\noutputs:\n") + 1));
  std::string line;
  std::getline(lines, line);  // "outputs:"
  while (std::getline(lines, line) && line.rfind("  ", 0) == 0) {
    const auto colon = line.find(": ");
    if (colon != std::string::npos) listed[line.substr(2, colon - 2)] = line.substr(colon + 2);
  }
  return listed;
}

json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  return json::parse(in);  // throws (fails the test) on bad JSON
}

std::string ReadText(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

void ExpectDemoOutputsValid(const testing::CommandResult& run, const fs::path& dir) {
  ASSERT_EQ(run.exit_code, 0) << run.both();
  ASSERT_NE(run.out.find("\noutputs:\n"), std::string::npos) << run.out;
  const auto listed = ListedOutputs(run.out);
  for (const char* label : {"merged map YAML", "merged map PGM", "preview PNG", "report",
                            "report page", "evaluation", "truth"}) {
    ASSERT_EQ(listed.count(label), 1u) << label << " not listed:\n" << run.out;
    EXPECT_TRUE(fs::is_regular_file(listed.at(label))) << listed.at(label);
  }
  EXPECT_EQ(listed.at("evaluation"), dir / "evaluation.json");
  EXPECT_EQ(listed.at("truth"), dir / "case" / "truth.yaml");
  EXPECT_EQ(listed.at("report"), dir / "case" / "merged" / "report.json");
  EXPECT_EQ(listed.at("report page"), dir / "case" / "merged" / "report.html");

  const LoadedMap merged = LoadMap(listed.at("merged map YAML"));
  EXPECT_EQ(merged.metadata.image_path, listed.at("merged map PGM"));
  EXPECT_GT(merged.grid.width(), 0);
  EXPECT_FALSE(cv::imread(listed.at("preview PNG").string()).empty());
  const json report = ReadJson(listed.at("report"));
  EXPECT_EQ(report["maps"].size(), 4u);
  const GroundTruth truth = LoadTruth(listed.at("truth"));
  EXPECT_EQ(truth.maps.size(), 4u);

  // evaluation.json is `eval --json` of the merge: recount the summary from its pairs.
  const json evaluation = ReadJson(listed.at("evaluation"));
  EXPECT_EQ(fs::path(evaluation["report"].get<std::string>()), listed.at("report"));
  int scored = 0, coarse = 0;
  for (const json& p : evaluation["pairs"]) {
    if (!p["scored"].get<bool>()) continue;
    ++scored;
    EXPECT_TRUE(p["merged"].get<bool>()) << p;
    EXPECT_TRUE(p["coarse"].get<bool>()) << p;
    coarse += p["coarse"].get<bool>();
  }
  const json& s = evaluation["summary"];
  EXPECT_GE(scored, 3) << "4 robots in one office: at least a spanning tree of pairs overlaps";
  EXPECT_EQ(s["scored_pairs"], scored);
  EXPECT_EQ(s["coarse_pairs"], coarse);
  EXPECT_EQ(s["false_merges"], 0);
  EXPECT_TRUE(evaluation["false_merges"].empty());
  EXPECT_TRUE(s["missed_maps"].empty());
  EXPECT_NE(run.out.find("evaluation: OK"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("success coarse (1.0 deg, 3.0 cells): " + std::to_string(scored) + "/" +
                         std::to_string(scored)),
            std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("total time"), std::string::npos) << run.out;
}

TEST(DemoCliTest, RunsMergesEveryOverlappingPairAndRerunsOverItsOwnFolder) {
  const fs::path dir = testing::MakeTempDir("demo_cli") / "demo";
  const auto first = Demo(dir);
  ExpectDemoOutputsValid(first, dir);
  const json first_evaluation = ReadJson(dir / "evaluation.json");

  // A file of the user's beside the case, and a stale file inside the previous case.
  std::ofstream(dir / "notes.txt") << "mine\n";
  std::ofstream(dir / "case" / "stale.txt") << "from an earlier demo\n";
  const auto second = Demo(dir);
  ExpectDemoOutputsValid(second, dir);
  EXPECT_EQ(ReadText(dir / "notes.txt"), "mine\n");
  EXPECT_FALSE(fs::exists(dir / "case" / "stale.txt")) << "the case is recreated, not added to";
  EXPECT_EQ(ReadJson(dir / "evaluation.json"), first_evaluation) << "the demo is deterministic";
}

TEST(DemoCliTest, RefusesACaseFolderThatIsNotADemosAndLeavesItUntouched) {
  const fs::path dir = testing::MakeTempDir("demo_cli_refuse") / "demo";
  fs::create_directories(dir / "case");
  std::ofstream(dir / "case" / "thesis.tex") << "do not delete\n";
  const auto run = Demo(dir);
  EXPECT_NE(run.exit_code, 0) << run.both();
  EXPECT_NE(run.err.find((dir / "case").string()), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("refusing to delete it"), std::string::npos) << run.err;
  EXPECT_EQ(ReadText(dir / "case" / "thesis.tex"), "do not delete\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir / "case"), fs::directory_iterator()), 1);
  EXPECT_FALSE(fs::exists(dir / "evaluation.json"));

  // An evaluation.json with no demo case beside it is not overwritten either.
  const fs::path other = testing::MakeTempDir("demo_cli_refuse_eval");
  std::ofstream(other / "evaluation.json") << "{\"mine\": true}\n";
  const auto run_eval = Demo(other);
  EXPECT_NE(run_eval.exit_code, 0) << run_eval.both();
  EXPECT_NE(run_eval.err.find("refusing to overwrite"), std::string::npos) << run_eval.err;
  EXPECT_EQ(ReadText(other / "evaluation.json"), "{\"mine\": true}\n");
  EXPECT_FALSE(fs::exists(other / "case"));
}

}  // namespace
}  // namespace fleetmerge
