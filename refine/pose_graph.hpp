// Joint refinement of the poses of all maps of one connected component (the fleet extension of
// the paper): nodes are maps, edges are pairwise hypotheses T_a_b weighted by their omega.
//
// For an edge (a, b) with measurement T_ab = (p_ab, yaw_ab) and anchor q (a point of b's frame,
// anchor_b_m below) the residual is, as in Ceres' pose_graph_2d example with the translation
// taken at q instead of at b's origin (q = 0 gives the example's),
//   r = sqrt(omega) * [ R(yaw_a)^T (p_b + R(yaw_b) q - p_a) - (p_ab + R(yaw_ab) q) ] / sigma_t
//       sqrt(omega) * wrap(yaw_b - yaw_a - yaw_ab)                              / sigma_yaw
// under a robust loss; the reference node is held constant (the gauge).
#pragma once

#include <optional>
#include <vector>

#include "core/pose2.hpp"

namespace fleetmerge {

enum class RobustLoss { kNone, kHuber, kCauchy };

// How each step's linear system (3 unknowns per map) is solved. Both are exact and give the same
// poses (to ~1e-14 m); their speed depends on the graph's density
// (tests/benchmarks/pose_graph_benchmark.cpp, docs/speed.md).
enum class PoseGraphSolver {
  kAutomatic,       // kDenseSchur for a dense graph (UseDenseSchur), else kSparseCholesky
  kSparseCholesky,  // Ceres' SPARSE_NORMAL_CHOLESKY with Eigen's simplicial factorisation
  kDenseSchur,      // Ceres' DENSE_SCHUR: the system made dense and factorised as one block
};

struct PoseGraphOptions {
  RobustLoss loss = RobustLoss::kCauchy;
  double loss_scale = 3.0;            // in sigmas of the whitened residual
  double translation_sigma_m = 0.10;  // expected pairwise error, about two cells at 5 cm
  double yaw_sigma_rad = 0.5 * M_PI / 180.0;
  // An edge whose residual after solving exceeds these is inconsistent with its cycles.
  double max_edge_yaw_error_rad = 1.0 * M_PI / 180.0;
  double max_edge_translation_error_m = 0.25;
  PoseGraphSolver solver = PoseGraphSolver::kAutomatic;
};

struct PoseGraphEdge {
  int a = 0, b = 0;
  Pose2 T_a_b;         // pose of b's frame in a's frame
  double omega = 1.0;  // weight
  // The edge's own sigmas (a pose prior's); 0: PoseGraphOptions' translation_sigma_m and
  // yaw_sigma_rad, the expected error of a pair's hypothesis.
  double translation_sigma_m = 0.0;
  double yaw_sigma_rad = 0.0;
  // The point of b's frame (metres) where the translation error is measured: b's frame origin,
  // or for a pair the centre of the two maps' overlap. A pair's hypothesis is known best where
  // its maps' cells are; a map's frame origin can lie tens of metres from them, and there a yaw
  // error of 0.1 deg already moves it by a cell or more.
  Eigen::Vector2d anchor_b_m = Eigen::Vector2d::Zero();
  // Multiplies the edge's cost after the robust loss: its weight against the other edges, while
  // the loss still trims it where its residual is loss_scale of its own sigmas.
  double cost_scale = 1.0;
};

// Whether kAutomatic solves a graph of `free_nodes` nodes that are not held constant and `edges`
// edges (residual blocks) with kDenseSchur: when the edges are at least a tenth of all pairs of
// those nodes. A fleet's maps overlap their neighbours, and from there on the sparse
// factorisation fills in to nearly dense: the dense solve is faster, 1.3-1.7x at 60 % of the
// pairs (ACES at 33 and 100 robots) for 100-200 maps; at 2 % the sparse one is
// (pose_graph_benchmark, docs/speed.md).
bool UseDenseSchur(int free_nodes, std::size_t edges);

// Poses T_ref_node of every node reached from `reference` by composing edges along a maximum-
// omega spanning tree; nullopt for nodes not connected to it.
std::vector<std::optional<Pose2>> SpanningTreePoses(int node_count,
                                                    const std::vector<PoseGraphEdge>& edges,
                                                    int reference);

// The same from several anchors (fixed maps): every node with an anchor pose starts at it and
// the tree grows from all of them at once.
std::vector<std::optional<Pose2>> SpanningTreePoses(
    int node_count, const std::vector<PoseGraphEdge>& edges,
    const std::vector<std::optional<Pose2>>& anchors);

// Solves the graph from `initial` (nodes without a pose are left out) with `reference` fixed.
std::vector<std::optional<Pose2>> OptimizePoseGraph(
    const std::vector<std::optional<Pose2>>& initial, const std::vector<PoseGraphEdge>& edges,
    int reference, const PoseGraphOptions& options);

// The same with every node where `constant` is true held at its initial pose (several fixed
// maps: an edge that contradicts their given poses can only be absorbed by its own residual).
std::vector<std::optional<Pose2>> OptimizePoseGraph(
    const std::vector<std::optional<Pose2>>& initial, const std::vector<PoseGraphEdge>& edges,
    const std::vector<bool>& constant, const PoseGraphOptions& options);

// How far an edge's measurement is from the poses: yaw and translation of
// T_a_b^-1 * (T_ref_a^-1 T_ref_b).
struct EdgeError {
  double yaw_rad = 0.0;
  double translation_m = 0.0;
};
EdgeError EdgeDisagreement(const PoseGraphEdge& edge, const Pose2& T_ref_a, const Pose2& T_ref_b);

}  // namespace fleetmerge
