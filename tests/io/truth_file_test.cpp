// truth.yaml: SaveTruth -> LoadTruth returns the same truth (poses bit-exact), map files are
// resolved against the file's folder, and every malformed file fails with the file, the line and
// the key path.
#include "io/truth_file.hpp"

#include <gtest/gtest.h>

#include <string>

#include "core/error.hpp"
#include "tests/io/io_test_util.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;

GroundTruth SampleTruth() {
  GroundTruth truth;
  truth.seed = 4294967295u;
  truth.buildings = {{"office", "synthetic office seed 7"}, {"foreign", "/maps/intel.yaml"}};
  truth.maps = {{"robot1", "robot1.yaml", "office", 0.05, Pose2(12.3, -4.5, 0.7)},
                {"robot2", "sub/robot2.yaml", "office", 0.1, Pose2(-0.1 / 3, 1e-9, -M_PI / 3)},
                {"other", "other.yaml", "foreign", 0.05, Pose2(0, 0, M_PI)}};
  truth.overlaps = {{"robot1", "robot2", 5321, 0.31}};
  return truth;
}

const std::string kHead =
    "format: fleetmerge-truth-1\nseed: 7\n"
    "buildings:\n  - {name: office, source: synthetic}\n  - {name: lab, source: lab.yaml}\n";
const std::string kMaps =
    "maps:\n"
    "  - {name: r1, file: r1.yaml, building: office, resolution: 0.05, pose: {x: 1, y: 2, yaw: "
    "0.5}}\n"
    "  - {name: r2, file: r2.yaml, building: office, resolution: 0.05, pose: {x: 0, y: 0, yaw: "
    "0}}\n"
    "  - {name: r3, file: r3.yaml, building: lab, resolution: 0.05, pose: {x: 0, y: 0, yaw: 0}}\n";

class TruthFileTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = ft::MakeTempDir("truth_file"); }
  fs::path Write(const std::string& text) const {
    ft::WriteFile(dir_ / "truth.yaml", text);
    return dir_ / "truth.yaml";
  }
  // The message of LoadTruth's error on `text`.
  std::string ErrorOf(const std::string& text) const {
    try {
      LoadTruth(Write(text));
    } catch (const Error& e) {
      return e.what();
    }
    ADD_FAILURE() << "accepted:\n" << text;
    return "";
  }
  fs::path dir_;
};

TEST_F(TruthFileTest, RoundTripIsExact) {
  const GroundTruth truth = SampleTruth();
  SaveTruth(truth, dir_ / "truth.yaml");
  const GroundTruth back = LoadTruth(dir_ / "truth.yaml");
  EXPECT_EQ(back.seed, truth.seed);
  ASSERT_EQ(back.buildings.size(), truth.buildings.size());
  for (std::size_t i = 0; i < truth.buildings.size(); ++i) {
    EXPECT_EQ(back.buildings[i].name, truth.buildings[i].name);
    EXPECT_EQ(back.buildings[i].source, truth.buildings[i].source);
  }
  ASSERT_EQ(back.maps.size(), truth.maps.size());
  for (std::size_t i = 0; i < truth.maps.size(); ++i) {
    const TruthMap &a = truth.maps[i], &b = back.maps[i];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.file, dir_ / a.file);  // resolved against truth.yaml's folder
    EXPECT_EQ(b.building, a.building);
    EXPECT_EQ(b.resolution_m, a.resolution_m);
    EXPECT_EQ(b.T_building_map.x_m(), a.T_building_map.x_m());
    EXPECT_EQ(b.T_building_map.y_m(), a.T_building_map.y_m());
    EXPECT_EQ(b.T_building_map.yaw_rad(), a.T_building_map.yaw_rad());
  }
  ASSERT_EQ(back.overlaps.size(), 1u);
  EXPECT_EQ(back.overlaps[0].a, "robot1");
  EXPECT_EQ(back.overlaps[0].b, "robot2");
  EXPECT_EQ(back.overlaps[0].cells, 5321);
  EXPECT_EQ(back.overlaps[0].share, 0.31);
}

TEST_F(TruthFileTest, AbsoluteMapFilesStayAbsoluteAndOverlapsMayBeAbsent) {
  const GroundTruth truth = LoadTruth(
      Write(kHead + "maps:\n  - {name: r1, file: /data/r1.yaml, building: lab, resolution: 0.1, "
                    "pose: {x: 0, y: 0, yaw: 0}}\n"));
  ASSERT_EQ(truth.maps.size(), 1u);
  EXPECT_EQ(truth.maps[0].file, fs::path("/data/r1.yaml"));
  EXPECT_TRUE(truth.overlaps.empty());
}

TEST_F(TruthFileTest, ValidListedFileLoads) {
  const GroundTruth truth =
      LoadTruth(Write(kHead + kMaps + "overlaps:\n  - {a: r1, b: r2, cells: 10, share: 0.5}\n"));
  EXPECT_EQ(truth.maps.size(), 3u);
  EXPECT_EQ(truth.maps[0].T_building_map.yaw_rad(), 0.5);
  EXPECT_EQ(truth.overlaps.size(), 1u);
}

struct Malformed {
  std::string text;
  std::string expected;  // part of the message after the file name
};

TEST_F(TruthFileTest, MalformedFilesNameFileLineAndKey) {
  const std::string ok_overlap = "overlaps:\n  - {a: r1, b: r2, cells: 10, share: 0.5}\n";
  const std::vector<Malformed> cases = {
      {"format: [\n", "malformed YAML"},
      {"- a\n- b\n", "expected a truth file"},
      {"format: fleetmerge-truth-2\nseed: 1\n" + kHead.substr(kHead.find("buildings")) + kMaps,
       "line 1: key 'format': expected 'fleetmerge-truth-1', got 'fleetmerge-truth-2'"},
      {kHead + kMaps + "extra: 1\n", "key 'extra': unknown key; allowed here: format, seed"},
      {kHead, "key 'maps': missing: expected a non-empty list of maps"},
      {kHead + "maps: []\n", "key 'maps': expected a non-empty list of maps"},
      {"format: fleetmerge-truth-1\nseed: -1\nbuildings: []\n" + kMaps,
       "line 2: key 'seed': expected an integer in [0, 4294967295], got '-1'"},
      {"format: fleetmerge-truth-1\nseed: 1\nbuildings:\n  - {name: a}\n",
       "line 4: key 'buildings[0].source': missing"},
      {"format: fleetmerge-truth-1\nseed: 1\nbuildings:\n  - {name: a, source: x}\n  - {name: a, "
       "source: y}\n",
       "line 5: key 'buildings[1]': building name 'a' appears twice (first at line 4)"},
      {kHead + kMaps +
           "  - {name: r1, file: x.yaml, building: lab, resolution: 0.05, pose: {x: "
           "0, y: 0, yaw: 0}}\n",
       "line 10: key 'maps[3]': map name 'r1' appears twice (first at line 7)"},
      {kHead + "maps:\n  - {name: r1, file: r1.yaml, building: garage, resolution: 0.05, pose: "
               "{x: 0, y: 0, yaw: 0}}\n",
       "line 7: key 'maps[0].building': expected the name of a building listed under "
       "'buildings', got 'garage'"},
      {kHead + "maps:\n  - {name: r1, file: r1.yaml, building: lab, resolution: 0, pose: {x: 0, "
               "y: 0, yaw: 0}}\n",
       "key 'maps[0].resolution': expected a number > 0, got '0'"},
      {kHead + "maps:\n  - {name: r1, file: r1.yaml, building: lab, resolution: 0.05, pose: {x: "
               ".nan, y: 0, yaw: 0}}\n",
       "key 'maps[0].pose.x': expected a finite number (metres), got '.nan'"},
      {kHead + "maps:\n  - {name: r1, file: r1.yaml, building: lab, resolution: 0.05, pose: {x: "
               "0, y: -.inf, yaw: 0}}\n",
       "key 'maps[0].pose.y': expected a finite number (metres), got '-.inf'"},
      {kHead + "maps:\n  - {name: r1, file: r1.yaml, building: lab, resolution: 0.05, pose: {x: "
               "0, y: 0, yaw: \"1\"}}\n",
       "key 'maps[0].pose.yaw': expected a finite number (radians), got '1' (quoted, so a "
       "string)"},
      {kHead + "maps:\n  - {name: r1, file: r1.yaml, building: lab, resolution: 0.05, pose: {x: "
               "0, y: 0}}\n",
       "key 'maps[0].pose.yaw': missing: expected radians"},
      {kHead + "maps:\n  - {name: r1, file: r1.yaml, building: lab, resolution: 0.05, pose: {x: "
               "0, y: 0, yaw: 0, z: 1}}\n",
       "key 'maps[0].pose.z': unknown key"},
      {kHead + "maps:\n  - {name: r1, building: lab, resolution: 0.05, pose: {x: 0, y: 0, yaw: "
               "0}}\n",
       "key 'maps[0].file': missing: expected the map's YAML file"},
      {kHead + kMaps + "overlaps:\n  - {a: r1, b: r9, cells: 10, share: 0.5}\n",
       "line 11: key 'overlaps[0].b': expected the name of a map listed under 'maps', got 'r9'"},
      {kHead + kMaps + "overlaps:\n  - {a: r2, b: r1, cells: 10, share: 0.5}\n",
       "key 'overlaps[0].b': expected a map listed after 'r2' under 'maps' (a before b), got 'r1'"},
      {kHead + kMaps + "overlaps:\n  - {a: r1, b: r3, cells: 10, share: 0.5}\n",
       "key 'overlaps[0].b': 'r1' and 'r3' are maps of different buildings"},
      {kHead + kMaps + "overlaps:\n  - {a: r1, b: r2, cells: 1.5, share: 0.5}\n",
       "key 'overlaps[0].cells': expected an integer"},
      {kHead + kMaps + "overlaps:\n  - {a: r1, b: r2, cells: 10, share: 1.5}\n",
       "key 'overlaps[0].share': expected a number in [0, 1], got '1.5'"},
      {kHead + kMaps + ok_overlap + "  - {a: r1, b: r2, cells: 11, share: 0.5}\n",
       "line 12: key 'overlaps[1]': the pair 'r1', 'r2' appears twice (first at line 11)"},
      {kHead + kMaps + "overlaps: {a: r1}\n", "key 'overlaps': expected a list of overlaps"},
  };
  for (const Malformed& c : cases) {
    const std::string message = ErrorOf(c.text);
    EXPECT_TRUE(ft::StartsWith(message, (dir_ / "truth.yaml").string() + ": ")) << c.text;
    EXPECT_TRUE(ft::Contains(message, c.expected)) << c.text;
  }
}

TEST_F(TruthFileTest, MissingFileAndFolderAreErrors) {
  EXPECT_TRUE(ft::Contains(
      [&] {
        try {
          LoadTruth(dir_ / "absent.yaml");
        } catch (const Error& e) {
          return std::string(e.what());
        }
        return std::string();
      }(),
      "absent.yaml: cannot open truth file"));
  EXPECT_THROW(LoadTruth(dir_), Error);
}

}  // namespace
}  // namespace fleetmerge
