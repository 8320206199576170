// The merged octree of a component: every input octree moved by its pose (x, y, yaw from the 2-D
// pipeline, z from the floor heights) into the component's frame and fused with OctoMap's own
// update rule (log-odds added, clamped: OccupancyOcTreeBase::updateNode). Fixed inputs (a site's
// base octree) are kept as the 2-D merged map keeps a fixed map (pipeline/composite.hpp): a voxel
// that a fixed tree knows is fused from the fixed trees alone, the others fill only the rest.
//
// Resampling is by inverse mapping (nearest voxel): each output voxel whose centre falls inside
// an input leaf receives that leaf's log-odds, once per input. Forward mapping of the input
// voxels would leave holes and double hits under an arbitrary yaw; this way every output voxel
// inside an input's known space is updated exactly once by that input, as OctoMap would update
// it from one more scan that saw it.
#pragma once

#include <octomap/OcTree.h>

#include <memory>
#include <vector>

#include "core/pose2.hpp"

namespace fleetmerge {

// Pose of an octree's frame in the merged frame: the 2-D pose (x, y, yaw about z) and a vertical
// offset, p_merged = (T_xy * p.xy, p.z + z_m).
struct OctreePose {
  Pose2 T_xy;
  double z_m = 0.0;
};

struct OctreeInput {
  const octomap::OcTree* tree = nullptr;
  OctreePose T_merged_tree;
  bool fixed = false;  // a fixed (base) map's tree: the voxels it knows are kept
};

// Throws fleetmerge::Error for no input, a null tree or resolution_m <= 0.
std::unique_ptr<octomap::OcTree> MergeOctrees(const std::vector<OctreeInput>& inputs,
                                              double resolution_m);

}  // namespace fleetmerge
