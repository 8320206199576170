// The public API's defaults are the command line's, and its maps convert to and from core's
// grids without loss (the installed-package and Python tests compare its results with the CLI).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>

#include "cli/merge_command.hpp"
#include "cli/pair_command.hpp"
#include "fleetmerge/fleetmerge.hpp"
#include "io/folder_lock.hpp"
#include "job/fleet_options.hpp"
#include "tests/support/shared_data.hpp"

namespace {

TEST(Api, OptionDefaultsAreTheCommandLines) {
  const fleetmerge::Options api;
  const fleetmerge::FleetOptions fleet;  // merge's defaults (cli/main.cpp starts from these)
  const fleetmerge::PairCommand pair;
  EXPECT_EQ(api.hypotheses, pair.hypotheses);
  EXPECT_EQ(api.resolution, fleet.resolution_m);
  EXPECT_EQ(api.omega_threshold, fleet.omega_threshold);
  EXPECT_EQ(api.min_overlap_cells, fleet.min_overlap_cells);
  EXPECT_EQ(api.min_wall_agreement, fleet.min_wall_agreement);
  EXPECT_EQ(api.min_bridge_wall_agreement, fleet.min_bridge_wall_agreement);
  EXPECT_EQ(api.fusion, "log-odds");
  EXPECT_EQ(fleet.fusion, fleetmerge::FusionMode::kLogOdds);
  EXPECT_EQ(api.threads, fleet.threads);
  EXPECT_EQ(api.refine, fleet.pair.refine);
  EXPECT_EQ(api.translation, "correlation");
  EXPECT_EQ(fleet.pair.hypotheses.translation.method,
            fleetmerge::TranslationMethod::kCorrelation2D);
  EXPECT_EQ(api.max_map_cells, fleet.max_map_cells);
  EXPECT_EQ(api.octree_band_min, fleet.octree.band_min_m);
  EXPECT_EQ(api.octree_band_max, fleet.octree.band_max_m);
}

TEST(Api, MapChecksItsContract) {
  EXPECT_THROW(fleetmerge::Map({0, 0, 0}, 2, 2, 0.05), std::invalid_argument);  // 3 != 2 x 2
  EXPECT_THROW(fleetmerge::Map({0, 0, 0, 0}, 2, 2, -1.0), std::invalid_argument);
  EXPECT_THROW(fleetmerge::Map({0, 0, 0, 101}, 2, 2, 0.05), std::invalid_argument);
  EXPECT_THROW(fleetmerge::Map({0, 0, 0, 0}, 0, 4, 0.05), std::invalid_argument);
  const fleetmerge::Map map({-1, 0, 50, 100}, 2, 2, 0.05, {1.0, 2.0, 0.5}, "m");
  EXPECT_EQ(map.at(1, 1), 100);
  EXPECT_EQ(map.at(0, 1), 50);
  EXPECT_EQ(map.at(2, 0), -1);  // outside
}

TEST(Api, FixedMapsKeepTheirPose) {
  fleetmerge::Map base({0, 100, 0, 100}, 2, 2, 0.05, {}, "base");
  EXPECT_FALSE(base.fixed());
  EXPECT_THROW(base.set_fixed(true, {0.0, std::nan(""), 0.0}), std::invalid_argument);
  EXPECT_THROW(base.set_fixed(true, {0.0, 0.0, 90.0}), std::invalid_argument);  // degrees
  // A pose without fixed would be ignored: refused, as a job file refuses `pose` alone.
  EXPECT_THROW(base.set_fixed(false, {1.0, 0.0, 0.0}), std::invalid_argument);
  EXPECT_FALSE(base.fixed());  // unchanged by the refused calls
  base.set_fixed(true, {1.5, -2.0, 0.3});
  const fleetmerge::Map robot({100, 0, 100, 0}, 2, 2, 0.05, {}, "robot");
  // Two maps that overlap too little to pair: each its own component; the base keeps its pose.
  const fleetmerge::MergeResult result = fleetmerge::Merge({robot, base});
  ASSERT_EQ(result.maps.size(), 2u);
  EXPECT_EQ(result.maps[1].pose.x, 1.5);
  EXPECT_EQ(result.maps[1].pose.y, -2.0);
  EXPECT_DOUBLE_EQ(result.maps[1].pose.yaw, 0.3);
  EXPECT_EQ(result.components[result.maps[1].component].reference, "base");  // the first fixed
  fleetmerge::Options options;
  options.reference = "robot";
  EXPECT_THROW(fleetmerge::Merge({robot, base}, options), std::invalid_argument);
}

TEST(Api, AMapThatPairsWithNoneIsPlacedAtItsInitialPose) {
  fleetmerge::Map base({0, 100, 0, 100}, 2, 2, 0.05, {}, "base");
  base.set_fixed(true, {1.5, -2.0, 0.3});
  fleetmerge::Map robot({100, 0, 100, 0}, 2, 2, 0.05, {}, "robot");
  EXPECT_FALSE(robot.initial_pose().has_value());
  EXPECT_THROW(robot.set_initial_pose({0.0, 0.0, std::nan("")}), std::invalid_argument);
  EXPECT_THROW(robot.set_initial_pose({0.0, 0.0, 0.0}, -0.5), std::invalid_argument);
  EXPECT_THROW(robot.set_initial_pose({0.0, 0.0, 0.0}, 0.5, 0.0), std::invalid_argument);
  EXPECT_THROW(robot.set_initial_pose({0.0, 0.0, 90.0}), std::invalid_argument);
  EXPECT_THROW(robot.set_initial_pose({0.0, 0.0, 0.0}, 0.5, 10.0), std::invalid_argument);
  EXPECT_FALSE(robot.initial_pose().has_value());  // unchanged by the refused calls
  robot.set_initial_pose({4.0, 1.0, -0.2});
  EXPECT_EQ(robot.initial_pose_sigma_m(), 0.5);  // the documented defaults
  EXPECT_NEAR(robot.initial_pose_sigma_rad(), 10.0 * M_PI / 180.0, 1e-15);
  // Too small to pair: without its prior the robot would be alone; with it, it joins the base's
  // component at its prior, in the base's (the site's) frame.
  const fleetmerge::MergeResult result = fleetmerge::Merge({base, robot});
  ASSERT_EQ(result.maps.size(), 2u);
  EXPECT_EQ(result.maps[0].placed_by, "fixed");
  EXPECT_EQ(result.maps[1].placed_by, "prior");
  EXPECT_EQ(result.maps[1].component, result.maps[0].component);
  EXPECT_NEAR(result.maps[1].pose.x, 4.0, 1e-9);
  EXPECT_NEAR(result.maps[1].pose.y, 1.0, 1e-9);
  EXPECT_NEAR(result.maps[1].pose.yaw, -0.2, 1e-9);
  EXPECT_NE(result.report_json.find("\"placed_by\": \"prior\""), std::string::npos);
  robot.clear_initial_pose();
  const fleetmerge::MergeResult alone = fleetmerge::Merge({base, robot});
  EXPECT_EQ(alone.maps[1].placed_by, "unmerged");
  EXPECT_NE(alone.maps[1].component, alone.maps[0].component);
  // A fixed map has its pose exactly: an initial pose on it is refused.
  base.set_initial_pose({0.0, 0.0, 0.0});
  EXPECT_THROW(fleetmerge::Merge({base, robot}), std::invalid_argument);
}

// MergeFiles takes fixed maps and initial poses by map name, as `merge --fixed` and
// `--initial-pose`; Merge takes them from its Maps and refuses them in Options.
TEST(Api, MapFilesTakeFixedMapsAndInitialPosesByName) {
  const std::filesystem::path dir = fleetmerge::testing::MakeTempDir("api_named_poses");
  fleetmerge::SaveMap(fleetmerge::Map({0, 100, 0, 100}, 2, 2, 0.05, {}, "base"),
                      (dir / "base.yaml").string());
  fleetmerge::SaveMap(fleetmerge::Map({100, 0, 100, 0}, 2, 2, 0.05, {}, "robot"),
                      (dir / "robot.yaml").string());
  const std::vector<std::string> files = {(dir / "base.yaml").string(),
                                          (dir / "robot.yaml").string()};
  fleetmerge::Options options;
  options.fixed["base"] = {1.5, -2.0, 0.3};
  options.initial_poses["robot"] = {{4.0, 1.0, -0.2}, 0.3, 0.1};
  const fleetmerge::MergeResult result = fleetmerge::MergeFiles(files, options);
  ASSERT_EQ(result.maps.size(), 2u);
  EXPECT_EQ(result.maps[0].placed_by, "fixed");
  EXPECT_NEAR(result.maps[0].pose.x, 1.5, 1e-12);
  EXPECT_EQ(result.maps[1].placed_by, "prior");  // too small to pair: at its initial pose
  EXPECT_NEAR(result.maps[1].pose.x, 4.0, 1e-9);
  EXPECT_NEAR(result.maps[1].pose.yaw, -0.2, 1e-9);
  EXPECT_NE(result.report_json.find("\"initial_pose_sigma\": [\n"), std::string::npos);
  const auto refused = [&](const fleetmerge::Options& bad, const std::string& what) {
    try {
      fleetmerge::MergeFiles(files, bad);
      ADD_FAILURE() << "no error for " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  fleetmerge::Options bad = options;
  bad.fixed["robot9"] = {};
  refused(bad, "options.fixed: no map is named 'robot9' (the maps: 'base', 'robot')");
  bad = options;
  bad.initial_poses["base"] = {};
  refused(bad, "map 'base' is in options.fixed and options.initial_poses");
  bad = options;
  bad.initial_poses["robot"].pose.yaw = 90.0;
  refused(bad, "90 rad looks like degrees");
  bad = options;
  bad.reference = "robot";
  refused(bad, "with fixed maps the reference is the first fixed map, 'base'");
  EXPECT_THROW(
      fleetmerge::Merge({fleetmerge::LoadMap(files[0]), fleetmerge::LoadMap(files[1])}, options),
      std::invalid_argument);
}

TEST(Api, EmptyMapAndBadOptionsAreInvalidArguments) {
  const fleetmerge::Map empty;
  const fleetmerge::Map map({0, 100, 0, 100}, 2, 2, 0.05);
  EXPECT_THROW(fleetmerge::Pair(empty, map), std::invalid_argument);
  fleetmerge::Options options;
  options.hypotheses = 0;
  EXPECT_THROW(fleetmerge::Pair(map, map, options), std::invalid_argument);
  options = {};
  options.translation = "fft";
  EXPECT_THROW(fleetmerge::Pair(map, map, options), std::invalid_argument);
  EXPECT_THROW(fleetmerge::Merge({}), std::invalid_argument);
  EXPECT_THROW(fleetmerge::LoadMap("/nonexistent/map.yaml"), std::runtime_error);
}

// Merge with an output folder writes through the CLI's result folder: it waits for another job
// holding the folder's lock (io/folder_lock.hpp) instead of removing that job's staging folder.
TEST(Api, MergeIntoAFolderWaitsForItsLock) {
  namespace fs = std::filesystem;
  const fs::path out = fleetmerge::testing::MakeTempDir("api_lock") / "out";
  std::vector<std::int8_t> cells(40 * 30, 0);  // a free room with walls around it
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      if (x == 0 || y == 0 || x == 39 || y == 29) cells[y * 40 + x] = 100;
    }
  }
  const fleetmerge::Map map(cells, 40, 30, 0.05);
  std::optional<fleetmerge::FolderLock> held(std::in_place, out, "job 'test holder'", 0);
  std::string error;
  std::thread merge([&] {
    try {
      fleetmerge::Merge({map}, {}, out.string());
    } catch (const std::exception& e) {
      error = e.what();
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  EXPECT_FALSE(fs::exists(out)) << "Merge did not wait for the folder's lock";
  held.reset();
  merge.join();
  EXPECT_EQ(error, "");
  EXPECT_TRUE(fs::exists(out / "report.json"));
  EXPECT_TRUE(fs::exists(out / "merged_0.yaml"));
}

}  // namespace
