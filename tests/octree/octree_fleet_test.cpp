// Octrees through the whole `fleetmerge merge` flow (job file, loading, projection, the 2-D
// pipeline, vertical offsets, merged_<c>.bt, report.json), against ground truth: a synthetic
// office extruded to 3-D (octree/synthetic_octree.hpp), cut into two overlapping robot maps
// (CutPair: 45-70 % overlap), the second moved by a seeded random (x, y, yaw), each given a
// random z. Extruding a cut, re-framed floor plan equals cutting and moving the 3-D building with
// nearest-voxel resampling, since the motion's rotation is about z only.
//
// The 3-D route must also give exactly the 2-D pipeline's answer. (Before hypotheses below
// min_overlap_cells were ranked last, a 200-cell overlap with omega 1.0 could outrank the true
// alignment of a synthetic office; all 5 pairs must now be found.)
#include <gtest/gtest.h>
#include <octomap/OcTree.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "cli/example_command.hpp"
#include "cli/merge_command.hpp"
#include "core/error.hpp"
#include "io/job_file.hpp"
#include "io/map_io.hpp"
#include "io/octree_io.hpp"
#include "octree/synthetic_octree.hpp"
#include "pipeline/fleet_merge.hpp"
#include "sim/ground_truth_pair.hpp"
#include "sim/synthetic_office.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kResolution_m = 0.1;

struct Fleet3d {
  OccupancyGrid building;
  GroundTruthFleet fleet;   // 2-D parts and their (x, y, yaw) in the building
  std::vector<double> z_m;  // each part's frame height in the building (floor at z = 0)
};

Fleet3d MakeFleet(std::uint32_t seed) {
  OfficeOptions office;
  office.width_m = 20.0;
  office.height_m = 14.0;
  office.resolution_m = kResolution_m;
  office.wall_thickness_m = 0.2;
  Fleet3d f{GenerateOfficeFloor(office, seed), {}, {}};
  std::mt19937 rng(seed);
  const double yaw_rad = std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
  const GroundTruthPair pair = CutPair(f.building, yaw_rad, rng, CutPairOptions{0.45, 0.7, 20.0});
  f.fleet.maps = {pair.a, pair.b};
  f.fleet.T_building_map = {Pose2(), pair.T_a_b};
  std::uniform_real_distribution<double> z(-1.5, 1.5);
  f.z_m = {z(rng), z(rng)};
  return f;
}

// Part k as robot k's octree: its floor at -z_k in its own frame.
std::unique_ptr<octomap::OcTree> PartOctree(const Fleet3d& f, int k) {
  ExtrudeOptions options;
  options.floor_z_m = -f.z_m[k];
  options.wall_height_m = 2.2;
  return ExtrudeFloorPlan(f.fleet.maps[k], options);
}

json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  return json::parse(in);
}

std::vector<Job> WriteJobFile(const fs::path& dir, const std::string& text) {
  std::ofstream(dir / "job.yaml") << text;
  return LoadJobFile(dir / "job.yaml");
}

int RunMergeJobs(const std::vector<Job>& jobs, std::string* messages = nullptr) {
  std::ostringstream out, err;
  const int code = RunJobs(jobs, /*quiet=*/true, out, err);
  if (messages) *messages = out.str() + err.str();
  return code;
}

Pose2 PoseOf(const json& map) {
  return Pose2(map["pose"]["x"].get<double>(), map["pose"]["y"].get<double>(),
               map["pose"]["yaw"].get<double>());
}

// Relative (x, y, yaw) of every pair within 1 degree and 3 cells, relative z within one voxel.
void ExpectPosesMatchTruth(const Fleet3d& f, const json& report, bool has_z_for_all) {
  const int n = static_cast<int>(f.fleet.maps.size());
  for (int a = 0; a < n; ++a) {
    for (int b = a + 1; b < n; ++b) {
      const json &ma = report["maps"][a], &mb = report["maps"][b];
      ASSERT_EQ(ma["component"], mb["component"]) << a << "-" << b;
      const Pose2 estimate = PoseOf(ma).inverse() * PoseOf(mb);
      const Pose2 truth = f.fleet.T_building_map[a].inverse() * f.fleet.T_building_map[b];
      const PoseError e = ComparePoses(f.fleet.maps[b], estimate, truth);
      EXPECT_LE(e.yaw_deg, 1.0) << a << "-" << b;
      EXPECT_LE(e.mean_displacement_cells, 3.0) << a << "-" << b;
      if (!has_z_for_all) continue;
      const double dz = mb["pose"]["z"].get<double>() - ma["pose"]["z"].get<double>();
      EXPECT_LE(std::abs(dz - (f.z_m[b] - f.z_m[a])), kResolution_m) << a << "-" << b;
    }
  }
}

// The merged octree (frame of map `reference`, z = 0 at that map's frame height) seen at 1 m
// above the floor and in the floor slab, at the building's cells that some robot saw: walls
// occupied, rooms free, and one floor slab (a floor stacked at another height would put
// occupied voxels in the rooms).
// `octree_maps`: the maps that are octrees (only they fill the merged octree).
void ExpectMergedOctreeIsTheBuilding(const Fleet3d& f, const octomap::OcTree& merged, int reference,
                                     double reference_z_m, const std::vector<int>& octree_maps) {
  const Pose2 T_ref_building = f.fleet.T_building_map[reference].inverse();
  const double floor_z = -(f.z_m[reference] - reference_z_m);  // building floor, merged frame
  int walls = 0, walls_ok = 0, rooms = 0, rooms_ok = 0, slab_ok = 0;
  const OccupancyGrid& b = f.building;
  for (int j = 0; j < b.height(); j += 2) {
    for (int i = 0; i < b.width(); i += 2) {
      const CellState state = b.at({i, j});
      if (state == CellState::kUnknown) continue;
      const Eigen::Vector2d p_building = b.geometry().CellCenter({i, j});
      bool seen = false;
      for (int k : octree_maps) {
        const OccupancyGrid& part = f.fleet.maps[k];
        const Eigen::Vector2d p = f.fleet.T_building_map[k].inverse() * p_building;
        seen = seen || part.StateOrUnknown(part.geometry().CellOf(p)) != CellState::kUnknown;
      }
      if (!seen) continue;
      const Eigen::Vector2d p = T_ref_building * p_building;
      const octomap::OcTreeNode* at_1m = merged.search(p.x(), p.y(), floor_z + 1.0);
      const octomap::OcTreeNode* in_slab = merged.search(p.x(), p.y(), floor_z - 0.05);
      const bool occupied = at_1m != nullptr && merged.isNodeOccupied(at_1m);
      if (state == CellState::kOccupied) {
        ++walls;
        walls_ok += occupied;
      } else {
        ++rooms;
        rooms_ok += at_1m != nullptr && !occupied;
      }
      slab_ok += in_slab != nullptr && merged.isNodeOccupied(in_slab);
    }
  }
  ASSERT_GT(walls, 300);
  ASSERT_GT(rooms, 3000);
  // Cells on a wall's edge may land a voxel off after two nearest-neighbour resamplings.
  EXPECT_GE(walls_ok, 0.9 * walls) << walls_ok << " of " << walls;
  EXPECT_GE(rooms_ok, 0.97 * rooms) << rooms_ok << " of " << rooms;
  EXPECT_GE(slab_ok, 0.97 * (walls + rooms)) << slab_ok << " of " << walls + rooms;
}

bool WithinTolerance(const Fleet3d& f, const Pose2& T_a_b) {
  const PoseError e = ComparePoses(f.fleet.maps[1], T_a_b, f.fleet.T_building_map[1]);
  return e.yaw_deg <= 1.0 && e.mean_displacement_cells <= 3.0;
}

TEST(OctreeFleet, TwoOctreesMergeToTheirTruePosesAndOneBuilding) {
  int true_poses = 0;
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const fs::path dir = testing::MakeTempDir("octree_fleet_" + std::to_string(seed));
    const Fleet3d f = MakeFleet(seed);
    // Odd seeds write the second robot in the full format: both kinds go through one job.
    const std::string b_file = seed % 2 ? "robot_b.ot" : "robot_b.bt";
    SaveOctree(*PartOctree(f, 0), dir / "robot_a.bt");
    SaveOctree(*PartOctree(f, 1), dir / b_file);
    const auto jobs = WriteJobFile(dir, "maps: [robot_a.bt, " + b_file + "]\noutput: out\n");
    std::string messages;
    ASSERT_EQ(RunMergeJobs(jobs, &messages), 0) << messages;
    const json report = ReadJson(dir / "out/report.json");

    // Each octree's floor, whatever the 2-D pipeline finds.
    EXPECT_NEAR(report["maps"][1]["floor_z"].get<double>(), -f.z_m[1], kResolution_m);
    EXPECT_EQ(report["maps"][0]["pose"]["z"], 0.0) << "the reference octree is z = 0";

    const FleetResult flat =
        MergeFleet({&f.fleet.maps[0], &f.fleet.maps[1]}, 0, jobs[0].options);  // 2-D only
    const Pose2 T_flat = flat.T_component_map[0].inverse() * flat.T_component_map[1];
    if (!WithinTolerance(f, T_flat)) {  // the 2-D pipeline's miss: the same answer in 3-D
      const Pose2 T_3d = PoseOf(report["maps"][1]);
      EXPECT_NEAR(T_3d.x_m(), T_flat.x_m(), 1e-6);
      EXPECT_NEAR(T_3d.yaw_rad(), T_flat.yaw_rad(), 1e-9);
      EXPECT_EQ(report["components"].size(), flat.components.size());
      continue;
    }
    ++true_poses;
    ASSERT_EQ(report["components"].size(), 1u) << report.dump(1);
    ExpectPosesMatchTruth(f, report, /*has_z_for_all=*/true);
    EXPECT_EQ(report["components"][0]["merged_octree"], "merged_0.bt");
    EXPECT_EQ(report["components"][0]["merged_map"], "merged_0.yaml");
    EXPECT_TRUE(report["timing_ms"].contains("octree_projection"));
    const auto merged = LoadOctree(dir / "out/merged_0.bt");
    ExpectMergedOctreeIsTheBuilding(f, *merged, 0, 0.0, {0, 1});
  }
  std::printf("[ octree ] true poses for %d of 5 synthetic pairs\n", true_poses);
  EXPECT_EQ(true_poses, 5);
}

// A fixed octree (a site's 3-D map) keeps every voxel in the merged .bt as it is, also where the
// robot's octree saw the same walls (fused, their log-odds would add up); the robot fills the rest.
TEST(OctreeFleet, AFixedOctreeKeepsItsVoxelsInTheMergedOctree) {
  const fs::path dir = testing::MakeTempDir("octree_fleet_fixed");
  const Fleet3d f = MakeFleet(1);
  const auto site = PartOctree(f, 0);
  const auto robot = PartOctree(f, 1);
  SaveOctree(*site, dir / "site.bt");
  SaveOctree(*robot, dir / "robot.bt");
  const auto jobs =
      WriteJobFile(dir, "maps:\n  - {path: site.bt, fixed: true}\n  - robot.bt\noutput: out\n");
  std::string messages;
  ASSERT_EQ(RunMergeJobs(jobs, &messages), 0) << messages;
  const json report = ReadJson(dir / "out/report.json");
  ASSERT_EQ(report["components"].size(), 1u) << report.dump(1);
  ExpectPosesMatchTruth(f, report, /*has_z_for_all=*/true);
  const auto merged = LoadOctree(dir / "out/merged_0.bt");
  ASSERT_DOUBLE_EQ(merged->getResolution(), site->getResolution());
  // The robot's voxels in the merged frame, to count the site's voxels it saw too.
  const Pose2 T_robot_merged = PoseOf(report["maps"][1]).inverse();
  const double robot_z_m = report["maps"][1]["pose"]["z"].get<double>();
  int kept = 0, robot_too = 0;
  for (auto it = site->begin_leafs(); it != site->end_leafs(); ++it) {
    const octomap::point3d p = it.getCoordinate();
    const octomap::OcTreeNode* node = merged->search(p);
    ASSERT_NE(node, nullptr) << p;
    ASSERT_FLOAT_EQ(node->getLogOdds(), it->getLogOdds()) << p;
    ++kept;
    const Eigen::Vector2d q = T_robot_merged * Eigen::Vector2d(p.x(), p.y());
    robot_too += robot->search(q.x(), q.y(), p.z() - robot_z_m) != nullptr;
  }
  EXPECT_GT(kept, 1000);
  EXPECT_GT(robot_too, 1000);               // not vacuous: the two octrees overlap
  EXPECT_GT(merged->size(), site->size());  // and the robot's own voxels were added
}

TEST(OctreeFleet, MixedJobOfA2dMapAndAnOctreeOfOneBuilding) {
  const fs::path dir = testing::MakeTempDir("octree_fleet_mixed");
  const Fleet3d f = MakeFleet(1);
  SaveMap(f.fleet.maps[0], dir / "lidar2d.yaml");
  SaveOctree(*PartOctree(f, 1), dir / "drone.bt");
  // The 2-D map is the reference: the merged octree's z = 0 is then the octree's own frame.
  const auto jobs = WriteJobFile(dir,
                                 "maps: [lidar2d.yaml, {path: drone.bt, name: drone}]\n"
                                 "output: out\noctree: {band_min_m: 0.4, band_max_m: 1.6}\n");
  ASSERT_DOUBLE_EQ(jobs[0].options.octree.band_min_m, 0.4);
  std::string messages;
  ASSERT_EQ(RunMergeJobs(jobs, &messages), 0) << messages;

  const json report = ReadJson(dir / "out/report.json");
  ASSERT_EQ(report["components"].size(), 1u) << report.dump(1);
  ExpectPosesMatchTruth(f, report, /*has_z_for_all=*/false);
  EXPECT_FALSE(report["maps"][0]["pose"].contains("z")) << "a 2-D map has no z";
  EXPECT_EQ(report["maps"][1]["pose"]["z"], 0.0);
  EXPECT_EQ(report["maps"][1]["name"], "drone");
  const auto merged = LoadOctree(dir / "out/merged_0.bt");
  // The merged frame is the 2-D map's (x, y) and the octree's z: check it against robot 0's frame.
  Fleet3d moved = f;
  moved.z_m[0] = f.z_m[1];  // the merged frame's z is the drone's
  ExpectMergedOctreeIsTheBuilding(moved, *merged, 0, 0.0, {1});

  // The same maps with `fleetmerge merge --out` and a band from the command line.
  MergeCommand command;
  command.inputs = {dir / "lidar2d.yaml", dir / "drone.bt"};
  command.out_dir = dir / "cli";
  command.quiet = true;
  command.options.octree.band_min_m = 0.5;
  std::ostringstream cli_out, cli_err;
  ASSERT_EQ(RunMergeCommand(command, cli_out, cli_err), 0) << cli_err.str();
  const json cli_report = ReadJson(dir / "cli/report.json");
  ExpectPosesMatchTruth(f, cli_report, /*has_z_for_all=*/false);
  EXPECT_EQ(cli_report["components"][0]["merged_octree"], "merged_0.bt");
}

// `fleetmerge example DIR --octree`, then `fleetmerge merge DIR/job.yaml`: the pose of
// truth.yaml.
TEST(OctreeFleet, OctreeExampleMergesToItsTruth) {
  const fs::path dir = testing::MakeTempDir("octree_example");
  std::ostringstream out;
  ASSERT_EQ(RunExampleCommand(ExampleCommand{dir, 1, /*octree=*/true}, out), 0);
  const YAML::Node truth = YAML::LoadFile((dir / "truth.yaml").string())["T_a_b"];
  const Pose2 T_true(truth["x"].as<double>(), truth["y"].as<double>(), truth["yaw"].as<double>());
  std::string messages;
  ASSERT_EQ(RunMergeJobs(LoadJobFile(dir / "job.yaml"), &messages), 0) << messages;

  const json report = ReadJson(dir / "merged/report.json");
  const Pose2 T_a_b = PoseOf(report["maps"][0]).inverse() * PoseOf(report["maps"][1]);
  EXPECT_LE(std::abs(WrapAngle(T_a_b.yaw_rad() - T_true.yaw_rad())), M_PI / 180.0);
  EXPECT_LE((T_a_b.translation_m() - T_true.translation_m()).norm(), 0.3);
  const double dz =
      report["maps"][1]["pose"]["z"].get<double>() - report["maps"][0]["pose"]["z"].get<double>();
  EXPECT_LE(std::abs(dz - truth["z"].as<double>()), 0.1);
  EXPECT_TRUE(fs::exists(dir / "merged/merged_0.bt"));
}

TEST(OctreeFleet, JobFileErrorsNameTheFileLineAndKey) {
  const fs::path dir = testing::MakeTempDir("octree_fleet_errors");
  std::ofstream(dir / "not_a_tree.bt") << "hello\n";
  std::ofstream(dir / "a.yaml") << "x";  // never read: the octree entry fails first
  auto error_of = [&](const std::string& text) {
    try {
      WriteJobFile(dir, text);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const std::string bad_tree = error_of("maps: [not_a_tree.bt]\noutput: out\n");
  EXPECT_NE(bad_tree.find("line 1: key 'maps[0]'"), std::string::npos) << bad_tree;
  EXPECT_NE(bad_tree.find("not_a_tree.bt: not an OctoMap octree"), std::string::npos) << bad_tree;
  const std::string band =
      error_of("maps: [not_a_tree.bt]\noutput: out\noctree: {band_min_m: 1.0, band_max_m: 0.5}\n");
  EXPECT_NE(band.find("not_a_tree.bt"), std::string::npos) << "maps are checked first: " << band;
  SaveOctree(*ExtrudeFloorPlan(MakeFleet(1).fleet.maps[0]), dir / "ok.bt");
  const std::string order =
      error_of("maps: [ok.bt]\noutput: out\noctree:\n  band_min_m: 1.0\n  band_max_m: 0.5\n");
  EXPECT_NE(order.find("line 5: key 'octree.band_max_m': expected band_min_m < band_max_m"),
            std::string::npos)
      << order;
  const std::string typo = error_of("maps: [ok.bt]\noutput: out\noctree: {band_mn_m: 1.0}\n");
  EXPECT_NE(typo.find("octree.band_mn_m"), std::string::npos) << typo;
}

}  // namespace
}  // namespace fleetmerge
