#include "refine/local_alignment.hpp"

#include <ceres/ceres.h>

#include <algorithm>

#include "core/point_sampling.hpp"  // OccupiedCellCenters

namespace fleetmerge {
namespace {

// r = D_target(T p) for a wall point p of the moving map; with `inverse`, r = D_target(T^-1 p).
// pose = (x_cells, y_cells, yaw_rad) of T = T_ga_gb.
struct WallDistanceResidual {
  WallDistanceResidual(const WallDistanceField& target, const Eigen::Vector2d& p, bool inverse)
      : target(target), p(p), inverse(inverse) {}

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    const T c = ceres::cos(pose[2]), s = ceres::sin(pose[2]);
    T x, y;
    if (!inverse) {  // T p = R p + t
      x = c * p.x() - s * p.y() + pose[0];
      y = s * p.x() + c * p.y() + pose[1];
    } else {  // T^-1 p = R^T (p - t)
      const T dx = p.x() - pose[0], dy = p.y() - pose[1];
      x = c * dx + s * dy;
      y = -s * dx + c * dy;
    }
    target.Evaluate(x, y, residual);
    return true;
  }

  const WallDistanceField& target;
  Eigen::Vector2d p;
  bool inverse;
};

std::vector<Eigen::Vector2d> WallPoints(const OccupancyGrid& grid) {
  std::vector<Eigen::Vector2d> out;
  for (const auto& p : OccupiedCellCenters(grid)) out.push_back(p.cast<double>());
  return out;
}

// Adds one residual for every k-th point, k chosen so that at most max_points are used.
int AddResiduals(ceres::Problem& problem, double* pose, const WallDistanceField& target,
                 const std::vector<Eigen::Vector2d>& points, bool inverse,
                 const LocalAlignmentOptions& options) {
  const std::size_t max_points = std::max(options.max_points, 1);
  const std::size_t step = (points.size() + max_points - 1) / max_points;
  int added = 0;
  for (std::size_t k = 0; k < points.size(); k += std::max<std::size_t>(step, 1), ++added) {
    const Eigen::Vector2d& p = points[k];
    auto* cost = new ceres::AutoDiffCostFunction<WallDistanceResidual, 1, 3>(
        new WallDistanceResidual(target, p, inverse));
    problem.AddResidualBlock(cost, new ceres::CauchyLoss(options.loss_scale_cells), pose);
  }
  return added;
}

}  // namespace

AlignmentTarget::AlignmentTarget(const OccupancyGrid& grid, double truncation_cells)
    : field(grid, truncation_cells), wall_points(WallPoints(grid)) {}

LocalAlignmentResult RefineAlignment(const AlignmentTarget& a, const AlignmentTarget& b,
                                     const Pose2& T_ga_gb_initial,
                                     const LocalAlignmentOptions& options) {
  double pose[3] = {T_ga_gb_initial.x_m(), T_ga_gb_initial.y_m(), T_ga_gb_initial.yaw_rad()};
  ceres::Problem problem;
  const int n = AddResiduals(problem, pose, a.field, b.wall_points, /*inverse=*/false, options) +
                AddResiduals(problem, pose, b.field, a.wall_points, /*inverse=*/true, options);

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_QR;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.num_threads = 1;  // pairs run in parallel one level up
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);

  LocalAlignmentResult result;
  result.T_ga_gb = Pose2(pose[0], pose[1], pose[2]);
  result.cost = n > 0 ? summary.final_cost / n : 0.0;
  result.converged = summary.IsSolutionUsable();
  return result;
}

}  // namespace fleetmerge
