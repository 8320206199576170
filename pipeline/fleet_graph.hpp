// Stage 2 of fleet merging: from pairwise outcomes to consistent map poses.
//
// Accepted pairs are edges weighted by omega. First every edge is checked against the triangles
// it closes with other edges (independent of any initial guess): the most contradicted edge is
// replaced by one of its pair's other hypotheses that its triangles support, or rejected. Then
// per connected component: initial poses from a
// maximum-omega spanning tree, one Ceres problem over all poses (refine/pose_graph.hpp), then
// the edge that most disagrees with its cycles is taken out; if one of that pair's other
// hypotheses agrees with the poses solved without it, that hypothesis replaces it, else the pair
// is rejected, unless its walls are strong and rejecting a weak edge beside it instead makes it
// agree; repeat until every edge agrees. A bridge edge has no cycle to check it.
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "job/pose_prior.hpp"
#include "pipeline/all_pairs.hpp"
#include "pipeline/placed_by.hpp"
#include "refine/pose_graph.hpp"

namespace fleetmerge {

struct FleetGraph {
  std::vector<int> component_of;         // per map, components numbered in map order
  std::vector<int> component_reference;  // per component: the map whose frame or cells it keeps
  std::vector<Pose2> T_component_map;    // per map: its frame in its component's frame
  std::vector<PlacedBy> placed_by;       // per map
};

// Per map, its component under the accepted pairs (all but pairs[skip_pair]), numbered by their
// first map, in map order.
std::vector<int> Components(int map_count, const std::vector<PairOutcome>& pairs,
                            int skip_pair = -1);

// Per map, its given pose in the merged frame if it is a fixed (base) map, else nullopt; empty
// when no map is fixed.
using FixedPoses = std::vector<std::optional<Pose2>>;
inline bool IsFixed(const FixedPoses& fixed, int m) { return !fixed.empty() && fixed[m]; }

// Where the pose graph measures the edge of a pair's hypothesis (PoseGraphEdge::anchor_b_m): a
// point of b's map frame, for the pair and the index of the hypothesis. Empty: b's frame origin.
using EdgeAnchor = std::function<Eigen::Vector2d(const PairOutcome& pair, int hypothesis)>;

// A prior's cost against a pair's in the pose graph, after the robust loss. A pair's edge is
// whitened by PoseGraphOptions' 0.10 m and 0.5 deg, about 20 times the error pairs show (a tenth
// of a cell), and a prior by its own sigmas, which are what an operator knows: at full cost a
// prior a few decimetres off bent what the pairs placed. Scaled by 1 / 20^2 the pairs keep their
// measured weight against it. It still places what no pair places, it still sets the component's
// placement in the site frame (the priors' weighted mean either way), and the loss still trims a
// far prior at its own sigmas. Both weights measured: docs/accuracy.md, "Known start poses".
constexpr double kPriorCostScale = 1.0 / 400.0;

// Marks pairs accepted (in `pairs`, with edge_hypothesis and notes) and returns the poses.
// `reference` is the job's reference map; other components use their first map.
// Fixed maps (`fixed`, `reference` then the first of them) are one component whatever the edges:
// their given poses tie them. They are all held at their poses in the pose graph, so an edge
// that contradicts those poses is the one that disagrees with its cycles and is rejected; the
// fixed maps' component has the merged frame (T_component_map of a fixed map is its pose).
//
// Known start poses (`priors`, job/pose_prior.hpp) are all given in one site frame: the graph
// gets a node S for that frame and one edge S -> m per map with a prior, measured as the prior
// with the prior's own sigmas, its cost scaled by kPriorCostScale. With fixed maps S is their
// frame, held at the identity; without, S is held at the identity all the same, so the component
// that holds the priors has the site frame (a map's pose there is comparable with its prior). S
// links every map with a prior, so those maps form one component (with the fixed maps) even where
// no pair links them: a map that overlaps no other is placed at its prior (PlacedBy::kPrior), and
// so is a group of maps that accepted pairs link to each other but not to the fixed maps (without
// fixed maps: a group other than the largest, the reference's on a tie), by its members' priors.
// Prior edges are never taken out by the cycle checks: the pairs that contradict the priors were
// dropped before (pipeline/pose_priors.hpp). Without priors and fixed maps nothing of this applies.
//
// `weak_wall_agreement` (FleetOptions::min_bridge_wall_agreement in a merge; 0: never) splits
// edges into weak and strong by the wall agreement of their hypothesis: when the cycle checks
// would reject a strong edge, a weak edge of one of its maps is rejected instead if the strong
// one then agrees.
FleetGraph SolveFleetGraph(int map_count, std::vector<PairOutcome>& pairs, int reference,
                           const PoseGraphOptions& options, const FixedPoses& fixed = {},
                           const PosePriors& priors = {}, const EdgeAnchor& anchor = {},
                           double weak_wall_agreement = 0.0);

}  // namespace fleetmerge
