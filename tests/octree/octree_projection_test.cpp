// octree/floor_height and octree/octree_projection: the floor of extruded floor plans at known
// heights, the projection against a brute-force per-column oracle on random trees, and the
// default band keeping walls while dropping floor, ceiling and low clutter.
#include "octree/octree_projection.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/error.hpp"
#include "octree/floor_height.hpp"
#include "octree/synthetic_octree.hpp"
#include "sim/synthetic_office.hpp"

namespace fleetmerge {
namespace {

OccupancyGrid SmallOffice(std::uint32_t seed) {
  OfficeOptions office;
  office.width_m = 14.0;
  office.height_m = 10.0;
  office.resolution_m = 0.1;
  office.wall_thickness_m = 0.2;
  return GenerateOfficeFloor(office, seed);
}

TEST(FloorHeight, FoundWithinHalfAVoxelAtAnyHeight) {
  const OccupancyGrid plan = SmallOffice(3);
  for (double floor_z_m : {0.0, 0.37, -1.23, 2.05, 0.05}) {
    ExtrudeOptions options;
    options.floor_z_m = floor_z_m;
    const auto tree = ExtrudeFloorPlan(plan, options);
    const FloorHeight floor = EstimateFloorHeight(*tree);
    // The floor voxel layer's top face is the floor quantised to the voxel grid.
    EXPECT_GE(floor.z_m - floor_z_m, -0.05 - 1e-9) << floor_z_m;
    EXPECT_LT(floor.z_m - floor_z_m, 0.05 + 1e-9) << floor_z_m;
    EXPECT_DOUBLE_EQ(floor.share, 1.0) << "floor and ceiling are the densest layers";
  }
}

TEST(FloorHeight, WallsOnlyStandOnTheirBottom) {
  octomap::OcTree tree(0.1);
  for (int i = 0; i < 40; ++i) {
    for (int k = 0; k < 20; ++k) tree.updateNode(0.1 * i + 0.05, 0.05, 0.8 + 0.1 * k + 0.05, true);
  }
  EXPECT_NEAR(EstimateFloorHeight(tree).z_m, 0.9, 1e-6);  // top of the lowest layer [0.8, 0.9)
  EXPECT_THROW(EstimateFloorHeight(octomap::OcTree(0.1)), Error);
}

// The floor plan of an extruded plan is the plan: walls and clutter occupied, rooms free (the
// floor below the band, the ceiling above it, the 0.1 m objects under it), outside unknown.
TEST(OctreeProjection, DefaultBandGivesBackTheFloorPlan) {
  const OccupancyGrid plan = SmallOffice(5);
  ExtrudeOptions options;
  options.floor_z_m = -0.42;
  const auto tree = ExtrudeFloorPlan(plan, options);
  const OctreeFloorPlan projected = ProjectOctree(*tree, OctreeOptions{});
  EXPECT_NEAR(projected.floor_z_m, -0.42, 0.05);
  EXPECT_DOUBLE_EQ(projected.grid.geometry().resolution_m(), 0.1);
  int compared = 0;
  for (int j = 0; j < plan.height(); ++j) {
    for (int i = 0; i < plan.width(); ++i) {
      const Eigen::Array2i cell =
          projected.grid.geometry().CellOf(plan.geometry().CellCenter({i, j}));
      ASSERT_EQ(projected.grid.StateOrUnknown(cell), plan.at({i, j})) << i << ", " << j;
      ++compared;
    }
  }
  EXPECT_EQ(projected.grid.Count(CellState::kOccupied), plan.Count(CellState::kOccupied));
  EXPECT_EQ(projected.grid.Count(CellState::kFree), plan.Count(CellState::kFree));
  EXPECT_GT(compared, 10000);

  // A band reaching into the floor slab: every observed column is occupied.
  OctreeOptions low;
  low.band_min_m = -0.05;
  const OctreeFloorPlan floor_too = ProjectOctree(*tree, low);
  EXPECT_EQ(floor_too.grid.Count(CellState::kFree), 0);
  EXPECT_EQ(floor_too.grid.Count(CellState::kOccupied),
            plan.Count(CellState::kOccupied) + plan.Count(CellState::kFree));
}

// A random tree with pruned blocks, against a per-voxel search of every column in the band.
TEST(OctreeProjection, MatchesBruteForceColumnSearch) {
  for (unsigned seed : {1u, 2u, 3u}) {
    octomap::OcTree tree(0.05);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> xy(-1.0, 1.0), z(-0.5, 2.5);
    for (int i = 0; i < 4000; ++i) tree.updateNode(xy(rng), xy(rng), z(rng), i % 4 == 0);
    for (double x = 0.0; x < 0.8; x += 0.05) {  // a free block that prunes into big leaves
      for (double y = 0.0; y < 0.8; y += 0.05) {
        for (double zz = 0.0; zz < 0.8; zz += 0.05)
          tree.updateNode(x + 0.01, y + 0.01, zz + 0.01, false);
      }
    }
    tree.prune();
    OctreeOptions band;
    band.band_min_m = 0.3;
    band.band_max_m = 1.8;
    const OctreeFloorPlan plan = ProjectOctreeAbove(tree, 0.0, band);
    const auto& g = plan.grid.geometry();
    int occupied = 0, free = 0;
    for (int j = 0; j < g.height(); ++j) {
      for (int i = 0; i < g.width(); ++i) {
        const Eigen::Vector2d p = g.CellCenter({i, j});
        bool any_occupied = false, any_free = false;
        for (int k = 6; k < 36; ++k) {  // voxel centres 0.325 .. 1.775 m
          const octomap::OcTreeNode* node = tree.search(p.x(), p.y(), 0.05 * k + 0.025);
          if (node == nullptr) continue;
          (tree.isNodeOccupied(node) ? any_occupied : any_free) = true;
        }
        const CellState expected = any_occupied ? CellState::kOccupied
                                   : any_free   ? CellState::kFree
                                                : CellState::kUnknown;
        ASSERT_EQ(plan.grid.at({i, j}), expected) << seed << ": " << i << ", " << j;
        occupied += any_occupied;
        free += !any_occupied && any_free;
      }
    }
    EXPECT_GT(occupied, 200);
    EXPECT_GT(free, 200);
  }
}

TEST(OctreeProjection, RefusesAnEmptyBand) {
  const auto tree = ExtrudeFloorPlan(SmallOffice(1));
  OctreeOptions band;
  band.band_min_m = 1.0;
  band.band_max_m = 1.0;
  EXPECT_THROW(ProjectOctree(*tree, band), Error);
}

}  // namespace
}  // namespace fleetmerge
