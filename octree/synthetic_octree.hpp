// Synthetic octrees of one storey for tests, benchmarks and examples: a 2-D floor plan (e.g.
// sim/synthetic_office.hpp, or a part of it cut by sim/ground_truth_pair.hpp) extruded
// into 3-D as a robot with a 3-D sensor would have mapped it. Occupied plan cells become walls
// from the floor to the ceiling; free cells become a floor voxel (occupied), free voxels up to
// the ceiling and, optionally, a ceiling voxel; unknown cells stay unobserved. Observed cells get
// OctoMap's clamping log-odds (a well-observed map), then the tree is pruned.
#pragma once

#include <octomap/OcTree.h>

#include <memory>

#include "core/occupancy_grid.hpp"

namespace fleetmerge {

struct ExtrudeOptions {
  double floor_z_m = 0.0;      // the floor's top surface, tree frame
  double wall_height_m = 2.5;  // walls and free space from the floor up to here
  bool ceiling = true;         // an occupied voxel layer on top of the free space
  bool low_clutter = true;     // every 7th free cell along x and y holds an object 0.1 m tall
};

// The octree has the plan's resolution and its cells on the plan's cell centres (tree frame =
// the plan's map frame). Throws fleetmerge::Error when wall_height_m < 2 voxels.
std::unique_ptr<octomap::OcTree> ExtrudeFloorPlan(const OccupancyGrid& plan,
                                                  const ExtrudeOptions& options = {});

}  // namespace fleetmerge
