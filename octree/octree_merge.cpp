#include "octree/octree_merge.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

// Adds one input to `out`: for every leaf of the input, the output voxels whose centres fall in
// the leaf's moved cube [c - s/2, c + s/2) (half-open, so neighbouring leaves never both claim a
// voxel) get the leaf's log-odds; the voxels `kept` holds (the fixed trees') are left as they are.
void AddTree(const OctreeInput& input, octomap::OcTree& out, const octomap::OcTree* kept) {
  const octomap::OcTree& tree = *input.tree;
  const Pose2& T = input.T_merged_tree.T_xy;
  const Pose2 T_tree_merged = T.inverse();
  const Eigen::Matrix2d R = T.rotation();
  const double r_out = out.getResolution();
  const double dz_m = input.T_merged_tree.z_m;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    const float log_odds = it->getLogOdds();
    const double half = 0.5 * it.getSize();
    const Eigen::Vector2d c(it.getX(), it.getY());
    // The moved square's bounding box in the merged frame (|R| maps half-extents to extents).
    const Eigen::Vector2d centre = T * c;
    const Eigen::Vector2d extent = R.cwiseAbs() * Eigen::Vector2d(half, half);
    const double z0 = it.getZ() - half + dz_m, z1 = it.getZ() + half + dz_m;
    // Output keys whose centre lies in [lo, hi): centre (k - 2^15 + 0.5) r.
    auto first_key = [&](double lo) { return int(std::ceil(lo / r_out - 0.5)) + (1 << 15); };
    const int i0 = first_key(centre.x() - extent.x()), i1 = first_key(centre.x() + extent.x());
    const int j0 = first_key(centre.y() - extent.y()), j1 = first_key(centre.y() + extent.y());
    const int k0 = first_key(z0), k1 = first_key(z1);
    if (i0 < 0 || j0 < 0 || k0 < 0 || i1 > 0xffff || j1 > 0xffff || k1 > 0xffff) {
      throw Error("a moved octree leaves OctoMap's coordinate range (+-" +
                  std::to_string(r_out * (1 << 15)) + " m at this resolution)");
    }
    for (int i = i0; i < i1; ++i) {
      for (int j = j0; j < j1; ++j) {
        const Eigen::Vector2d p_merged(out.keyToCoord(octomap::key_type(i)),
                                       out.keyToCoord(octomap::key_type(j)));
        const Eigen::Vector2d d = T_tree_merged * p_merged - c;  // in the input leaf's frame
        if (d.x() < -half || d.x() >= half || d.y() < -half || d.y() >= half) continue;
        for (int k = k0; k < k1; ++k) {
          const octomap::OcTreeKey key{octomap::key_type(i), octomap::key_type(j),
                                       octomap::key_type(k)};
          if (kept != nullptr && kept->search(key) != nullptr) continue;
          out.updateNode(key, log_odds, /*lazy_eval=*/true);
        }
      }
    }
  }
}

}  // namespace

std::unique_ptr<octomap::OcTree> MergeOctrees(const std::vector<OctreeInput>& inputs,
                                              double resolution_m) {
  if (inputs.empty()) throw Error("merging octrees needs at least one octree");
  if (!(resolution_m > 0.0)) throw Error("the merged octree's resolution must be > 0");
  for (const OctreeInput& input : inputs) {
    if (input.tree == nullptr) throw Error("merging octrees: a null octree");
  }
  auto out = std::make_unique<octomap::OcTree>(resolution_m);
  for (const OctreeInput& input : inputs) {
    if (input.fixed) AddTree(input, *out, nullptr);
  }
  // The fixed trees' voxels, which the others must not change (a copy: the others add voxels).
  std::unique_ptr<const octomap::OcTree> kept;
  if (out->size() > 0) kept = std::make_unique<const octomap::OcTree>(*out);
  for (const OctreeInput& input : inputs) {
    if (!input.fixed) AddTree(input, *out, kept.get());
  }
  // Lazy updates leave inner nodes stale; OctoMap's own pass fixes them, then merges identical
  // children (a compact tree, as OctoMap would hold after the same updates made eagerly).
  out->updateInnerOccupancy();
  out->prune();
  return out;
}

}  // namespace fleetmerge
