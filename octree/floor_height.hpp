// The floor height of an octree of one storey: the z of the floor's top surface, in the tree's
// frame. Used to cut the height band of the floor plan (octree/octree_projection.hpp) relative to
// the floor, and to estimate the vertical offset between the octrees of one merged component
// (their floors must coincide).
//
// Method: a histogram of occupied volume per voxel layer (a pruned leaf of size n voxels adds n*n
// to each of its n layers). A floor seen from above is one dense horizontal layer (area), while
// walls add about the same small amount (perimeter) to every layer. The floor is the lowest layer
// holding at least half the count of the densest layer, followed upwards through the layers
// directly above it that are as dense and also hold more than twice the median layer (a slab
// several voxels thick, told apart from walls); its height is the top face of the highest. A
// ceiling is also dense but lies above free space, so it never joins the floor. An octree without a
// visible floor (walls only) gets the bottom of its walls, the lowest dense layer.
#pragma once

#include <octomap/OcTree.h>

namespace fleetmerge {

struct FloorHeight {
  double z_m = 0.0;    // top surface of the floor, tree frame
  double share = 0.0;  // the floor layer's count / the densest layer's (1 when it is densest)
};

// Throws fleetmerge::Error when the tree has no occupied voxel.
FloorHeight EstimateFloorHeight(const octomap::OcTree& tree);

}  // namespace fleetmerge
