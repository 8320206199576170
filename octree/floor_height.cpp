#include "octree/floor_height.hpp"

#include <algorithm>
#include <vector>

#include "core/error.hpp"

namespace fleetmerge {

FloorHeight EstimateFloorHeight(const octomap::OcTree& tree) {
  // Occupied volume (in voxels) per z key; keys are 16-bit, so a flat array is cheap.
  std::vector<double> layer_voxels(1u << 16, 0.0);
  const unsigned max_depth = tree.getTreeDepth();
  bool any = false;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    const unsigned n = 1u << (max_depth - it.getDepth());  // edge of a pruned leaf, in voxels
    const unsigned z0 = it.getIndexKey()[2];               // its lowest voxel layer
    for (unsigned k = 0; k < n; ++k) layer_voxels[z0 + k] += double(n) * double(n);
    any = true;
  }
  if (!any) throw Error("the octree has no occupied voxel, so no floor to stand the map on");

  const double densest = *std::max_element(layer_voxels.begin(), layer_voxels.end());
  const double dense = 0.5 * densest;
  std::size_t floor_key = 0;
  while (layer_voxels[floor_key] < dense) ++floor_key;  // the densest layer stops it
  const double share = layer_voxels[floor_key] / densest;
  // A thick slab continues through layers that stand out from the walls: more than twice the
  // median layer (walls only: every layer is the median, so the bottom layer stays the floor).
  std::vector<double> non_empty;
  for (double v : layer_voxels) {
    if (v > 0.0) non_empty.push_back(v);
  }
  std::nth_element(non_empty.begin(), non_empty.begin() + non_empty.size() / 2, non_empty.end());
  const double slab = std::max(dense, 2.0 * non_empty[non_empty.size() / 2]);
  while (floor_key + 1 < layer_voxels.size() && layer_voxels[floor_key + 1] >= slab) ++floor_key;

  // Top face of the floor layer: its key's lower face plus one voxel.
  const double z_top_m =
      tree.keyToCoord(static_cast<octomap::key_type>(floor_key)) + 0.5 * tree.getResolution();
  return {z_top_m, share};
}

}  // namespace fleetmerge
