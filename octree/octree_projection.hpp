// An octree's floor plan: the 2-D occupancy grid the Hough pipeline merges, cut from a height
// band above the octree's floor (octree/octree_options.hpp, octree/floor_height.hpp).
//
// Rule for each column (x, y) of voxels, over the voxels whose z lies in the band:
//   occupied  if any of them is occupied (a wall, a door, a table: an obstacle at robot height);
//   free      if none is occupied and at least one was observed free;
//   unknown   otherwise (nothing observed in the band).
// The grid has the octree's resolution and frame: its cells are the voxel columns (OctoMap's
// voxel boundaries lie on multiples of the resolution, and so do the grid's), and the grid's map
// frame is the octree's x-y frame, so a 2-D pose of the grid is the octree's pose.
#pragma once

#include <octomap/OcTree.h>

#include "core/occupancy_grid.hpp"
#include "octree/octree_options.hpp"

namespace fleetmerge {

struct OctreeFloorPlan {
  OccupancyGrid grid;
  double floor_z_m = 0.0;                         // estimated floor height (tree frame)
  double band_min_z_m = 0.0, band_max_z_m = 0.0;  // the band used, tree frame
};

// Throws fleetmerge::Error when the tree has no occupied voxel (no floor), or when the options'
// band is empty (band_min_m >= band_max_m).
OctreeFloorPlan ProjectOctree(const octomap::OcTree& tree, const OctreeOptions& options);

// The same with the floor height given (no estimate).
OctreeFloorPlan ProjectOctreeAbove(const octomap::OcTree& tree, double floor_z_m,
                                   const OctreeOptions& options);

}  // namespace fleetmerge
