// The result set as ROS tools see it (issue 21): `fleetmerge merge` runs as a user runs it, then
//   - merged_bag/ is read by merged_bag_check.mjs (npm's @mcap/core, @foxglove/rosmsg2-
//     serialization, yaml: readers fleetmerge did not write), which compares each map topic's
//     cells with merged_<c>.pgm and /tf_static with report.json's poses;
//   - merged_bag/ is read back through fleetmerge's own ROS 2 bag reader (io/bag_maps.hpp), as a
//     user merging the bag again would, and equals merged_<c>.yaml;
//   - transforms.launch is loaded by ROS 1's roslaunch (ros1_launch_check.py, Debian's
//     python3-roslaunch) and its nodes compared with report.json.
// The node_modules (npm ci in tests/rosbag) and python3-roslaunch come from
// scripts/install_deps.sh; without them the tests fail saying so.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/bag_maps.hpp"
#include "io/map_io.hpp"
#include "tests/support/fleetmerge_cli.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::Fleetmerge;
using testing::RunCommand;
using testing::ShellQuote;

const fs::path kHere = fs::path(FLEETMERGE_SOURCE_DIR) / "tests" / "rosbag";

json ReadReport(const fs::path& out) {
  std::ifstream in(out / "report.json");
  return json::parse(in);
}

// Merges `maps` into `out`; returns the report.
json Merge(const fs::path& out, const std::vector<fs::path>& maps) {
  std::string words;
  for (const fs::path& map : maps) words += " " + ShellQuote(map);
  const auto run = Fleetmerge("merge --quiet --out " + ShellQuote(out) + words);
  EXPECT_EQ(run.exit_code, 0) << run.both();
  return ReadReport(out);
}

int MergedMaps(const json& report) {
  int n = 0;
  for (const json& c : report.at("components")) n += c.contains("merged_map") ? 1 : 0;
  return n;
}

// The three readers' verdicts on one result set.
void ExpectRosToolsAgree(const fs::path& out) {
  ASSERT_TRUE(fs::is_directory(kHere / "node_modules"))
      << kHere / "node_modules"
      << " is missing: run scripts/install_deps.sh (npm ci there)";
  const auto bag =
      RunCommand("node " + ShellQuote(kHere / "merged_bag_check.mjs") + " " + ShellQuote(out));
  EXPECT_EQ(bag.exit_code, 0) << bag.both();
  EXPECT_NE(bag.out.find("merged_bag_check: OK"), std::string::npos) << bag.both();

  const auto launch = RunCommand("/usr/bin/python3 " + ShellQuote(kHere / "ros1_launch_check.py") +
                                 " " + ShellQuote(out));
  EXPECT_EQ(launch.exit_code, 0) << launch.both()
                                 << "\n(python3-roslaunch comes from scripts/install_deps.sh)";
  EXPECT_NE(launch.out.find("ros1_launch_check: OK"), std::string::npos) << launch.both();

  // fleetmerge's own ROS 2 bag reader gives each merged map back, cell for cell.
  const json report = ReadReport(out);
  const fs::path bag_folder = out / "merged_bag";
  std::vector<std::string> expected_topics;
  for (std::size_t c = 0; c < report["components"].size(); ++c) {
    const json& component = report["components"][c];
    if (!component.contains("merged_map")) continue;
    const std::string topic = c == 0 ? "/map" : "/merged_" + std::to_string(c) + "/map";
    expected_topics.push_back(topic);
    const LoadedMap from_bag = LoadBagMap(bag_folder, topic);
    const LoadedMap from_file = LoadMap(out / component["merged_map"].get<std::string>());
    ASSERT_TRUE(from_bag.bag.has_value());
    EXPECT_EQ(from_bag.bag->frame_id, component["frame"].get<std::string>());
    EXPECT_EQ(from_bag.grid.width(), from_file.grid.width());
    ASSERT_EQ(from_bag.grid.height(), from_file.grid.height());
    EXPECT_EQ(cv::countNonZero(from_bag.grid.cells() != from_file.grid.cells()), 0) << topic;
    EXPECT_EQ(from_bag.grid.geometry().resolution_m(), from_file.grid.geometry().resolution_m());
  }
  if (expected_topics.empty()) {
    EXPECT_THROW(BagMapTopics(bag_folder), Error) << "no OccupancyGrid topic in the bag";
  } else {
    std::sort(expected_topics.begin(), expected_topics.end());
    EXPECT_EQ(BagMapTopics(bag_folder), expected_topics);
  }
}

class ResultSetRosTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new fs::path(testing::MakeTempDir("result_set_ros"));
    for (const char* seed : {"1", "2"}) {
      const auto run = Fleetmerge("example " + ShellQuote(*dir_ / ("seed" + std::string(seed))) +
                                  " --seed " + seed);
      ASSERT_EQ(run.exit_code, 0) << run.both();
    }
    // Seed 2's building under names of its own (their YAMLs still name robot_a/b.pgm).
    for (const char* robot : {"a", "b"}) {
      const fs::path from = *dir_ / "seed2" / ("robot_" + std::string(robot) + ".yaml");
      fs::copy_file(from, *dir_ / "seed2" / ("other_" + std::string(robot) + ".yaml"),
                    fs::copy_options::overwrite_existing);
    }
  }
  static fs::path Map(const char* seed, const char* name) {
    return *dir_ / seed / (std::string(name) + ".yaml");
  }
  static fs::path* dir_;
};
fs::path* ResultSetRosTest::dir_ = nullptr;

TEST_F(ResultSetRosTest, TwoBuildingsGiveMapAndMerged1Map) {
  const fs::path out = *dir_ / "two_buildings";
  const json report = Merge(out, {Map("seed1", "robot_a"), Map("seed1", "robot_b"),
                                  Map("seed2", "other_a"), Map("seed2", "other_b")});
  ASSERT_EQ(MergedMaps(report), 2) << report.dump(1) << "\n(the case needs two merged maps)";
  ExpectRosToolsAgree(out);
}

TEST_F(ResultSetRosTest, NothingMergedGivesTfStaticOnly) {
  const fs::path out = *dir_ / "nothing_merged";
  const json report = Merge(out, {Map("seed1", "robot_a"), Map("seed2", "other_a")});
  ASSERT_EQ(MergedMaps(report), 0) << report.dump(1) << "\n(the case needs nothing merged)";
  ExpectRosToolsAgree(out);
}

TEST_F(ResultSetRosTest, RealCorridorRunsAndAnotherBuilding) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path maps = *testing::SharedMapsDir();
  const fs::path out = *dir_ / "real";
  const json report =
      Merge(out, {maps / "robotis_corridor_run1.yaml", maps / "robotis_corridor_run2.yaml",
                  maps / "robotis_corridor_run3.yaml", maps / "robotis_corridor_run4.yaml",
                  maps / "intel_lab.yaml"});
  ASSERT_GE(MergedMaps(report), 1) << report.dump(1);
  ExpectRosToolsAgree(out);
}

}  // namespace
}  // namespace fleetmerge
