// `fleetmerge merge` end to end, through the executable: report.json's documented names and
// poses against the ground truth of `fleetmerge example`, a failing job that does not stop the
// next one, job-file validation before any work, a map of another building left unmerged, the
// reference and progress options, and outputs that never replace an input.
//
// Maps: `fleetmerge example --seed 1` (two robots in one synthetic building, with truth.yaml)
// and `--seed 2`'s robot_a, a map of a different building; the real corridor runs and Intel lab
// from ../shared where present.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/pose2.hpp"
#include "io/map_io.hpp"
#include "job/pose_prior.hpp"
#include "tests/support/files.hpp"
#include "tests/support/fleetmerge_cli.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::ShellQuote;

constexpr double kTranslationTolerance_m = 0.05;
constexpr double kYawTolerance_rad = 0.25 * M_PI / 180.0;

using testing::Fleetmerge;
using testing::ReadFile;
using testing::WriteFile;

json ReadJson(const fs::path& path) { return json::parse(ReadFile(path)); }

std::set<std::string> FilesIn(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

// Progress lines on a stderr that is not a terminal: "<job>: <stage> <done>/<total>".
std::vector<std::string> ProgressLines(const std::string& err, const std::string& stage) {
  const std::regex line_format("^[^:]+: " + stage +
                               " [0-9]+/[0-9]+( \\(about [0-9.]+ s left\\))?$");
  std::vector<std::string> lines;
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);) {
    if (std::regex_match(line, line_format)) lines.push_back(line);
  }
  return lines;
}

Pose2 PoseOf(const json& pose) {
  return Pose2(pose.at("x").get<double>(), pose.at("y").get<double>(),
               pose.at("yaw").get<double>());
}

void ExpectNear(const Pose2& actual, const Pose2& expected, const std::string& what) {
  EXPECT_NEAR(actual.x_m(), expected.x_m(), kTranslationTolerance_m) << what;
  EXPECT_NEAR(actual.y_m(), expected.y_m(), kTranslationTolerance_m) << what;
  EXPECT_NEAR(std::remainder(actual.yaw_rad() - expected.yaw_rad(), 2 * M_PI), 0.0,
              kYawTolerance_rad)
      << what;
}

using IsType = bool (json::*)() const noexcept;
constexpr IsType kArray = &json::is_array, kObject = &json::is_object, kString = &json::is_string,
                 kNumber = &json::is_number, kIndex = &json::is_number_unsigned,
                 kBool = &json::is_boolean;

// `object` is a JSON object holding each of `fields` with its type.
void ExpectFields(const json& object, const std::vector<std::pair<std::string, IsType>>& fields,
                  const std::string& where) {
  ASSERT_TRUE(object.is_object()) << where << ": " << object;
  for (const auto& [name, is_type] : fields) {
    EXPECT_TRUE(object.contains(name) && (object[name].*is_type)())
        << where << "." << name << " in " << object;
  }
}

// The names pipeline/report_json.hpp fixes, with their JSON types (it allows added fields).
void ExpectDocumentedNames(const json& report) {
  ExpectFields(
      report, {{"maps", kArray}, {"components", kArray}, {"pairs", kArray}, {"timing_ms", kObject}},
      "report");
  for (const json& map : report.value("maps", json::array())) {
    ExpectFields(map, {{"name", kString}, {"source", kString}, {"component", kIndex}}, "maps[]");
    ExpectFields(map.value("pose", json()), {{"x", kNumber}, {"y", kNumber}, {"yaw", kNumber}},
                 "maps[].pose");
  }
  for (const json& component : report.value("components", json::array())) {
    ExpectFields(component, {{"id", kIndex}, {"maps", kArray}}, "components[]");
    for (const json& name : component.value("maps", json::array())) EXPECT_TRUE(name.is_string());
    if (component.contains("merged_map")) {
      EXPECT_TRUE(component["merged_map"].is_string()) << component;
    }
  }
  for (const json& pair : report.value("pairs", json::array())) {
    ExpectFields(pair,
                 {{"a", kString},
                  {"b", kString},
                  {"omega", kNumber},
                  {"accepted", kBool},
                  {"overlap_cells", kNumber},
                  {"wall_agreement", kNumber},
                  {"ambiguous", kBool},
                  {"hypotheses", kArray}},
                 "pairs[]");
    // The margin is null when the pair has no runner-up.
    ASSERT_TRUE(pair.contains("margin"));
    EXPECT_TRUE(pair["margin"].is_number() || pair["margin"].is_null()) << pair["margin"];
    for (const json& h : pair.value("hypotheses", json::array())) {
      ExpectFields(h,
                   {{"x", kNumber},
                    {"y", kNumber},
                    {"yaw", kNumber},
                    {"omega", kNumber},
                    {"overlap_cells", kNumber},
                    {"wall_agreement", kNumber}},
                   "pairs[].hypotheses[]");
    }
  }
  ExpectFields(report.value("timing_ms", json()),
               {{"load", kNumber},
                {"pairs", kNumber},
                {"refine", kNumber},
                {"composite", kNumber},
                {"total", kNumber}},
               "timing_ms");
}

// Copies, so that a missing name reads as null instead of asserting in nlohmann::json.
json MapNamed(const json& report, const std::string& name) {
  for (const json& map : report.at("maps")) {
    if (map.at("name") == name) return map;
  }
  ADD_FAILURE() << "no map named " << name << " in " << report.at("maps");
  return json::object();
}

json ComponentOf(const json& report, const std::string& name) {
  return report.at("components").at(MapNamed(report, name).value("component", 0u));
}

class MergeCliTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(testing::MakeTempDir("merge_cli"));
    ASSERT_EQ(Fleetmerge("example " + ShellQuote(*dir_ / "seed1") + " --seed 1").exit_code, 0);
    ASSERT_EQ(Fleetmerge("example " + ShellQuote(*dir_ / "seed2") + " --seed 2").exit_code, 0);
    // Another building's map, under a name of its own (its YAML still names robot_a.pgm).
    fs::copy_file(*dir_ / "seed2" / "robot_a.yaml", *dir_ / "seed2" / "other_building.yaml");
    const YAML::Node truth = YAML::LoadFile((*dir_ / "seed1" / "truth.yaml").string())["T_a_b"];
    T_a_b_ = Pose2(truth["x"].as<double>(), truth["y"].as<double>(), truth["yaw"].as<double>());
  }
  static fs::path A() { return *dir_ / "seed1" / "robot_a.yaml"; }
  static fs::path B() { return *dir_ / "seed1" / "robot_b.yaml"; }
  static fs::path Other() { return *dir_ / "seed2" / "other_building.yaml"; }
  // `yaml` with $A and $B replaced by the (quoted) paths of seed 1's maps.
  static std::string WithMaps(std::string yaml) {
    for (const auto& [word, path] : {std::pair{"$A", A()}, std::pair{"$B", B()}}) {
      for (auto at = yaml.find(word); at != std::string::npos; at = yaml.find(word)) {
        yaml.replace(at, 2, "\"" + path.string() + "\"");
      }
    }
    return yaml;
  }
  static std::string Maps(const std::vector<fs::path>& maps) {
    std::string words;
    for (const auto& map : maps) words += " " + ShellQuote(map);
    return words;
  }
  // `merge --out out <maps> <options>`, which must succeed; returns its report.
  static json MergeOk(const fs::path& out, const std::vector<fs::path>& maps,
                      const std::string& options = "--quiet") {
    const auto run = Fleetmerge("merge --out " + ShellQuote(out) + Maps(maps) + " " + options);
    EXPECT_EQ(run.exit_code, 0) << run.both();
    if (!fs::exists(out / "report.json")) return json::object();
    return ReadJson(out / "report.json");
  }

  static fs::path* dir_;
  static Pose2 T_a_b_;  // seed 1's truth: robot_b's map frame in robot_a's
};
fs::path* MergeCliTest::dir_ = nullptr;
Pose2 MergeCliTest::T_a_b_;

TEST_F(MergeCliTest, ReportHasTheDocumentedNamesAndFindsTheTruth) {
  const fs::path out = testing::MakeTempDir("merge_report") / "out";
  const auto run = Fleetmerge("merge --quiet --out " + ShellQuote(out) + Maps({A(), B()}));
  ASSERT_EQ(run.exit_code, 0) << run.both();
  EXPECT_NE(run.out.find((out / "report.json").string()), std::string::npos) << run.out;
  json report = ReadJson(out / "report.json");
  ExpectDocumentedNames(report);
  ASSERT_EQ(report["maps"].size(), 2u);
  EXPECT_EQ(report["maps"][0]["name"], "robot_a") << "names default to the YAML file's stem";
  EXPECT_EQ(report["maps"][1]["name"], "robot_b");
  EXPECT_EQ(report["maps"][0]["source"], A().string());
  json& reference_pose = report["maps"][0]["pose"];
  EXPECT_EQ(reference_pose["x"].get<double>(), 0.0);
  EXPECT_EQ(reference_pose["y"].get<double>(), 0.0);
  EXPECT_EQ(reference_pose["yaw"].get<double>(), 0.0);
  ExpectNear(PoseOf(report["maps"][1]["pose"]), T_a_b_, "robot_b's pose against truth.yaml");

  ASSERT_EQ(report["components"].size(), 1u);
  EXPECT_EQ(report["components"][0]["maps"], json({"robot_a", "robot_b"}));
  EXPECT_EQ(report["components"][0]["merged_map"], "merged_0.yaml");
  ASSERT_EQ(report["pairs"].size(), 1u);
  json& pair = report["pairs"][0];
  EXPECT_EQ(pair["a"], "robot_a");
  EXPECT_EQ(pair["b"], "robot_b");
  EXPECT_TRUE(pair["accepted"].get<bool>());
  ASSERT_GE(pair["hypotheses"].size(), 1u);
  EXPECT_EQ(pair["omega"], pair["hypotheses"][0]["omega"]) << "omega is the best hypothesis'";
  EXPECT_EQ(pair["overlap_cells"], pair["hypotheses"][0]["overlap_cells"]);
  EXPECT_EQ(pair["wall_agreement"], pair["hypotheses"][0]["wall_agreement"]);

  json& t = report["timing_ms"];
  EXPECT_LE(t["load"].get<double>() + t["pairs"].get<double>() + t["refine"].get<double>() +
                t["composite"].get<double>(),
            t["total"].get<double>());
  for (const char* file : {"merged_0.yaml", "merged_0.pgm", "merged_0_preview.png"}) {
    EXPECT_TRUE(fs::is_regular_file(out / file)) << file;
  }
}

TEST_F(MergeCliTest, MergedMapLoadsAndIsDrawnInTheReferenceFrame) {
  const fs::path out = testing::MakeTempDir("merge_loads") / "out";
  MergeOk(out, {A(), B()});
  const LoadedMap merged = LoadMap(out / "merged_0.yaml");
  const LoadedMap a = LoadMap(A());
  EXPECT_EQ(merged.grid.geometry().resolution_m(), a.grid.geometry().resolution_m());
  EXPECT_GT(merged.grid.Count(CellState::kOccupied), 0);
  EXPECT_GT(merged.grid.Count(CellState::kFree), a.grid.Count(CellState::kFree))
      << "robot_b's part of the building is added";
  // The merged map is in robot_a's frame: robot_a overlays it at the identity.
  const auto run = Fleetmerge("pair " + Maps({out / "merged_0.yaml", A()}) + " --json -n 1");
  ASSERT_EQ(run.exit_code, 0) << run.both();
  json pair = json::parse(run.out);
  ASSERT_GE(pair["hypotheses"].size(), 1u);
  ExpectNear(PoseOf(pair["hypotheses"][0]), Pose2(), "robot_a on the merged map");
}

TEST_F(MergeCliTest, ReferenceOptionPutsThatMapAtTheIdentity) {
  const fs::path out = testing::MakeTempDir("merge_reference") / "out";
  json report = MergeOk(out, {A(), B()}, "--quiet --reference robot_b");
  ASSERT_EQ(report.value("maps", json::array()).size(), 2u);
  ExpectNear(PoseOf(MapNamed(report, "robot_b")["pose"]), Pose2(), "the reference");
  ExpectNear(PoseOf(MapNamed(report, "robot_a")["pose"]), T_a_b_.inverse(), "robot_a in b");
}

TEST_F(MergeCliTest, UnknownReferenceIsRefusedBeforeAnyOutput) {
  const fs::path out = testing::MakeTempDir("merge_bad_reference") / "out";
  const auto run =
      Fleetmerge("merge --out " + ShellQuote(out) + Maps({A(), B()}) + " --reference nobody");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("--reference 'nobody'"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out));
}

TEST_F(MergeCliTest, ProgressLinesOnStderrUnlessQuiet) {
  const fs::path dir = testing::MakeTempDir("merge_progress");
  const auto loud = Fleetmerge("merge --out " + ShellQuote(dir / "loud") + Maps({A(), B()}));
  ASSERT_EQ(loud.exit_code, 0) << loud.both();
  const std::vector<std::string> pairs = ProgressLines(loud.err, "pairs");
  ASSERT_FALSE(pairs.empty()) << "stderr:\n" << loud.err;
  EXPECT_EQ(pairs.back(), "merge: pairs 1/1");
  EXPECT_EQ(loud.err.find('\r'), std::string::npos) << "no redrawn bar when not a terminal";
  EXPECT_EQ(ProgressLines(loud.out, "pairs").size(), 0u) << "progress is not on stdout";

  const auto quiet =
      Fleetmerge("merge --quiet --out " + ShellQuote(dir / "quiet") + Maps({A(), B()}));
  ASSERT_EQ(quiet.exit_code, 0) << quiet.both();
  EXPECT_EQ(quiet.err, "");
  EXPECT_TRUE(fs::exists(dir / "quiet" / "report.json"));
}

// Octrees too: OctoMap's writeBinaryData() prints "Writing N nodes to output stream..." on
// stderr, without a newline, whenever the library is built with its debug output (Debian's is),
// which broke --quiet and ran into the next line of the output. `example` writes octrees the same
// way and prints only its own lines.
TEST(MergeCliOctrees, QuietMergeOfOctreesPrintsNothingOnStderr) {
  const fs::path dir = testing::MakeTempDir("merge_octrees_quiet");
  const auto example = Fleetmerge("example " + ShellQuote(dir) + " --octree");
  ASSERT_EQ(example.exit_code, 0) << example.both();
  EXPECT_EQ(example.err, "");
  const auto quiet = Fleetmerge("merge --quiet " + ShellQuote(dir / "job.yaml"));
  ASSERT_EQ(quiet.exit_code, 0) << quiet.both();
  EXPECT_EQ(quiet.err, "");
  EXPECT_EQ(quiet.out.rfind("job", 0), 0u) << "stdout starts with the job's line:\n" << quiet.out;
  EXPECT_TRUE(fs::exists(dir / "merged" / "merged_0.bt"));
}

TEST_F(MergeCliTest, ProgressShowsTheTimeLeftBeforeAStageEnds) {
  // 4 maps, 6 pairs: lines at 2/6 and 4/6 with the time left, and 6/6 without.
  const fs::path out = testing::MakeTempDir("merge_progress_left") / "out";
  const fs::path other_b = *dir_ / "seed2" / "other_robot_b.yaml";  // its YAML names robot_b.pgm
  if (!fs::exists(other_b)) fs::copy_file(*dir_ / "seed2" / "robot_b.yaml", other_b);
  const auto run =
      Fleetmerge("merge --out " + ShellQuote(out) + Maps({A(), B(), Other(), other_b}));
  ASSERT_EQ(run.exit_code, 0) << run.both();
  const std::vector<std::string> pairs = ProgressLines(run.err, "pairs");
  ASSERT_EQ(pairs.size(), 3u) << run.err;
  EXPECT_NE(pairs[0].find("pairs 2/6 (about "), std::string::npos) << pairs[0];
  EXPECT_NE(pairs[1].find("pairs 4/6 (about "), std::string::npos) << pairs[1];
  EXPECT_EQ(pairs[2], "merge: pairs 6/6");
}

TEST_F(MergeCliTest, MapOfAnotherBuildingStaysUnmerged) {
  const fs::path out = testing::MakeTempDir("merge_foreign") / "out";
  json report = MergeOk(out, {A(), B(), Other()});
  ExpectDocumentedNames(report);
  ASSERT_EQ(report.value("components", json::array()).size(), 2u) << report;
  json foreign = ComponentOf(report, "other_building");
  EXPECT_EQ(foreign["maps"], json({"other_building"}));
  EXPECT_FALSE(foreign.contains("merged_map")) << foreign;
  ExpectNear(PoseOf(MapNamed(report, "other_building")["pose"]), Pose2(), "its own reference");
  json fleet = ComponentOf(report, "robot_a");
  EXPECT_EQ(fleet["maps"], json({"robot_a", "robot_b"}));
  ASSERT_TRUE(fleet.contains("merged_map")) << fleet;
  EXPECT_TRUE(fs::is_regular_file(out / fleet["merged_map"].get<std::string>()));
  for (const json& pair : report["pairs"]) {
    if (pair.at("b") == "other_building") {
      EXPECT_FALSE(pair.at("accepted").get<bool>()) << pair;
    }
  }
  const std::set<std::string> expected = {
      ".fleetmerge-job",      "report.json",       "merged_0.yaml",          "merged_0.pgm",
      "merged_0_preview.png", "transforms.launch", "transforms.launch.yaml", "report.html",
      "report_map_0.png",     "report_map_1.png",  "report_map_2.png",       "merged_bag"};
  EXPECT_EQ(FilesIn(out), expected) << "no merged map for the unmerged component";
}

// --fixed and --initial-pose give a map list what a job file's fixed/pose and initial_pose keys
// give (configs/README.md): the fixed map stays at its pose and is the merged frame, the maps its
// pairs link follow it, and a map that overlaps nobody is placed at its start pose.
TEST_F(MergeCliTest, FixedAndInitialPoseOptionsPlaceTheMaps) {
  const fs::path out = testing::MakeTempDir("merge_fixed_prior") / "out";
  const Pose2 T_merged_a(1.0, 2.0, 0.5), T_merged_other(3.0, 4.0, 0.1);
  json report = MergeOk(out, {A(), B(), Other()},
                        "--quiet --fixed robot_a=1,2,0.5 --initial-pose other_building=3,4,0.1");
  ASSERT_EQ(report.value("maps", json::array()).size(), 3u) << report;
  const json a = MapNamed(report, "robot_a");
  EXPECT_EQ(a["placed_by"], "fixed");
  EXPECT_EQ(a["pose"], json({{"x", 1.0}, {"y", 2.0}, {"yaw", 0.5}})) << "a fixed pose is exact";
  const json b = MapNamed(report, "robot_b");
  EXPECT_EQ(b["placed_by"], "pairs");
  ExpectNear(PoseOf(b["pose"]), T_merged_a * T_a_b_, "robot_b: the fixed pose times the truth");
  const json other = MapNamed(report, "other_building");
  EXPECT_EQ(other["placed_by"], "prior");
  ExpectNear(PoseOf(other["pose"]), T_merged_other, "other_building at its start pose");
  EXPECT_EQ(PoseOf(other["initial_pose"]).translation_m(), T_merged_other.translation_m());
  EXPECT_EQ(other["initial_pose_sigma"],
            json({kDefaultPriorTranslationSigmaM, kDefaultPriorYawSigmaRad}));
}

// The only map with a start pose, overlapping nobody: placed at it in the site frame, which no
// other map shares (its own component), with the merged map, transform and report of a placed map;
// the maps without priors are merged as without it.
TEST_F(MergeCliTest, TheOnlyMapWithAStartPoseIsPlacedAtItAlone) {
  const fs::path out = testing::MakeTempDir("merge_lone_prior") / "out";
  const Pose2 T_site_other(3.0, 4.0, 0.1);
  const auto run = Fleetmerge("merge --out " + ShellQuote(out) + Maps({A(), B(), Other()}) +
                              " --initial-pose other_building=3,4,0.1");
  ASSERT_EQ(run.exit_code, 0) << run.both();
  EXPECT_NE(run.out.find("other_building placed by its initial_pose (no accepted pair links it to "
                         "another map)"),
            std::string::npos)
      << run.out;
  const json report = ReadJson(out / "report.json");
  ExpectDocumentedNames(report);
  const json other = MapNamed(report, "other_building");
  EXPECT_EQ(other["placed_by"], "prior");
  EXPECT_EQ(other["pose"], json({{"x", 3.0}, {"y", 4.0}, {"yaw", 0.1}})) << "exactly its prior";
  EXPECT_EQ(MapNamed(report, "robot_a")["placed_by"], "reference");
  EXPECT_EQ(MapNamed(report, "robot_b")["placed_by"], "pairs");
  ExpectNear(PoseOf(MapNamed(report, "robot_b")["pose"]), T_a_b_, "robot_b");
  EXPECT_EQ(ComponentOf(report, "robot_a")["maps"], json({"robot_a", "robot_b"}));
  const json site = ComponentOf(report, "other_building");
  EXPECT_EQ(site["maps"], json({"other_building"}));
  ASSERT_TRUE(site.contains("merged_map")) << site;
  // Its merged map is the map's own cells, where its prior puts them.
  const LoadedMap input = LoadMap(Other());
  const LoadedMap merged = LoadMap(out / site["merged_map"].get<std::string>());
  EXPECT_EQ(cv::countNonZero(merged.grid.cells() != input.grid.cells()), 0);
  const Pose2 expected = T_site_other * input.grid.geometry().T_map_grid();
  ExpectNear(merged.grid.geometry().T_map_grid(), expected, "merged map's origin");
  // A transform from the site component's frame (map_1: the second component) to its map frame.
  const std::string launch = ReadFile(out / "transforms.launch");
  EXPECT_NE(launch.find("name=\"fleetmerge_tf_other_building\" args=\"3 4 0 0.1 0 0 map_1 "
                        "other_building/map\""),
            std::string::npos)
      << launch;
  EXPECT_EQ(launch.find("was not merged"), std::string::npos) << launch;
}

TEST_F(MergeCliTest, RepeatableOptionsBeforeTheMapsTakeOneValueEach) {
  // CLI11 lets a vector option take every word after it unless told otherwise: robot_a.yaml
  // would become a value of --fixed.
  const fs::path out = testing::MakeTempDir("merge_option_order") / "out";
  const auto run =
      Fleetmerge("merge --quiet --out " + ShellQuote(out) +
                 " --initial-pose robot_b=0,0,0,100,3 --fixed robot_a" + Maps({A(), B()}));
  ASSERT_EQ(run.exit_code, 0) << run.both();
  const json report = ReadJson(out / "report.json");
  ASSERT_EQ(report["maps"].size(), 2u) << report;
  EXPECT_EQ(MapNamed(report, "robot_a")["placed_by"], "fixed");
  EXPECT_EQ(MapNamed(report, "robot_b")["placed_by"], "pairs");
}

TEST_F(MergeCliTest, AStartPoseFiveMetresOffRefusesThePairNamingIt) {
  const fs::path out = testing::MakeTempDir("merge_wrong_prior") / "out";
  const Pose2 wrong = Pose2(5.0, 0.0, 0.0) * T_a_b_;
  std::ostringstream option;
  option.precision(17);
  option << "--initial-pose robot_b=" << wrong.x_m() << "," << wrong.y_m() << "," << wrong.yaw_rad()
         << ",0.2,0.05";
  json report = MergeOk(out, {A(), B()}, "--quiet --fixed robot_a " + option.str());
  ASSERT_EQ(report.value("pairs", json::array()).size(), 1u) << report;
  const json& pair = report["pairs"][0];
  EXPECT_FALSE(pair["accepted"].get<bool>()) << pair;
  EXPECT_NE(pair.value("note", "").find("initial_pose"), std::string::npos) << pair;
  EXPECT_EQ(MapNamed(report, "robot_b")["placed_by"], "prior");
}

TEST_F(MergeCliTest, BadFixedOrInitialPoseIsRefusedBeforeAnyOutput) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--initial-pose robot9=1,2,0", "no map is named 'robot9' (the maps: 'robot_a', 'robot_b')"},
      {"--initial-pose robot_b=1,2", "2 numbers; expected NAME=X,Y,YAW"},
      {"--initial-pose robot_b=1,2,0,", "a number is missing"},
      {"--initial-pose robot_b=1,nan,0", "'nan' is not a finite number"},
      {"--initial-pose robot_b=1,2,0,-0.5,0.1", "the sigmas (metres, radians) must be > 0"},
      {"--initial-pose robot_b", "no pose given"},
      {"--fixed robot_a=1,2,inf", "'inf' is not a finite number"},
      {"--fixed robot_a=0x10,2,0", "'0x10' is not a finite number"},
      {"--initial-pose robot_b=1,2,90", "YAW 90 rad looks like degrees (90 deg is 1.5708 rad)"},
      {"--initial-pose robot_b=1,2,0,0.5,10", "SIGMA_RAD 10 rad looks like degrees"},
      {"--fixed robot_a --initial-pose robot_a=1,2,0", "map 'robot_a' is already given"},
      {"--fixed robot_b --reference robot_a", "the reference is the first fixed map, 'robot_b'"},
  };
  for (const auto& [options, message] : cases) {
    const fs::path out = testing::MakeTempDir("merge_bad_prior") / "out";
    const auto run =
        Fleetmerge("merge --quiet --out " + ShellQuote(out) + Maps({A(), B()}) + " " + options);
    EXPECT_NE(run.exit_code, 0) << options;
    EXPECT_NE(run.err.find(message), std::string::npos) << options << ": " << run.err;
    EXPECT_FALSE(fs::exists(out)) << options;
  }
  const auto job_file = Fleetmerge("merge " + ShellQuote(A()) + " --fixed robot_a");
  EXPECT_NE(job_file.exit_code, 0);
  EXPECT_NE(job_file.err.find("--fixed names a map of --out's map list"), std::string::npos)
      << job_file.err;
}

TEST_F(MergeCliTest, RealMapOfAnotherBuildingStaysUnmerged) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path maps = *testing::SharedMapsDir();
  const fs::path out = testing::MakeTempDir("merge_real_foreign") / "out";
  json report = MergeOk(out, {maps / "robotis_corridor_run1.yaml",
                              maps / "robotis_corridor_run2.yaml", maps / "intel_lab.yaml"});
  ExpectDocumentedNames(report);
  json lab = ComponentOf(report, "intel_lab");
  EXPECT_EQ(lab["maps"], json({"intel_lab"}));
  EXPECT_FALSE(lab.contains("merged_map")) << lab;
  json corridor = ComponentOf(report, "robotis_corridor_run1");
  EXPECT_EQ(corridor["maps"], json({"robotis_corridor_run1", "robotis_corridor_run2"}));
  EXPECT_TRUE(corridor.contains("merged_map")) << corridor;
}

// --- Job files -------------------------------------------------------------------------------

// Two jobs: `first` (which must fail at run time) and `second`, a good one.
testing::CommandResult RunTwoJobs(const fs::path& dir, const std::string& jobs_yaml) {
  WriteFile(dir / "jobs.yaml", jobs_yaml);
  return Fleetmerge("merge --quiet " + ShellQuote(dir / "jobs.yaml"));
}

void ExpectSecondJobComplete(const fs::path& dir, const testing::CommandResult& run) {
  EXPECT_EQ(run.err.find("job 'second' failed"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("1 of 2 job(s) failed"), std::string::npos) << run.err;
  EXPECT_NE(run.out.find("second: 2 maps"), std::string::npos) << run.out;
  const fs::path out = dir / "second_out";
  ASSERT_TRUE(fs::is_regular_file(out / "report.json"));
  json report = ReadJson(out / "report.json");
  ExpectDocumentedNames(report);
  EXPECT_EQ(report["maps"].size(), 2u);
  EXPECT_EQ(report["pairs"].size(), 1u);
  ASSERT_EQ(report["components"].size(), 1u);
  EXPECT_EQ(report["components"][0].value("merged_map", ""), "merged_0.yaml");
  EXPECT_TRUE(fs::is_regular_file(out / "merged_0.yaml"));
}

// The options a job ran with, as its report.html lists those that differ from the defaults:
// {"threads": {"default": 0, "value": 1}, ...}.
json OptionsChanged(const fs::path& report_html) {
  const std::string page = ReadFile(report_html);
  const std::string key = "\"options_changed\":";
  const std::size_t start = page.find(key);
  if (start == std::string::npos) {
    ADD_FAILURE() << "no options_changed in " << report_html;
    return json::object();
  }
  std::size_t end = start + key.size();
  int depth = 0;  // the object's braces (its keys and values hold none)
  do {
    depth += page[end] == '{' ? 1 : page[end] == '}' ? -1 : 0;
    ++end;
  } while (depth > 0 && end < page.size());
  return json::parse(page.substr(start + key.size(), end - start - key.size()));
}

// Options on the command line that job files' keys also set apply to every job of the files,
// over their keys: `merge --omega-threshold 1.0 jobs.yaml` accepts no pair in either job. A
// sampling option keeps a job's own seed.
TEST_F(MergeCliTest, CommandLineOptionsApplyToEveryJobOfAJobFile) {
  const fs::path dir = testing::MakeTempDir("merge_job_options");
  WriteFile(dir / "jobs.yaml", WithMaps(R"(jobs:
  - {name: first, maps: [$A, $B], output: first_out}
  - {name: second, maps: [$A, $B], output: second_out, threads: 2, seed: 7, omega_threshold: 0.5,
     hough: {n_theta: 120}}
)"));
  const auto run =
      Fleetmerge("merge --quiet --threads 1 --omega-threshold 1.0 --n-theta 90 " +
                 std::string("--hough-sampling every:2 ") + ShellQuote(dir / "jobs.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.both();
  for (const char* job : {"first", "second"}) {
    const fs::path out = dir / (std::string(job) + "_out");
    const json report = ReadJson(out / "report.json");
    EXPECT_EQ(MapNamed(report, "robot_b")["placed_by"], "unmerged") << job;
    EXPECT_EQ(report["components"].size(), 2u) << job;
    const json changed = OptionsChanged(out / "report.html");
    EXPECT_EQ(changed["threads"]["value"], 1) << job << ": " << changed;
    EXPECT_EQ(changed["omega_threshold"]["value"], 1.0) << job << ": " << changed;
    EXPECT_EQ(changed["hough.n_theta"]["value"], 90) << job << ": " << changed;
    EXPECT_EQ(changed["hough.sampling.step"]["value"], 2) << job << ": " << changed;
  }
  EXPECT_EQ(OptionsChanged(dir / "second_out" / "report.html")["seed"]["value"], 7);
  EXPECT_FALSE(OptionsChanged(dir / "first_out" / "report.html").contains("seed"));

  // Without the options, the same jobs merge both maps.
  ASSERT_EQ(Fleetmerge("merge --quiet " + ShellQuote(dir / "jobs.yaml")).exit_code, 0);
  EXPECT_EQ(ReadJson(dir / "first_out" / "report.json")["components"].size(), 1u);
}

// The options of --out's map list (each has a job file key) and a height band that the command
// line's bound leaves empty are refused with a job file, before anything is written.
TEST_F(MergeCliTest, MapListOptionsAndAnEmptyBandWithAJobFileAreRefused) {
  const fs::path dir = testing::MakeTempDir("merge_job_map_list_options");
  WriteFile(dir / "jobs.yaml", WithMaps("jobs:\n  - {name: site, maps: [$A, $B], output: out}\n"));
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--reference robot_b",
       "--reference is for --out's map list; a job file sets it with "
       "its 'reference' key"},
      {"--topic /map",
       "--topic is for --out's map list; a job file sets it with each map "
       "entry's 'topic' key"},
      {"--tf-parent world",
       "--tf-parent is for --out's map list; a job file sets it with its "
       "'tf_parent' key"},
      {"--tf-child robot/{name}", "--tf-child is for --out's map list"},
      {"--octree-band-min 2.5",
       "--octree-band-min/--octree-band-max: job 'site' gets the "
       "height band [2.500000, 1.800000] m, which is empty"}};
  for (const auto& [option, message] : cases) {
    const auto run = Fleetmerge("merge --quiet " + option + " " + ShellQuote(dir / "jobs.yaml"));
    EXPECT_EQ(run.exit_code, 1) << option << ": " << run.both();
    EXPECT_NE(run.err.find(message), std::string::npos) << option << ": " << run.err;
    EXPECT_FALSE(fs::exists(dir / "out")) << option;
  }
}

TEST_F(MergeCliTest, JobWhoseOutputCannotBeCreatedFailsAlone) {
  // `output` under a regular file passes validation (the folder does not exist yet) and fails
  // when the job writes.
  const fs::path dir = testing::MakeTempDir("merge_job_output");
  WriteFile(dir / "file.txt", "not a folder\n");
  const auto run = RunTwoJobs(dir, WithMaps(R"(jobs:
  - {name: first, maps: [$A, $B], output: file.txt/sub}
  - {name: second, maps: [$A, $B], output: second_out}
)"));
  EXPECT_EQ(run.exit_code, 1) << run.both();
  EXPECT_NE(run.err.find("job 'first' failed"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("file.txt/sub"), std::string::npos) << "names the folder: " << run.err;
  EXPECT_NE(run.err.find("Not a directory"), std::string::npos) << "says why: " << run.err;
  EXPECT_EQ(ReadFile(dir / "file.txt"), "not a folder\n");
  ExpectSecondJobComplete(dir, run);
}

TEST_F(MergeCliTest, JobWithAnUnreadableImageFailsAlone) {
  // The map YAML is checked when the job file is loaded, its image only when the job runs.
  const fs::path dir = testing::MakeTempDir("merge_job_image");
  fs::create_directories(dir / "broken");
  fs::copy_file(A(), dir / "broken" / "robot_a.yaml");
  WriteFile(dir / "broken" / "robot_a.pgm", "these bytes are not an image\n");
  const auto run = RunTwoJobs(dir, WithMaps(R"(jobs:
  - {name: first, maps: [broken/robot_a.yaml, $B], output: first_out}
  - {name: second, maps: [$A, $B], output: second_out}
)"));
  EXPECT_EQ(run.exit_code, 1) << run.both();
  EXPECT_NE(run.err.find("job 'first' failed"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("robot_a.pgm"), std::string::npos) << "names the image: " << run.err;
  EXPECT_FALSE(fs::exists(dir / "first_out" / "report.json"));
  ExpectSecondJobComplete(dir, run);
}

// A job file that validation must reject: non-zero exit, the file, line and key in the message,
// and no job started (no output folder).
void ExpectRejected(const std::string& yaml, const std::string& expected_message) {
  const fs::path dir = testing::MakeTempDir("merge_invalid");
  const fs::path job_file = dir / "jobs.yaml";
  WriteFile(job_file, yaml);
  const auto run = Fleetmerge("merge " + ShellQuote(job_file));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find(job_file.string() + ": " + expected_message), std::string::npos)
      << run.err;
  EXPECT_EQ(FilesIn(dir), std::set<std::string>{"jobs.yaml"}) << "no output folder";
}

TEST_F(MergeCliTest, UnknownKeyInALaterJobStopsEveryJob) {
  ExpectRejected(WithMaps(R"(jobs:
  - {name: one, maps: [$A, $B], output: out1}
  - name: two
    maps: [$A, $B]
    output: out2
    omega_treshold: 0.8
)"),
                 "line 6: key 'jobs[1].omega_treshold': unknown key");
}

TEST_F(MergeCliTest, UnknownNestedKeyIsNamedWithItsPath) {
  ExpectRejected(WithMaps(R"(maps: [$A, $B]
output: out
hough:
  n_thetas: 90
)"),
                 "line 4: key 'hough.n_thetas': unknown key");
}

TEST_F(MergeCliTest, UnknownCommandLineOptionIsRefusedBeforeAnyOutput) {
  const fs::path out = testing::MakeTempDir("merge_bad_option") / "out";
  const auto run =
      Fleetmerge("merge --out " + ShellQuote(out) + Maps({A(), B()}) + " --omega-treshold 0.8");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.both().find("--omega-treshold"), std::string::npos) << run.both();
  EXPECT_FALSE(fs::exists(out));
}

// --- Inputs are never overwritten -------------------------------------------------------------

// The inputs' folder holds `merged_0.yaml` (an input, its image `image_name`) and robot_b; the
// merge writes into that folder and must leave every file as it was.
void ExpectInputsSurvive(const fs::path& a_yaml, const fs::path& b_yaml,
                         const std::string& image_name) {
  const fs::path folder = testing::MakeTempDir("merge_overwrite_" + image_name);
  fs::copy_file(a_yaml.parent_path() / "robot_a.pgm", folder / image_name);
  std::string yaml = ReadFile(a_yaml);
  yaml.replace(yaml.find("robot_a.pgm"), std::string("robot_a.pgm").size(), image_name);
  WriteFile(folder / "merged_0.yaml", yaml);
  fs::copy_file(b_yaml, folder / "robot_b.yaml");
  fs::copy_file(b_yaml.parent_path() / "robot_b.pgm", folder / "robot_b.pgm");
  std::vector<std::string> before;
  const std::set<std::string> files = FilesIn(folder);
  for (const auto& name : files) before.push_back(ReadFile(folder / name));

  const auto run =
      Fleetmerge("merge --quiet --out " + ShellQuote(folder) + " " +
                 ShellQuote(folder / "merged_0.yaml") + " " + ShellQuote(folder / "robot_b.yaml"));
  EXPECT_NE(run.exit_code, 0);
  EXPECT_NE(run.err.find("refusing to overwrite"), std::string::npos) << run.err;
  EXPECT_EQ(FilesIn(folder), files) << "no file added, none left half-written";
  std::size_t i = 0;
  for (const auto& name : files) EXPECT_EQ(ReadFile(folder / name), before[i++]) << name;
}

TEST_F(MergeCliTest, RefusesToOverwriteAnInputNamedLikeTheMergedMap) {
  ExpectInputsSurvive(A(), B(), "robot_a.pgm");
}

TEST_F(MergeCliTest, RefusesToOverwriteAnInputAndItsImage) {
  ExpectInputsSurvive(A(), B(), "merged_0.pgm");
}

}  // namespace
}  // namespace fleetmerge

namespace fleetmerge {
namespace {

TEST(MergeCliDuplicates, SameFileTwiceIsRefusedAndClashingStemsAreNamedByFolder) {
  const auto dir = testing::MakeTempDir("merge_dup");
  ASSERT_EQ(testing::RunCommand(std::string(FLEETMERGE_EXECUTABLE) + " example " +
                                (dir / "s1").string() + " --seed 1")
                .exit_code,
            0);
  ASSERT_EQ(testing::RunCommand(std::string(FLEETMERGE_EXECUTABLE) + " example " +
                                (dir / "s2").string() + " --seed 2")
                .exit_code,
            0);
  const std::string a1 = (dir / "s1" / "robot_a.yaml").string();
  const std::string a2 = (dir / "s2" / "robot_a.yaml").string();
  const auto twice =
      testing::RunCommand(std::string(FLEETMERGE_EXECUTABLE) + " merge --quiet --out " +
                          (dir / "o1").string() + " " + a1 + " " + a1);
  EXPECT_NE(twice.exit_code, 0);
  EXPECT_NE(twice.err.find("is listed twice"), std::string::npos) << twice.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "o1"));
  // Same stem in two folders: named by the folders (io/map_names.hpp).
  const auto clash =
      testing::RunCommand(std::string(FLEETMERGE_EXECUTABLE) + " merge --quiet --out " +
                          (dir / "o2").string() + " " + a1 + " " + a2);
  ASSERT_EQ(clash.exit_code, 0) << clash.err;
  const json report = json::parse(ReadFile(dir / "o2" / "report.json"));
  EXPECT_EQ(report["maps"][0]["name"], "s1");
  EXPECT_EQ(report["maps"][1]["name"], "s2");
}

}  // namespace
}  // namespace fleetmerge
