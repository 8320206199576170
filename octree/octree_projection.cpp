#include "octree/octree_projection.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"
#include "octree/floor_height.hpp"

namespace fleetmerge {
namespace {

// The x-y key range of the tree's known space (every leaf, free or occupied).
struct KeyBox {
  int x0 = 0, y0 = 0, width = 0, height = 0;
};

KeyBox KnownKeyBox(const octomap::OcTree& tree) {
  double min_x = 0, min_y = 0, min_z = 0, max_x = 0, max_y = 0, max_z = 0;
  tree.getMetricMin(min_x, min_y, min_z);
  tree.getMetricMax(max_x, max_y, max_z);
  const double r = tree.getResolution();
  // Leaves span whole voxels, so the bounds lie on voxel faces; the half voxel keeps the keys
  // of the first and last column away from rounding at those faces.
  KeyBox box;
  box.x0 = tree.coordToKey(min_x + 0.5 * r);
  box.y0 = tree.coordToKey(min_y + 0.5 * r);
  box.width = int(tree.coordToKey(max_x - 0.5 * r)) - box.x0 + 1;
  box.height = int(tree.coordToKey(max_y - 0.5 * r)) - box.y0 + 1;
  return box;
}

}  // namespace

OctreeFloorPlan ProjectOctree(const octomap::OcTree& tree, const OctreeOptions& options) {
  return ProjectOctreeAbove(tree, EstimateFloorHeight(tree).z_m, options);
}

OctreeFloorPlan ProjectOctreeAbove(const octomap::OcTree& tree, double floor_z_m,
                                   const OctreeOptions& options) {
  if (!(options.band_min_m < options.band_max_m)) {
    throw Error("the octree height band is empty: band_min_m must be below band_max_m");
  }
  if (tree.size() == 0) throw Error("the octree is empty");
  const double r = tree.getResolution();
  OctreeFloorPlan plan;
  plan.floor_z_m = floor_z_m;
  plan.band_min_z_m = floor_z_m + options.band_min_m;
  plan.band_max_z_m = floor_z_m + options.band_max_m;

  const KeyBox box = KnownKeyBox(tree);
  // Grid cell (i, j) is voxel column (x0 + i, y0 + j); the key's lower face is at
  // (key - 2^15) * r, so the grid frame sits at the lower face of (x0, y0).
  const Pose2 T_map_grid(tree.keyToCoord(octomap::key_type(box.x0)) - 0.5 * r,
                         tree.keyToCoord(octomap::key_type(box.y0)) - 0.5 * r, 0.0);
  plan.grid = OccupancyGrid(GridGeometry(r, {box.width, box.height}, T_map_grid));
  cv::Mat1b& cells = plan.grid.mutable_cells();

  // Voxel layers whose centres lie in [band_min_z, band_max_z). Only the subtrees that reach
  // into the band are visited (OctoMap's bounding-box iterator).
  const int z_lo = int(std::ceil(plan.band_min_z_m / r - 0.5)) + (1 << 15);
  const int z_hi = int(std::ceil(plan.band_max_z_m / r - 0.5)) + (1 << 15) - 1;
  if (z_hi < 0 || z_lo > 0xffff || z_lo > z_hi) return plan;  // band outside the tree: unknown
  const octomap::OcTreeKey key_min(0, 0, octomap::key_type(std::max(z_lo, 0)));
  const octomap::OcTreeKey key_max(0xffff, 0xffff, octomap::key_type(std::min(z_hi, 0xffff)));
  const unsigned max_depth = tree.getTreeDepth();
  const auto free_value = static_cast<std::uint8_t>(CellState::kFree);
  const auto occupied_value = static_cast<std::uint8_t>(CellState::kOccupied);
  for (auto it = tree.begin_leafs_bbx(key_min, key_max), end = tree.end_leafs_bbx(); it != end;
       ++it) {
    const int n = 1 << (max_depth - it.getDepth());  // a pruned leaf covers n x n columns
    const octomap::OcTreeKey corner = it.getIndexKey();
    const bool occupied = tree.isNodeOccupied(*it);
    const int i0 = std::max(int(corner[0]) - box.x0, 0);
    const int j0 = std::max(int(corner[1]) - box.y0, 0);
    const int i1 = std::min(int(corner[0]) + n - box.x0, box.width);
    const int j1 = std::min(int(corner[1]) + n - box.y0, box.height);
    for (int j = j0; j < j1; ++j) {
      std::uint8_t* row = cells[j];
      for (int i = i0; i < i1; ++i) {
        if (occupied) {
          row[i] = occupied_value;  // any occupied voxel in the band wins
        } else if (row[i] != occupied_value) {
          row[i] = free_value;
        }
      }
    }
  }
  return plan;
}

}  // namespace fleetmerge
