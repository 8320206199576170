#include "refine/pose_graph.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>

namespace fleetmerge {
namespace {

template <typename T>
T WrapAngleT(const T& angle) {
  // The same wrap as Ceres' pose_graph_2d NormalizeAngle, usable on Jets.
  const T two_pi(2.0 * M_PI);
  return angle - two_pi * ceres::floor((angle + T(M_PI)) / two_pi);
}

struct RelativePoseResidual {
  RelativePoseResidual(const PoseGraphEdge& edge, const PoseGraphOptions& options)
      : q_b(edge.anchor_b_m),
        q_a(edge.T_a_b * edge.anchor_b_m),
        yaw_ab(edge.T_a_b.yaw_rad()),
        w_t(std::sqrt(edge.omega) / (edge.translation_sigma_m > 0.0 ? edge.translation_sigma_m
                                                                    : options.translation_sigma_m)),
        w_yaw(std::sqrt(edge.omega) /
              (edge.yaw_sigma_rad > 0.0 ? edge.yaw_sigma_rad : options.yaw_sigma_rad)) {}

  // pose = (x_m, y_m, yaw_rad) of T_ref_node.
  template <typename T>
  bool operator()(const T* a, const T* b, T* r) const {
    // The anchor q_b of b's frame in a's frame under the poses, against where the edge puts it.
    const T cb = ceres::cos(b[2]), sb = ceres::sin(b[2]);
    const T qx = b[0] + cb * T(q_b.x()) - sb * T(q_b.y());
    const T qy = b[1] + sb * T(q_b.x()) + cb * T(q_b.y());
    const T c = ceres::cos(a[2]), s = ceres::sin(a[2]);
    const T dx = qx - a[0], dy = qy - a[1];
    r[0] = T(w_t) * (c * dx + s * dy - T(q_a.x()));
    r[1] = T(w_t) * (-s * dx + c * dy - T(q_a.y()));
    r[2] = T(w_yaw) * WrapAngleT(b[2] - a[2] - T(yaw_ab));
    return true;
  }

  Eigen::Vector2d q_b, q_a;  // the anchor in b's frame, and where the edge puts it in a's
  double yaw_ab, w_t, w_yaw;
};

ceres::LossFunction* MakeLoss(const PoseGraphOptions& options) {
  switch (options.loss) {
    case RobustLoss::kHuber:
      return new ceres::HuberLoss(options.loss_scale);
    case RobustLoss::kCauchy:
      return new ceres::CauchyLoss(options.loss_scale);
    case RobustLoss::kNone:
      break;
  }
  return nullptr;
}

}  // namespace

bool UseDenseSchur(int free_nodes, std::size_t edges) {
  const std::size_t n = static_cast<std::size_t>(std::max(free_nodes, 0));
  return n >= 2 && 10 * edges >= n * (n - 1) / 2;
}

std::vector<std::optional<Pose2>> SpanningTreePoses(int node_count,
                                                    const std::vector<PoseGraphEdge>& edges,
                                                    int reference) {
  std::vector<std::optional<Pose2>> anchors(node_count);
  anchors[reference] = Pose2();
  return SpanningTreePoses(node_count, edges, anchors);
}

std::vector<std::optional<Pose2>> SpanningTreePoses(
    int node_count, const std::vector<PoseGraphEdge>& edges,
    const std::vector<std::optional<Pose2>>& anchors) {
  // Prim's algorithm from the anchors, always taking the highest-omega edge out of the tree.
  std::vector<std::optional<Pose2>> poses = anchors;
  poses.resize(node_count);
  using Candidate = std::pair<double, int>;  // (omega, edge index)
  std::priority_queue<Candidate> frontier;
  // Each node's edges in index order, listed once: scanning every edge for each node placed
  // cost O(nodes x edges) per solve, and a 100-robot fleet solves ~36 times.
  std::vector<std::vector<int>> edges_of(node_count);
  const auto listed = [&](int node) { return node >= 0 && node < node_count; };
  for (int e = 0; e < static_cast<int>(edges.size()); ++e) {
    if (listed(edges[e].a)) edges_of[edges[e].a].push_back(e);
    if (listed(edges[e].b) && edges[e].b != edges[e].a) edges_of[edges[e].b].push_back(e);
  }
  const auto push_edges_of = [&](int node) {
    for (const int e : edges_of[node]) frontier.push({edges[e].omega, -e});
  };
  for (int node = 0; node < node_count; ++node) {
    if (poses[node]) push_edges_of(node);
  }
  while (!frontier.empty()) {
    const PoseGraphEdge& edge = edges[-frontier.top().second];  // ties: lowest index first
    frontier.pop();
    if (poses[edge.a] && !poses[edge.b]) {
      poses[edge.b] = *poses[edge.a] * edge.T_a_b;
      push_edges_of(edge.b);
    } else if (poses[edge.b] && !poses[edge.a]) {
      poses[edge.a] = *poses[edge.b] * edge.T_a_b.inverse();
      push_edges_of(edge.a);
    }
  }
  return poses;
}

std::vector<std::optional<Pose2>> OptimizePoseGraph(
    const std::vector<std::optional<Pose2>>& initial, const std::vector<PoseGraphEdge>& edges,
    int reference, const PoseGraphOptions& options) {
  std::vector<bool> constant(initial.size(), false);
  constant[reference] = true;
  return OptimizePoseGraph(initial, edges, constant, options);
}

std::vector<std::optional<Pose2>> OptimizePoseGraph(
    const std::vector<std::optional<Pose2>>& initial, const std::vector<PoseGraphEdge>& edges,
    const std::vector<bool>& constant, const PoseGraphOptions& options) {
  std::vector<std::array<double, 3>> x(initial.size());
  for (std::size_t n = 0; n < initial.size(); ++n) {
    if (initial[n]) x[n] = {initial[n]->x_m(), initial[n]->y_m(), initial[n]->yaw_rad()};
  }
  ceres::Problem problem;
  for (const PoseGraphEdge& edge : edges) {
    if (!initial[edge.a] || !initial[edge.b]) continue;
    auto* cost = new ceres::AutoDiffCostFunction<RelativePoseResidual, 3, 3, 3>(
        new RelativePoseResidual(edge, options));
    ceres::LossFunction* loss = MakeLoss(options);
    if (edge.cost_scale != 1.0) {
      loss = new ceres::ScaledLoss(loss, edge.cost_scale, ceres::TAKE_OWNERSHIP);
    }
    problem.AddResidualBlock(cost, loss, x[edge.a].data(), x[edge.b].data());
  }
  bool gauge = false;
  for (std::size_t n = 0; n < initial.size(); ++n) {
    if (constant[n] && problem.HasParameterBlock(x[n].data())) {
      problem.SetParameterBlockConstant(x[n].data());  // the gauge (and any other fixed map)
      gauge = true;
    }
  }
  if (gauge) {
    ceres::Solver::Options solver;
    int free_nodes = 0;
    for (std::size_t n = 0; n < initial.size(); ++n) {
      free_nodes += problem.HasParameterBlock(x[n].data()) && !constant[n];
    }
    const bool dense =
        options.solver == PoseGraphSolver::kDenseSchur ||
        (options.solver == PoseGraphSolver::kAutomatic &&
         UseDenseSchur(free_nodes, static_cast<std::size_t>(problem.NumResidualBlocks())));
    if (dense) {
      // Ceres eliminates an independent set of nodes (a few, in a dense graph) and factorises
      // the rest as one dense matrix with Eigen's blocked Cholesky.
      solver.linear_solver_type = ceres::DENSE_SCHUR;
    } else {
      solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      // A sparse graph: Eigen's simplicial factorisation, no BLAS calls to pay for on 3
      // parameters a map.
      if (ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::EIGEN_SPARSE)) {
        solver.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
      }
    }
    solver.max_num_iterations = 100;
    solver.logging_type = ceres::SILENT;
    solver.num_threads = 1;
    ceres::Solver::Summary summary;
    ceres::Solve(solver, &problem, &summary);
  }
  std::vector<std::optional<Pose2>> out(initial.size());
  for (std::size_t n = 0; n < initial.size(); ++n) {
    if (initial[n]) out[n] = Pose2(x[n][0], x[n][1], x[n][2]);
  }
  return out;
}

EdgeError EdgeDisagreement(const PoseGraphEdge& edge, const Pose2& T_ref_a, const Pose2& T_ref_b) {
  const Pose2 delta = edge.T_a_b.inverse() * (T_ref_a.inverse() * T_ref_b);
  return {std::abs(delta.yaw_rad()), delta.translation_m().norm()};
}

}  // namespace fleetmerge
