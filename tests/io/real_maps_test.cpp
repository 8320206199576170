// Loads every real map in ../shared/data/maps and checks it against SOURCES.md.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/map_io.hpp"
#include "tests/io/io_test_util.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;

struct RealMap {
  const char* name;  // YAML stem
  const char* image;
  int width;
  int height;
  double resolution_m;
};

// Sizes (cells, W x H) and resolutions as listed in SOURCES.md.
const std::vector<RealMap>& RealMaps() {
  static const std::vector<RealMap> maps = {
      {"aces3_austin", "aces3_austin.pgm", 1129, 1134, 0.05},
      {"bookstore_tb3", "bookstore_tb3.pgm", 384, 384, 0.05},
      {"gdc_floor1_full", "gdc_floor1_full.pgm", 1857, 1255, 0.05},
      {"gdc_floor2_full", "gdc_floor2_full.pgm", 1800, 1400, 0.05},
      {"intel_lab", "intel_lab.pgm", 888, 848, 0.05},
      {"intel_lab_10cm_grey", "intel_lab_10cm_grey.pgm", 579, 581, 0.1},
      {"lab_pair_demo_1", "lab_pair_demo_1.pgm", 380, 500, 0.05},
      {"lab_pair_demo_2", "lab_pair_demo_2.pgm", 500, 440, 0.05},
      {"mit_building_31", "mit_building_31.png", 693, 648, 0.05},
      {"mit_csail", "mit_csail.pgm", 1597, 1208, 0.05},
      {"nav2_depot", "nav2_depot.pgm", 604, 307, 0.05},
      {"nav2_warehouse", "nav2_warehouse.pgm", 1006, 1674, 0.03},
      {"office_raw_rplidarA3", "office_raw_rplidarA3.pgm", 384, 384, 0.05},
      {"robotis_corridor_run1", "robotis_corridor_run1.pgm", 384, 384, 0.05},
      {"robotis_corridor_run2", "robotis_corridor_run2.pgm", 384, 384, 0.05},
      {"robotis_corridor_run3", "robotis_corridor_run3.pgm", 384, 384, 0.05},
      {"robotis_corridor_run4", "robotis_corridor_run4.pgm", 384, 384, 0.05},
      {"robotis_corridor_run5", "robotis_corridor_run5.pgm", 384, 384, 0.05},
      {"robotis_corridor_run6", "robotis_corridor_run6.pgm", 384, 384, 0.05},
      {"robotis_maze_arena_2017", "robotis_maze_arena_2017.pgm", 384, 384, 0.05},
      {"stata_basement", "stata_basement.png", 1730, 1300, 0.0504},
      {"turtlebot3_world_sim", "turtlebot3_world_sim.pgm", 384, 384, 0.05},
      {"warehouse_002", "warehouse_002.pgm", 1536, 1504, 0.02},
      {"willow-full-0.05", "willow-full-0.05.pgm", 1165, 945, 0.05},
      {"willow-full-0.10", "willow-full-0.10.pgm", 584, 526, 0.1},
  };
  return maps;
}

TEST(RealMapsTest, TableMatchesSourcesMdAndTheFolder) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path dir = *ft::SharedMapsDir();
  const std::string sources = ft::ReadFile(dir / "SOURCES.md");
  std::set<std::string> yaml_stems;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() == ".yaml") yaml_stems.insert(entry.path().stem().string());
  }
  EXPECT_EQ(yaml_stems.size(), 25u);
  EXPECT_EQ(RealMaps().size(), 25u);
  for (const RealMap& map : RealMaps()) {
    const std::string row = "| " + std::string(map.image) + " | " + std::to_string(map.width) +
                            "x" + std::to_string(map.height) + " |";
    EXPECT_NE(sources.find(row), std::string::npos) << "SOURCES.md has no row starting " << row;
    EXPECT_EQ(yaml_stems.count(map.name), 1u) << map.name;
  }
}

TEST(RealMapsTest, EveryMapLoadsWithListedSizeAndHasOccupiedAndFreeCells) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path dir = *ft::SharedMapsDir();
  for (const RealMap& expected : RealMaps()) {
    SCOPED_TRACE(expected.name);
    LoadedMap map;
    ASSERT_NO_THROW(map = LoadMap(dir / (std::string(expected.name) + ".yaml")));
    EXPECT_EQ(map.metadata.image_path.filename(), expected.image);
    EXPECT_EQ(map.grid.width(), expected.width);
    EXPECT_EQ(map.grid.height(), expected.height);
    EXPECT_DOUBLE_EQ(map.grid.geometry().resolution_m(), expected.resolution_m);
    const int occupied = map.grid.Count(CellState::kOccupied);
    const int free = map.grid.Count(CellState::kFree);
    const int unknown = map.grid.Count(CellState::kUnknown);
    EXPECT_GT(occupied, 0);
    EXPECT_GT(free, 0);
    EXPECT_EQ(occupied + free + unknown, expected.width * expected.height);
    std::cout << "[ counts   ] " << expected.name << ": occupied " << occupied << ", free " << free
              << ", unknown " << unknown << "\n";
  }
}

TEST(RealMapsTest, IntelLabSizeAndOrigin) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const LoadedMap map = LoadMap(*ft::SharedMapsDir() / "intel_lab.yaml");
  EXPECT_EQ(map.grid.width(), 888);
  EXPECT_EQ(map.grid.height(), 848);
  EXPECT_EQ(map.grid.geometry().T_map_grid().translation_m(), Eigen::Vector2d::Zero());
}

TEST(RealMapsTest, StataBasementHasRotatedOrigin) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const LoadedMap map = LoadMap(*ft::SharedMapsDir() / "stata_basement.yaml");
  const Pose2& origin = map.grid.geometry().T_map_grid();
  EXPECT_NEAR(origin.yaw_rad(), 3.14, 1e-12);
  EXPECT_DOUBLE_EQ(origin.x_m(), 25.9);
  EXPECT_DOUBLE_EQ(origin.y_m(), 48.5);
  EXPECT_DOUBLE_EQ(map.grid.geometry().resolution_m(), 0.0504);
}

TEST(RealMapsTest, ThresholdsAndModeFromTheYamlAreUsed) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const LoadedMap grey = LoadMap(*ft::SharedMapsDir() / "intel_lab_10cm_grey.yaml");
  EXPECT_DOUBLE_EQ(grey.metadata.occupied_thresh, 0.2);
  EXPECT_DOUBLE_EQ(grey.metadata.free_thresh, 0.05);
  const LoadedMap depot = LoadMap(*ft::SharedMapsDir() / "nav2_depot.yaml");
  EXPECT_EQ(depot.metadata.mode, MapMode::kTrinary);
  EXPECT_DOUBLE_EQ(depot.metadata.free_thresh, 0.25);
}

TEST(RealMapsTest, RealMapsRoundTrip) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path out = ft::MakeTempDir("real_maps_round_trip");
  for (const char* name : {"stata_basement", "intel_lab_10cm_grey", "nav2_depot"}) {
    SCOPED_TRACE(name);
    const fs::path input = *ft::SharedMapsDir() / (std::string(name) + ".yaml");
    const LoadedMap original = LoadMap(input);
    SaveMap(original.grid, out / (std::string(name) + ".yaml"),
            {input, original.metadata.image_path});
    const LoadedMap copy = LoadMap(out / (std::string(name) + ".yaml"));
    EXPECT_EQ(cv::countNonZero(copy.grid.cells() != original.grid.cells()), 0);
    EXPECT_EQ(copy.grid.geometry().T_map_grid().yaw_rad(),
              original.grid.geometry().T_map_grid().yaw_rad());
    EXPECT_EQ(copy.grid.geometry().resolution_m(), original.grid.geometry().resolution_m());
  }
}

TEST(RealMapsTest, SavingOverARealMapIsRefused) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const fs::path input = *ft::SharedMapsDir() / "nav2_depot.yaml";
  const LoadedMap map = LoadMap(input);
  EXPECT_THROW(SaveMap(map.grid, input, {input, map.metadata.image_path}), Error);
}

}  // namespace
}  // namespace fleetmerge
