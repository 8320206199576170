// `fleetmerge simulate` through the executable: the case it writes merges with `fleetmerge
// merge` (all robots of the building in one component, the foreign one alone), a case with a
// fixed base is evaluated against it, neither `simulate` nor `bench cut-fleet` writes over the
// building map, and bad options or an unreadable building map fail with a message.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/files.hpp"
#include "tests/support/fleetmerge_cli.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using testing::ShellQuote;

using testing::Fleetmerge;

std::map<std::string, int> ComponentOfEachMap(const fs::path& report_json) {
  std::ifstream in(report_json);
  const nlohmann::json report = nlohmann::json::parse(in);
  std::map<std::string, int> component;
  for (const auto& m : report.at("maps")) component[m.at("name")] = m.at("component").get<int>();
  return component;
}

// The default case: its job runs and puts all four robots into one component.
TEST(SimulateCli, DefaultCaseMerges) {
  const fs::path dir = testing::MakeTempDir("simulate_cli");
  const auto run = Fleetmerge("simulate " + ShellQuote(dir));
  ASSERT_EQ(run.exit_code, 0) << run.both();
  EXPECT_NE(run.out.find("truth.yaml"), std::string::npos) << run.out;
  for (const char* f : {"robot1.yaml", "robot1.pgm", "robot4.pgm", "truth.yaml", "job.yaml"}) {
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  }
  const auto merge = Fleetmerge("merge --quiet " + ShellQuote(dir / "job.yaml"));
  ASSERT_EQ(merge.exit_code, 0) << merge.both();
  const auto component = ComponentOfEachMap(dir / "merged" / "report.json");
  ASSERT_EQ(component.size(), 4u);
  for (const char* robot : {"robot2", "robot3", "robot4"}) {
    EXPECT_EQ(component.at(robot), component.at("robot1")) << robot;
  }
}

TEST(SimulateCli, ResolutionsForeignBuildingAndLittleOverlap) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path dir = testing::MakeTempDir("simulate_cli_options");
  const fs::path intel = *testing::SharedMapsDir() / "intel_lab.yaml";
  const auto run = Fleetmerge("simulate " + ShellQuote(dir) + " --robots 3 --seed 4 --foreign " +
                              ShellQuote(intel) + " --resolutions 0.05,0.05,0.1,0.05 " +
                              "--little-overlap --path-length 20 --beams 180 --range 6");
  ASSERT_EQ(run.exit_code, 0) << run.both();
  EXPECT_EQ(YAML::LoadFile((dir / "robot3.yaml").string())["resolution"].as<double>(), 0.1);
  const YAML::Node truth = YAML::LoadFile((dir / "truth.yaml").string());
  ASSERT_EQ(truth["maps"].size(), 4u);
  EXPECT_EQ(truth["maps"][3]["name"].as<std::string>(), "robot4");
  EXPECT_EQ(truth["maps"][3]["building"].as<std::string>(), "foreign");
  EXPECT_EQ(truth["buildings"][1]["source"].as<std::string>(), intel.string());
  EXPECT_EQ(truth["overlaps"].size(), 3u);
}

// `simulate --fixed-base`, merged and evaluated: the base stays at the identity (placed_by
// "fixed") and `eval` scores every robot against it, all within the coarse tolerance.
TEST(SimulateCli, AFixedBaseCaseIsEvaluatedAgainstTheBase) {
  const fs::path dir = testing::MakeTempDir("simulate_cli_base");
  const auto run = Fleetmerge("simulate " + ShellQuote(dir) + " --robots 3 --seed 2 --fixed-base");
  ASSERT_EQ(run.exit_code, 0) << run.both();
  EXPECT_NE(run.out.find("base.yaml: building office, its own map"), std::string::npos) << run.out;
  const auto merge = Fleetmerge("merge --quiet " + ShellQuote(dir / "job.yaml"));
  ASSERT_EQ(merge.exit_code, 0) << merge.both();
  std::ifstream in(dir / "merged" / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_EQ(report.at("maps").size(), 4u);
  const nlohmann::json& base = report.at("maps").at(0);
  EXPECT_EQ(base.at("name"), "base");
  EXPECT_EQ(base.at("placed_by"), "fixed");
  for (const char* key : {"x", "y", "yaw"}) EXPECT_EQ(base.at("pose").at(key), 0.0) << key;

  const auto eval = Fleetmerge("eval --json " + ShellQuote(dir / "merged" / "report.json") + " " +
                               ShellQuote(dir / "truth.yaml"));
  ASSERT_EQ(eval.exit_code, 0) << eval.both();
  const nlohmann::json result = nlohmann::json::parse(eval.out);
  int base_pairs = 0;
  for (const nlohmann::json& p : result.at("pairs")) {
    if (p.at("a") != "base") continue;
    ++base_pairs;
    EXPECT_TRUE(p.at("scored").get<bool>()) << p;
    EXPECT_TRUE(p.at("coarse").get<bool>()) << p;
  }
  EXPECT_EQ(base_pairs, 3);
  EXPECT_EQ(result.at("summary").at("coarse_pairs"), result.at("summary").at("scored_pairs"));
  EXPECT_EQ(result.at("summary").at("false_merges"), 0);
}

// `simulate --priors`, merged and evaluated: the known start poses put the merged frame on the
// building's, and every pair is within the coarse tolerance. Each robot's reported pose is its
// true pose moved by one rigid error common to all, the priors' consensus: its yaw within their
// 5 deg, its shift at a frame origin within their 0.3 m plus that yaw over the frames' spread
// (up to 20 m per axis), so under 2 m. Without priors the first robot would sit at the identity.
TEST(SimulateCli, PriorsPutTheMergedFrameOnTheBuildings) {
  const fs::path dir = testing::MakeTempDir("simulate_cli_priors");
  const auto run =
      Fleetmerge("simulate " + ShellQuote(dir) + " --robots 3 --seed 2 --priors 0.3,5");
  ASSERT_EQ(run.exit_code, 0) << run.both();
  EXPECT_NE(run.out.find("; initial_pose x "), std::string::npos) << run.out;
  const auto merge = Fleetmerge("merge --quiet " + ShellQuote(dir / "job.yaml"));
  ASSERT_EQ(merge.exit_code, 0) << merge.both();
  std::ifstream in(dir / "merged" / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  const YAML::Node truth = YAML::LoadFile((dir / "truth.yaml").string());
  ASSERT_EQ(report.at("maps").size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const nlohmann::json& map = report.at("maps").at(k);
    const YAML::Node pose = truth["maps"][k]["pose"];
    ASSERT_EQ(map.at("name"), truth["maps"][k]["name"].as<std::string>());
    const double dx = map.at("pose").at("x").get<double>() - pose["x"].as<double>();
    const double dy = map.at("pose").at("y").get<double>() - pose["y"].as<double>();
    const double dyaw = std::remainder(
        map.at("pose").at("yaw").get<double>() - pose["yaw"].as<double>(), 2.0 * M_PI);
    EXPECT_LT(std::hypot(dx, dy), 2.0) << map;
    EXPECT_LT(std::abs(dyaw), 5.5 * M_PI / 180.0) << map;
  }
  const auto eval = Fleetmerge("eval --json " + ShellQuote(dir / "merged" / "report.json") + " " +
                               ShellQuote(dir / "truth.yaml"));
  ASSERT_EQ(eval.exit_code, 0) << eval.both();
  const nlohmann::json result = nlohmann::json::parse(eval.out);
  EXPECT_GT(result.at("summary").at("scored_pairs").get<int>(), 0);
  EXPECT_EQ(result.at("summary").at("coarse_pairs"), result.at("summary").at("scored_pairs"));
  EXPECT_EQ(result.at("summary").at("false_merges"), 0);
}

// A building map kept in the case folder, whose image has the name of a file the case writes
// (the base's, or a robot's): `simulate` and `bench cut-fleet` refuse before writing anything,
// and the image is intact.
TEST(SimulateCli, CaseCommandsNeverOverwriteTheBuildingsImage) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path intel = *testing::SharedMapsDir() / "intel_lab.pgm";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"base.pgm", "simulate {dir} --building {yaml} --fixed-base --robots 2 --path-length 10"},
      {"robot1.pgm", "simulate {dir} --building {yaml} --robots 2 --path-length 10"},
      {"robot2.pgm", "bench cut-fleet {yaml} {dir} --robots 2 --seed 1"}};
  for (const auto& [image, command] : cases) {
    const fs::path dir = testing::MakeTempDir("case_commands_image");
    fs::copy_file(intel, dir / image);
    testing::WriteFile(dir / "site.yaml", "image: " + image +
                                              "\nresolution: 0.05\norigin: [0.0, 0.0, 0.0]\n"
                                              "negate: 0\noccupied_thresh: 0.65\n"
                                              "free_thresh: 0.196\n");
    std::string args = command;
    args.replace(args.find("{dir}"), 5, ShellQuote(dir));
    args.replace(args.find("{yaml}"), 6, ShellQuote(dir / "site.yaml"));
    const auto run = Fleetmerge(args);
    EXPECT_NE(run.exit_code, 0) << command;
    EXPECT_NE(run.err.find("refusing to overwrite input file"), std::string::npos) << run.both();
    EXPECT_NE(run.err.find(image), std::string::npos) << run.both();
    EXPECT_FALSE(fs::exists(dir / "job.yaml")) << command;
    EXPECT_FALSE(fs::exists(dir / "truth.yaml")) << command;
    EXPECT_TRUE(testing::ReadFile(dir / image) == testing::ReadFile(intel)) << command;
  }
}

TEST(SimulateCli, BadInputFailsWithAMessage) {
  const fs::path dir = testing::MakeTempDir("simulate_cli_bad");
  const auto missing = Fleetmerge("simulate " + ShellQuote(dir / "out") + " --building " +
                                  ShellQuote(dir / "nowhere.yaml"));
  EXPECT_EQ(missing.exit_code, 1) << missing.both();
  EXPECT_NE(missing.err.find("nowhere.yaml"), std::string::npos) << missing.err;
  EXPECT_FALSE(fs::exists(dir / "out" / "job.yaml"));

  const auto resolutions =
      Fleetmerge("simulate " + ShellQuote(dir / "out") + " --robots 3 --resolutions 0.05,0.1");
  EXPECT_EQ(resolutions.exit_code, 1) << resolutions.both();
  EXPECT_NE(resolutions.err.find("resolutions"), std::string::npos) << resolutions.err;

  const auto same_office =
      Fleetmerge("simulate " + ShellQuote(dir / "out") + " --seed 3 --foreign-office-seed 3");
  EXPECT_EQ(same_office.exit_code, 1) << same_office.both();

  for (const char* bad : {"--robots 0", "--range -1", "--beams abc", "--resolutions 0",
                          "--building a.yaml --office-seed 2"}) {
    const auto run = Fleetmerge("simulate " + ShellQuote(dir / "out") + " " + bad);
    EXPECT_NE(run.exit_code, 0) << bad;
    EXPECT_FALSE(run.err.empty()) << bad;
  }
  EXPECT_FALSE(fs::exists(dir / "out" / "job.yaml"));
}

}  // namespace
}  // namespace fleetmerge
