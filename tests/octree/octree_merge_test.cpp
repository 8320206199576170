// octree/octree_merge: the moved tree against a brute-force inverse mapping of every voxel, and
// the fusion of overlapping trees by OctoMap's clamped log-odds sum.
#include "octree/octree_merge.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

octomap::OcTree RandomTree(unsigned seed, double resolution_m) {
  octomap::OcTree tree(resolution_m);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> coord(0.0, 1.2);
  for (int i = 0; i < 1500; ++i) tree.updateNode(coord(rng), coord(rng), coord(rng), i % 3 == 0);
  for (double x = 0.0; x < 0.4; x += resolution_m) {  // a block that prunes into one leaf
    for (double y = 0.0; y < 0.4; y += resolution_m) {
      for (double z = 0.0; z < 0.4; z += resolution_m) {
        tree.updateNode(x + 1e-3, y + 1e-3, z + 1e-3 - 0.4, false);
      }
    }
  }
  tree.prune();
  return tree;
}

// Every output voxel in a box around the moved tree: its centre mapped back into the input must
// find the node the merged tree holds there (same log-odds), or nothing where the input has none.
void ExpectInverseMapping(const octomap::OcTree& input, const OctreePose& T,
                          const octomap::OcTree& merged) {
  const double r = merged.getResolution();
  const Pose2 T_input_merged = T.T_xy.inverse();
  int known = 0;
  for (double x = -1.6; x < 3.2; x += r) {
    for (double y = -1.6; y < 3.2; y += r) {
      for (double z = -1.0; z < 2.5; z += r) {
        const octomap::OcTreeKey key = merged.coordToKey(x, y, z);
        const octomap::point3d q = merged.keyToCoord(key);
        const Eigen::Vector2d p = T_input_merged * Eigen::Vector2d(q.x(), q.y());
        const octomap::OcTreeNode* in = input.search(p.x(), p.y(), q.z() - T.z_m);
        const octomap::OcTreeNode* out = merged.search(key);
        ASSERT_EQ(in == nullptr, out == nullptr) << q;
        if (in == nullptr) continue;
        ASSERT_NEAR(out->getLogOdds(), in->getLogOdds(), 1e-5) << q;
        ++known;
      }
    }
  }
  EXPECT_GT(known, 500);
}

TEST(OctreeMerge, OneMovedTreeIsItsInverseMapping) {
  const octomap::OcTree tree = RandomTree(1, 0.1);
  for (const OctreePose& T :
       {OctreePose{Pose2(0, 0, 0), 0.0}, OctreePose{Pose2(0.7, -0.3, 0.6), 0.23},
        OctreePose{Pose2(-0.25, 1.1, -2.9), -0.41}}) {
    const auto merged = MergeOctrees({{&tree, T}}, 0.1);
    ExpectInverseMapping(tree, T, *merged);
  }
}

TEST(OctreeMerge, IdentityMergeKeepsTheLeaves) {
  const octomap::OcTree tree = RandomTree(2, 0.05);
  const auto merged = MergeOctrees({{&tree, {}}}, 0.05);
  EXPECT_EQ(merged->size(), tree.size());
  for (auto it = tree.begin_leafs(); it != tree.end_leafs(); ++it) {
    const octomap::OcTreeNode* node = merged->search(it.getKey(), it.getDepth());
    ASSERT_NE(node, nullptr);
    EXPECT_FLOAT_EQ(node->getLogOdds(), it->getLogOdds());
  }
}

// Two trees over the same voxels: the merged log-odds is their sum clamped to OctoMap's bounds,
// as OccupancyOcTreeBase::updateNode does for one more observation.
TEST(OctreeMerge, OverlapFusesByClampedLogOddsSum) {
  const octomap::OcTree a = RandomTree(3, 0.1), b = RandomTree(4, 0.1);
  const auto merged = MergeOctrees({{&a, {}}, {&b, {}}}, 0.1);
  int both = 0;
  for (auto it = merged->begin_leafs(); it != merged->end_leafs(); ++it) {
    const octomap::point3d p = it.getCoordinate();
    if (it.getDepth() != merged->getTreeDepth()) continue;
    const octomap::OcTreeNode* na = a.search(p);
    const octomap::OcTreeNode* nb = b.search(p);
    float expected = 0.0f;
    for (const auto* n : {na, nb}) {
      if (n == nullptr) continue;
      expected = std::clamp(expected + n->getLogOdds(), merged->getClampingThresMinLog(),
                            merged->getClampingThresMaxLog());
    }
    EXPECT_NEAR(it->getLogOdds(), expected, 1e-5) << p;
    both += na != nullptr && nb != nullptr;
  }
  EXPECT_GT(both, 300);
}

// A fixed tree (a site's base) keeps every voxel it knows, whatever the other trees say there;
// the others are fused as before where no fixed tree knows the voxel. Order does not matter.
TEST(OctreeMerge, AFixedTreeKeepsTheVoxelsItKnows) {
  const octomap::OcTree base = RandomTree(6, 0.1), a = RandomTree(7, 0.1), b = RandomTree(8, 0.1);
  const OctreePose T_a{Pose2(0.3, -0.2, 0.4), 0.1};  // partly over the base, partly beside it
  for (const bool base_first : {true, false}) {
    std::vector<OctreeInput> inputs = {{&a, T_a}, {&b, {}}};
    inputs.insert(base_first ? inputs.begin() : inputs.end(), {&base, {}, true});
    const auto merged = MergeOctrees(inputs, 0.1);
    const auto others = MergeOctrees({{&a, T_a}, {&b, {}}}, 0.1);  // the moving trees alone
    int kept = 0, others_differ = 0, filled = 0;
    for (auto it = merged->begin_leafs(); it != merged->end_leafs(); ++it) {
      if (it.getDepth() != merged->getTreeDepth()) continue;  // pruned: its centre is no voxel's
      const octomap::point3d p = it.getCoordinate();
      const octomap::OcTreeNode* in_base = base.search(p);
      const octomap::OcTreeNode* in_others = others->search(p);
      ASSERT_TRUE(in_base != nullptr || in_others != nullptr) << p;
      if (in_base != nullptr) {
        ASSERT_FLOAT_EQ(it->getLogOdds(), in_base->getLogOdds()) << p;
        ++kept;
        if (in_others == nullptr) continue;
        // Fusing the base with the others would have changed the voxel.
        others_differ += std::clamp(in_base->getLogOdds() + in_others->getLogOdds(),
                                    merged->getClampingThresMinLog(),
                                    merged->getClampingThresMaxLog()) != in_base->getLogOdds();
      } else {
        ASSERT_NEAR(it->getLogOdds(), in_others->getLogOdds(), 1e-5) << p;
        ++filled;
      }
    }
    EXPECT_GT(kept, 500);
    EXPECT_GT(others_differ, 100);  // not vacuous
    EXPECT_GT(filled, 300);
    // Every voxel of either kind is in the merged tree: the base's and the others' outside it.
    for (auto it = base.begin_leafs(); it != base.end_leafs(); ++it) {
      ASSERT_NE(merged->search(it.getCoordinate()), nullptr) << it.getCoordinate();
    }
  }
}

TEST(OctreeMerge, RefusesNoInput) {
  EXPECT_THROW(MergeOctrees({}, 0.1), Error);
  const octomap::OcTree tree = RandomTree(5, 0.1);
  EXPECT_THROW(MergeOctrees({{&tree, {}}}, 0.0), Error);
}

}  // namespace
}  // namespace fleetmerge
