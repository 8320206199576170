// Maps from robot bags, end to end through the `fleetmerge` executable. The bags are written by
// writers other than our readers (tests/data/bags/make_bags.py: Debian's python3-rosbag for
// ROS 1, Python's sqlite3 + its own CDR encoder for rosbag2 db3; make_mcap.mjs: npm's
// @mcap/core + @foxglove/rosmsg2-serialization for the checked-in MCAP bags), from maps with a
// known answer (`fleetmerge simulate`, `fleetmerge bench cut-fleet` of a real map).
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "io/map_io.hpp"
#include "tests/support/files.hpp"
#include "tests/support/fleetmerge_cli.hpp"
#include "tests/support/run_command.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using testing::Fleetmerge;
using testing::ShellQuote;

const fs::path kBagsDir = fs::path(FLEETMERGE_SOURCE_DIR) / "tests" / "data" / "bags";

// make_bags.py with Debian's Python (python3-rosbag lives there).
void MakeBag(const std::string& args) {
  const auto run =
      testing::RunCommand("/usr/bin/python3 " + ShellQuote(kBagsDir / "make_bags.py") + " " + args);
  ASSERT_EQ(run.exit_code, 0) << "make_bags.py " << args << "\n" << run.both();
}

// A simulated fleet of 3 robots with its truth (seed 3: every pair overlaps).
fs::path SimulateFleet(const fs::path& dir) {
  const auto run = Fleetmerge("simulate " + ShellQuote(dir / "sim") + " --robots 3 --seed 3");
  EXPECT_EQ(run.exit_code, 0) << run.both();
  return dir / "sim";
}

void ExpectSameMap(const fs::path& got_yaml, const fs::path& want_yaml) {
  const LoadedMap got = LoadMap(got_yaml), want = LoadMap(want_yaml);
  ASSERT_EQ(got.grid.width(), want.grid.width()) << got_yaml;
  ASSERT_EQ(got.grid.height(), want.grid.height()) << got_yaml;
  EXPECT_EQ(got.grid.geometry().resolution_m(), want.grid.geometry().resolution_m());
  const Pose2 a = got.grid.geometry().T_map_grid(), b = want.grid.geometry().T_map_grid();
  EXPECT_NEAR(a.x_m(), b.x_m(), 1e-9);
  EXPECT_NEAR(a.y_m(), b.y_m(), 1e-9);
  EXPECT_NEAR(a.yaw_rad(), b.yaw_rad(), 1e-9);
  EXPECT_EQ(cv::countNonZero(got.grid.cells() != want.grid.cells()), 0) << got_yaml;
}

json ReadJson(const fs::path& path) { return json::parse(testing::ReadFile(path)); }

// Every truly overlapping pair merged within 1 degree and 3 cells (eval's "coarse"), one
// component, no false merge.
void ExpectAllPairsCoarse(const fs::path& report, const fs::path& truth) {
  const auto eval = Fleetmerge("eval --json " + ShellQuote(report) + " " + ShellQuote(truth));
  ASSERT_EQ(eval.exit_code, 0) << eval.both();
  const json j = json::parse(eval.out);
  EXPECT_TRUE(j["false_merges"].empty()) << eval.out;
  int scored = 0;
  for (const json& p : j["pairs"]) {
    if (!p["scored"].get<bool>()) continue;
    ++scored;
    EXPECT_TRUE(p["merged"].get<bool>()) << p.dump();
    EXPECT_TRUE(p["coarse"].get<bool>()) << p.dump();
    EXPECT_LE(p["yaw_error_deg"].get<double>(), 1.0);
    EXPECT_LE(p["displacement_cells"].get<double>(), 3.0);
  }
  EXPECT_GE(scored, 2) << eval.out;
}

// The two reports place every map identically (maps in the same order).
void ExpectSamePoses(const fs::path& report_a, const fs::path& report_b) {
  const json a = ReadJson(report_a), b = ReadJson(report_b);
  ASSERT_EQ(a["maps"].size(), b["maps"].size());
  for (std::size_t m = 0; m < a["maps"].size(); ++m) {
    for (const char* k : {"x", "y", "yaw"}) {
      EXPECT_NEAR(a["maps"][m]["pose"][k].get<double>(), b["maps"][m]["pose"][k].get<double>(),
                  1e-9)
          << a["maps"][m]["name"] << " " << k;
    }
  }
}

// transforms.launch.yaml (ROS 2) and transforms.launch (ROS 1) beside report.json hold, for
// each merged map, its pose in its component's frame as report.json has it, parent `map` and
// child `<name>/map`. Parsed as the launch systems read them: YAML and XML.
void ExpectLaunchFilesMatchReport(const fs::path& out) {
  const json report = ReadJson(out / "report.json");
  const YAML::Node launch = YAML::LoadFile((out / "transforms.launch.yaml").string());
  ASSERT_TRUE(launch["launch"].IsSequence());
  ASSERT_EQ(launch["launch"].size(), report["maps"].size());
  const std::string xml = testing::ReadFile(out / "transforms.launch");
  const std::regex node_re(
      R"re(<node pkg="tf2_ros" type="static_transform_publisher" name="([^"]+)" args="([^"]+)"/>)re");
  std::vector<std::vector<std::string>> xml_args;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), node_re);
       it != std::sregex_iterator(); ++it) {
    std::istringstream words((*it)[2].str());
    xml_args.emplace_back(std::istream_iterator<std::string>(words),
                          std::istream_iterator<std::string>());
  }
  ASSERT_EQ(xml_args.size(), report["maps"].size()) << xml;
  EXPECT_NE(xml.find("<launch>"), std::string::npos);
  for (std::size_t m = 0; m < report["maps"].size(); ++m) {
    const json& map = report["maps"][m];
    const YAML::Node node = launch["launch"][m]["node"];
    EXPECT_EQ(node["pkg"].as<std::string>(), "tf2_ros");
    EXPECT_EQ(node["exec"].as<std::string>(), "static_transform_publisher");
    std::istringstream words(node["args"].as<std::string>());
    std::map<std::string, std::string> args;
    for (std::string key, value; words >> key >> value;) args[key] = value;
    const std::string child = map["name"].get<std::string>() + "/map";
    EXPECT_EQ(args["--frame-id"], "map");
    EXPECT_EQ(args["--child-frame-id"], child);
    EXPECT_NEAR(std::stod(args["--x"]), map["pose"]["x"].get<double>(), 1e-9);
    EXPECT_NEAR(std::stod(args["--y"]), map["pose"]["y"].get<double>(), 1e-9);
    EXPECT_NEAR(std::stod(args["--yaw"]), map["pose"]["yaw"].get<double>(), 1e-9);
    ASSERT_EQ(xml_args[m].size(), 8u);  // x y z yaw pitch roll frame_id child_frame_id
    EXPECT_NEAR(std::stod(xml_args[m][0]), map["pose"]["x"].get<double>(), 1e-9);
    EXPECT_NEAR(std::stod(xml_args[m][1]), map["pose"]["y"].get<double>(), 1e-9);
    EXPECT_NEAR(std::stod(xml_args[m][3]), map["pose"]["yaw"].get<double>(), 1e-9);
    EXPECT_EQ(xml_args[m][6], "map");
    EXPECT_EQ(xml_args[m][7], child);
    EXPECT_EQ(map["frame"], child);
  }
}

// --- ROS 1 ------------------------------------------------------------------------------------

class Ros1RoundTrip : public ::testing::TestWithParam<std::string> {};

TEST_P(Ros1RoundTrip, ExtractGivesTheSameCellsOriginAndResolution) {
  const fs::path dir = testing::MakeTempDir("ros1_round_trip_" + GetParam());
  const fs::path sim = SimulateFleet(dir);
  const std::string kind = GetParam();
  const std::string options =
      kind == "unindexed" ? "--compression bz2 --unindexed" : "--compression " + kind;
  MakeBag("ros1 --map " + ShellQuote(sim / "robot2.yaml") + " --out " +
          ShellQuote(dir / "robot2.bag") + " --messages 4 " + options);
  const auto run = Fleetmerge("extract " + ShellQuote(dir / "robot2.bag") + " --out " +
                              ShellQuote(dir / "extracted"));
  ASSERT_EQ(run.exit_code, 0) << run.both();
  EXPECT_NE(run.out.find("topic /map"), std::string::npos) << run.out;
  ExpectSameMap(dir / "extracted" / "robot2.yaml", sim / "robot2.yaml");
}

INSTANTIATE_TEST_SUITE_P(Chunks, Ros1RoundTrip,
                         ::testing::Values("none", "bz2", "lz4", "unindexed"));

TEST(Ros1Bags, RealGmappingMapsMergedByFileNameAlone) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  // intel_lab: a GMapping-style grid from the real Intel Research Lab log, cut into three
  // overlapping robot maps in random frames with their truth (bench cut-fleet), each written
  // as a GMapping-like /map topic (growing maps, the last the whole map) in its robot's bag.
  const fs::path dir = testing::MakeTempDir("ros1_gmapping");
  const fs::path map = *testing::SharedMapsDir() / "intel_lab.yaml";
  ASSERT_EQ(Fleetmerge("bench cut-fleet " + ShellQuote(map) + " " + ShellQuote(dir / "cut") +
                       " --robots 3 --seed 5")
                .exit_code,
            0);
  const std::vector<std::string> compression = {"bz2", "lz4", "none"};
  std::string bags, files;
  for (int r = 1; r <= 3; ++r) {
    const std::string robot = "robot" + std::to_string(r);
    MakeBag("ros1 --map " + ShellQuote(dir / "cut" / (robot + ".yaml")) + " --out " +
            ShellQuote(dir / (robot + ".bag")) + " --messages 4 --compression " +
            compression[r - 1]);
    bags += " " + ShellQuote(dir / (robot + ".bag"));
    files += " " + ShellQuote(dir / "cut" / (robot + ".yaml"));
  }
  const auto merged = Fleetmerge("merge --quiet --out " + ShellQuote(dir / "out") + bags);
  ASSERT_EQ(merged.exit_code, 0) << merged.both();
  ExpectAllPairsCoarse(dir / "out" / "report.json", dir / "cut" / "truth.yaml");
  ExpectLaunchFilesMatchReport(dir / "out");
  const json report = ReadJson(dir / "out" / "report.json");
  EXPECT_EQ(report["components"].size(), 1u);
  EXPECT_EQ(report["maps"][1]["name"], "robot2");
  EXPECT_EQ(report["maps"][1]["bag"]["topic"], "/map");
  EXPECT_EQ(report["maps"][1]["bag"]["type"], "nav_msgs/OccupancyGrid");
  // The last of the 4 messages (make_bags.py: 5 s apart from t0 = 1.7e9 s).
  EXPECT_EQ(report["maps"][1]["bag"]["log_time_ns"].get<std::int64_t>(), 1'700'000'020'000'000'000);
  // The same maps as files give the same poses.
  ASSERT_EQ(Fleetmerge("merge --quiet --out " + ShellQuote(dir / "files") + files).exit_code, 0);
  ExpectSamePoses(dir / "out" / "report.json", dir / "files" / "report.json");
}

TEST(Ros1Bags, SeveralMapTopicsInOneBagAreNamedByStemAndTopic) {
  const fs::path dir = testing::MakeTempDir("ros1_topics");
  const fs::path sim = SimulateFleet(dir);
  MakeBag("ros1 --out " + ShellQuote(dir / "fleet.bag") + " --compression lz4" + " --map " +
          ShellQuote(sim / "robot1.yaml") + " --topic /robot1/map" + " --map " +
          ShellQuote(sim / "robot2.yaml") + " --topic /robot2/map" + " --map " +
          ShellQuote(sim / "robot3.yaml") + " --topic /robot3/map");
  const auto merged = Fleetmerge("merge --quiet --out " + ShellQuote(dir / "out") + " " +
                                 ShellQuote(dir / "fleet.bag"));
  ASSERT_EQ(merged.exit_code, 0) << merged.both();
  const json report = ReadJson(dir / "out" / "report.json");
  ASSERT_EQ(report["maps"].size(), 3u);
  EXPECT_EQ(report["maps"][0]["name"], "fleet_robot1_map");
  EXPECT_EQ(report["maps"][2]["bag"]["topic"], "/robot3/map");
  // Same poses as the files.
  ASSERT_EQ(Fleetmerge("merge --quiet --out " + ShellQuote(dir / "files") + " " +
                       ShellQuote(sim / "robot1.yaml") + " " + ShellQuote(sim / "robot2.yaml") +
                       " " + ShellQuote(sim / "robot3.yaml"))
                .exit_code,
            0);
  ExpectSamePoses(dir / "out" / "report.json", dir / "files" / "report.json");

  // --topic picks; pair needs exactly one map per input.
  const auto two =
      Fleetmerge("merge --quiet --out " + ShellQuote(dir / "two") + " " +
                 ShellQuote(dir / "fleet.bag") + " --topic /robot1/map --topic " + "robot3/map");
  ASSERT_EQ(two.exit_code, 0) << two.both();
  const json two_report = ReadJson(dir / "two" / "report.json");
  ASSERT_EQ(two_report["maps"].size(), 2u);
  EXPECT_EQ(two_report["maps"][1]["bag"]["topic"], "/robot3/map");
  const auto ambiguous =
      Fleetmerge("pair " + ShellQuote(dir / "fleet.bag") + " " + ShellQuote(sim / "robot2.yaml"));
  EXPECT_EQ(ambiguous.exit_code, 1);
  EXPECT_NE(ambiguous.err.find("pick one with --topic"), std::string::npos) << ambiguous.err;
  const auto pair = Fleetmerge("pair --json --topic /robot2/map " + ShellQuote(dir / "fleet.bag") +
                               " " + ShellQuote(sim / "robot3.yaml"));
  ASSERT_EQ(pair.exit_code, 0) << pair.both();
  EXPECT_EQ(json::parse(pair.out)["a_name"], "fleet");
  const auto missing = Fleetmerge("extract " + ShellQuote(dir / "fleet.bag") + " --topic /nope" +
                                  " --out " + ShellQuote(dir / "x"));
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_NE(missing.err.find("/robot1/map, /robot2/map, /robot3/map"), std::string::npos)
      << missing.err;
  EXPECT_FALSE(fs::exists(dir / "x"));
}

// --- One folder per robot ---------------------------------------------------------------------

TEST(RobotFolders, MapSaverLayoutMergesNamedByFolder) {
  const fs::path dir = testing::MakeTempDir("robot_folders");
  const fs::path sim = SimulateFleet(dir);
  std::string folders, files;
  for (int r = 1; r <= 3; ++r) {
    const std::string robot = "robot" + std::to_string(r);
    fs::create_directories(dir / "mission" / ("r" + std::to_string(r)));
    SaveMap(LoadMap(sim / (robot + ".yaml")).grid,
            dir / "mission" / ("r" + std::to_string(r)) / "map.yaml");
    folders += " " + ShellQuote(dir / "mission" / ("r" + std::to_string(r)) / "map.yaml");
    files += " " + ShellQuote(sim / (robot + ".yaml"));
  }
  const auto merged = Fleetmerge("merge --quiet --out " + ShellQuote(dir / "out") + folders);
  ASSERT_EQ(merged.exit_code, 0) << merged.both();
  const json report = ReadJson(dir / "out" / "report.json");
  ASSERT_EQ(report["maps"].size(), 3u);
  for (int r = 0; r < 3; ++r) EXPECT_EQ(report["maps"][r]["name"], "r" + std::to_string(r + 1));
  ASSERT_EQ(Fleetmerge("merge --quiet --out " + ShellQuote(dir / "files") + files).exit_code, 0);
  ExpectSamePoses(dir / "out" / "report.json", dir / "files" / "report.json");
  // pair names them the same way.
  const auto pair = Fleetmerge("pair" + folders.substr(0, folders.rfind(" '")));
  ASSERT_EQ(pair.exit_code, 0) << pair.both();
  EXPECT_NE(pair.out.find("a: r1 ("), std::string::npos) << pair.out;
  EXPECT_NE(pair.out.find("b: r2 ("), std::string::npos) << pair.out;
  // A map paired with itself (a sanity check) is still allowed: one name for both.
  const std::string r1 = ShellQuote(dir / "mission" / "r1" / "map.yaml");
  const auto self = Fleetmerge("pair " + r1 + " " + r1);
  ASSERT_EQ(self.exit_code, 0) << self.both();
  EXPECT_NE(self.out.find("b: map ("), std::string::npos) << self.out;
}

// --- ROS 2 ------------------------------------------------------------------------------------

class Ros2Db3Fleet : public ::testing::TestWithParam<std::string> {};

TEST_P(Ros2Db3Fleet, SimulatedFleetMergesFromBagFolders) {
  const std::string distro = GetParam();
  const fs::path dir = testing::MakeTempDir("ros2_db3_" + distro);
  const fs::path sim = SimulateFleet(dir);
  std::string bags;
  for (int r = 1; r <= 3; ++r) {
    const std::string robot = "robot" + std::to_string(r);
    MakeBag("db3 --distro " + distro + " --map " + ShellQuote(sim / (robot + ".yaml")) + " --out " +
            ShellQuote(dir / robot));
    // The folder for robots 1 and 2, the .db3 file alone for robot 3.
    bags += " " + ShellQuote(r < 3 ? dir / robot : dir / robot / (robot + "_0.db3"));
  }
  const auto merged = Fleetmerge("merge --quiet --out " + ShellQuote(dir / "out") + bags);
  ASSERT_EQ(merged.exit_code, 0) << merged.both();
  ExpectAllPairsCoarse(dir / "out" / "report.json", sim / "truth.yaml");
  ExpectLaunchFilesMatchReport(dir / "out");
  ASSERT_EQ(Fleetmerge("merge --quiet --out " + ShellQuote(dir / "files") + " " +
                       ShellQuote(sim / "robot1.yaml") + " " + ShellQuote(sim / "robot2.yaml") +
                       " " + ShellQuote(sim / "robot3.yaml"))
                .exit_code,
            0);
  ExpectSamePoses(dir / "out" / "report.json", dir / "files" / "report.json");
  const json report = ReadJson(dir / "out" / "report.json");
  EXPECT_EQ(report["maps"][2]["name"], "robot3");  // a bag's file is named by its bag
  EXPECT_EQ(report["maps"][0]["bag"]["type"], "nav_msgs/msg/OccupancyGrid");
  ASSERT_EQ(Fleetmerge("extract " + ShellQuote(dir / "robot1") + " --out " +
                       ShellQuote(dir / "extracted"))
                .exit_code,
            0);
  ExpectSameMap(dir / "extracted" / "robot1.yaml", sim / "robot1.yaml");
}

INSTANTIATE_TEST_SUITE_P(Distros, Ros2Db3Fleet, ::testing::Values("humble", "jazzy"));

TEST(Ros2Db3, MessageCompressionZstdRoundTrip) {
  const fs::path dir = testing::MakeTempDir("ros2_db3_zstd");
  const fs::path sim = SimulateFleet(dir);
  MakeBag("db3 --distro jazzy --message-zstd --map " + ShellQuote(sim / "robot3.yaml") + " --out " +
          ShellQuote(dir / "robot3"));
  const auto run = Fleetmerge("extract " + ShellQuote(dir / "robot3") + " --out " +
                              ShellQuote(dir / "extracted"));
  ASSERT_EQ(run.exit_code, 0) << run.both();
  ExpectSameMap(dir / "extracted" / "robot3.yaml", sim / "robot3.yaml");
}

TEST(Ros2Db3, SplitBagGivesTheLastMapOfAllItsFiles) {
  const fs::path dir = testing::MakeTempDir("ros2_db3_split");
  const fs::path sim = SimulateFleet(dir);
  MakeBag("db3 --split --messages 4 --map " + ShellQuote(sim / "robot1.yaml") + " --out " +
          ShellQuote(dir / "robot1"));
  ASSERT_EQ(
      Fleetmerge("extract " + ShellQuote(dir / "robot1") + " --out " + ShellQuote(dir / "whole"))
          .exit_code,
      0);
  ExpectSameMap(dir / "whole" / "robot1.yaml", sim / "robot1.yaml");
  // The first file alone holds only the earlier, smaller maps (make_bags.py's growing crops).
  const auto first = Fleetmerge("extract " + ShellQuote(dir / "robot1" / "robot1_0.db3") +
                                " --out " + ShellQuote(dir / "first"));
  ASSERT_EQ(first.exit_code, 0) << first.both();
  const LoadedMap early = LoadMap(dir / "first" / "robot1.yaml");
  const LoadedMap full = LoadMap(sim / "robot1.yaml");
  EXPECT_LT(early.grid.width(), full.grid.width());
  EXPECT_LT(early.grid.height(), full.grid.height());
}

// --- Job files --------------------------------------------------------------------------------

TEST(BagJobFiles, EntriesNameBagsAndTheirTopics) {
  const fs::path dir = testing::MakeTempDir("bag_job_file");
  const fs::path sim = SimulateFleet(dir);
  MakeBag("ros1 --out " + ShellQuote(dir / "fleet.bag") + " --map " +
          ShellQuote(sim / "robot1.yaml") + " --topic /robot1/map --map " +
          ShellQuote(sim / "robot2.yaml") + " --topic /robot2/map");
  MakeBag("db3 --map " + ShellQuote(sim / "robot3.yaml") + " --out " + ShellQuote(dir / "r3"));
  testing::WriteFile(dir / "job.yaml",
                     "maps:\n  - {path: fleet.bag, topic: robot2/map, name: second}\n"
                     "  - {path: fleet.bag, topic: /robot1/map}\n  - r3\noutput: out\n"
                     "reference: second\ntf_parent: world\ntf_child: '{name}_map'\n"
                     "name: night--run\n");
  const auto run = Fleetmerge("merge --quiet " + ShellQuote(dir / "job.yaml"));
  ASSERT_EQ(run.exit_code, 0) << run.both();
  const json report = ReadJson(dir / "out" / "report.json");
  ASSERT_EQ(report["maps"].size(), 3u);
  EXPECT_EQ(report["maps"][0]["name"], "second");
  EXPECT_EQ(report["maps"][0]["bag"]["topic"], "/robot2/map");
  EXPECT_EQ(report["maps"][1]["name"], "fleet_robot1_map");  // the bag gives the job two maps
  EXPECT_EQ(report["maps"][2]["name"], "r3");
  EXPECT_EQ(report["maps"][2]["frame"], "r3_map");
  const std::string launch = testing::ReadFile(dir / "out" / "transforms.launch.yaml");
  EXPECT_NE(launch.find("--frame-id world --child-frame-id second_map"), std::string::npos)
      << launch;
  // The job's name goes into the ROS 1 file's XML comment, where "--" may not appear.
  const std::string xml = testing::ReadFile(dir / "out" / "transforms.launch");
  const std::regex comment_re("<!--([\\s\\S]*?)-->");
  int comments = 0;
  for (auto it = std::sregex_iterator(xml.begin(), xml.end(), comment_re);
       it != std::sregex_iterator(); ++it, ++comments) {
    EXPECT_EQ((*it)[1].str().find("--"), std::string::npos) << xml;
  }
  EXPECT_GE(comments, 1) << xml;
  EXPECT_NE(xml.find("night-_run"), std::string::npos) << xml;
  // A name for a bag of several map topics is refused, naming the entry's line.
  testing::WriteFile(dir / "bad.yaml",
                     "maps:\n  - {path: fleet.bag, name: x}\n  - r3\n"
                     "output: out2\n");
  const auto bad = Fleetmerge("merge --quiet " + ShellQuote(dir / "bad.yaml"));
  EXPECT_EQ(bad.exit_code, 1);
  EXPECT_NE(bad.err.find("line 2"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("is given to a bag with 2 map topics"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "out2"));
}

// Checked-in MCAP bags (make_mcap_fixtures.sh: make_mcap.mjs, npm's @mcap/core) of the fleet of
// `fleetmerge simulate --robots 3 --seed 3`, robot1 zstd chunks, robot2 lz4, robot3 uncompressed,
// with the maps they hold and their truth in mcap_sim_seed3/maps.
TEST(Ros2McapFleet, CheckedInBagsMergeAndMatchTheirMaps) {
  const fs::path dir = testing::MakeTempDir("ros2_mcap");
  const fs::path mcap = kBagsDir / "mcap_sim_seed3";
  std::string bags;
  for (int r = 1; r <= 3; ++r) {
    const std::string robot = "robot" + std::to_string(r);
    bags += " " + ShellQuote(mcap / robot);
    ASSERT_EQ(Fleetmerge("extract " + ShellQuote(mcap / robot) + " --out " +
                         ShellQuote(dir / "extracted"))
                  .exit_code,
              0);
    ExpectSameMap(dir / "extracted" / (robot + ".yaml"), mcap / "maps" / (robot + ".yaml"));
  }
  const auto merged = Fleetmerge("merge --quiet --out " + ShellQuote(dir / "out") + bags);
  ASSERT_EQ(merged.exit_code, 0) << merged.both();
  ExpectAllPairsCoarse(dir / "out" / "report.json", mcap / "maps" / "truth.yaml");
  ExpectLaunchFilesMatchReport(dir / "out");
}

// --- Map files: a resolution whose resampled grid cannot exist ------------------------------

TEST(ResampledSize, TinyResolutionBesideANormalMapIsRefusedNamingTheFiles) {
  const fs::path dir = testing::MakeTempDir("resolution_1e-300");
  const std::string pgm = std::string("P5\n4 3\n255\n") + std::string(12, '\xfe');
  const std::string yaml =
      "negate: 0\norigin: [0, 0, 0]\noccupied_thresh: 0.65\nfree_thresh: 0.196\n";
  testing::WriteFile(dir / "a.pgm", pgm);
  testing::WriteFile(dir / "b.pgm", pgm);
  testing::WriteFile(dir / "tiny.yaml", "image: a.pgm\nresolution: 1e-300\n" + yaml);
  testing::WriteFile(dir / "normal.yaml", "image: b.pgm\nresolution: 0.05\n" + yaml);
  for (const std::string& command :
       {"pair " + ShellQuote(dir / "tiny.yaml") + " " + ShellQuote(dir / "normal.yaml") +
            " --out " + ShellQuote(dir / "pair_out"),
        "merge --quiet --out " + ShellQuote(dir / "merge_out") + " " +
            ShellQuote(dir / "tiny.yaml") + " " + ShellQuote(dir / "normal.yaml")}) {
    const auto run = Fleetmerge(command);
    EXPECT_EQ(run.exit_code, 1) << command << "\n" << run.both();
    EXPECT_NE(run.err.find("normal.yaml: its 4 x 3 cells of 0.05 m would become"),
              std::string::npos)
        << run.err;
    EXPECT_NE(run.err.find("that of " + (dir / "tiny.yaml").string()), std::string::npos)
        << run.err;
    EXPECT_EQ(run.err.find("grid size must be"), std::string::npos) << run.err;
  }
  EXPECT_FALSE(fs::exists(dir / "pair_out"));
  EXPECT_FALSE(fs::exists(dir / "merge_out"));
}

}  // namespace
}  // namespace fleetmerge
