#include "refine/local_alignment.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "core/point_sampling.hpp"  // OccupiedCellCenters

namespace fleetmerge {
namespace {

// All wall points of one direction in one cost function, with analytic derivatives. One
// residual block per point (autodiff, a CauchyLoss each) spent most of a refinement in Ceres'
// per-block bookkeeping, not in the distance field (perf: 15 % of a pair in AutoDiff
// evaluation, 5 % in AddResidualBlock).
//
// The Cauchy loss is folded into the residuals: r_i = sign(d_i) sqrt(rho(d_i^2)), so that
// 1/2 sum r_i^2 = 1/2 sum rho(d_i^2) is the robust cost of the per-point formulation, with
// d_i = D_target(T p_i) (or D_target(T^-1 p_i) with `inverse`) and
// rho(s) = b log(1 + s / b), b = loss_scale^2 (ceres::CauchyLoss). Parameters: the pose
// (x_cells, y_cells, yaw_rad) of T = T_ga_gb.
class WallDistanceCost : public ceres::CostFunction {
 public:
  WallDistanceCost(const WallDistanceField& target, std::vector<Eigen::Vector2d> points,
                   bool inverse, double loss_scale_cells)
      : target_(target),
        points_(std::move(points)),
        inverse_(inverse),
        b_(loss_scale_cells * loss_scale_cells) {
    const double truncation = static_cast<float>(target.truncation_cells());  // as the field
    flat_residual_ = std::sqrt(b_ * std::log1p(truncation * truncation / b_));
    set_num_residuals(static_cast<int>(points_.size()));
    mutable_parameter_block_sizes()->push_back(3);
  }

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const double* pose = parameters[0];
    const double s = std::sin(pose[2]), c = std::cos(pose[2]);
    double* jacobian = jacobians != nullptr ? jacobians[0] : nullptr;
    for (std::size_t i = 0; i < points_.size(); ++i) {
      const Eigen::Vector2d& p = points_[i];
      // The point in the target's grid and its derivatives by (x, y, yaw).
      double x, y;
      Eigen::Matrix<double, 2, 3> dxy_dpose;
      if (!inverse_) {  // T p = R p + t
        x = c * p.x() - s * p.y() + pose[0];
        y = s * p.x() + c * p.y() + pose[1];
        dxy_dpose << 1.0, 0.0, -(y - pose[1]),  //
            0.0, 1.0, x - pose[0];
      } else {  // T^-1 p = R^T (p - t)
        const double dx = p.x() - pose[0], dy = p.y() - pose[1];
        x = c * dx + s * dy;
        y = -s * dx + c * dy;
        dxy_dpose << -c, -s, y,  //
            s, -c, -x;
      }
      double d = 0.0, dd_dx = 0.0, dd_dy = 0.0;
      if (target_.Evaluate(x, y, &d, &dd_dx, &dd_dy)) {
        // No wall of the target near the point: the truncation's constant residual, no slope.
        residuals[i] = flat_residual_;
        if (jacobian != nullptr) std::fill_n(jacobian + 3 * i, 3, 0.0);
        continue;
      }
      // r = sign(d) sqrt(rho(d^2)); dr/dd = rho'(d^2) |d| / sqrt(rho(d^2)), which tends to 1
      // as d -> 0 (rho(s) ~ s there).
      const double squared = d * d;
      const double rho = b_ * std::log1p(squared / b_);
      const double root = std::sqrt(rho);
      residuals[i] = std::copysign(root, d);
      if (jacobian != nullptr) {
        const double dr_dd = root > 0.0 ? std::abs(d) / (1.0 + squared / b_) / root : 1.0;
        const Eigen::RowVector3d row =
            dr_dd * (dd_dx * dxy_dpose.row(0) + dd_dy * dxy_dpose.row(1));
        for (int k = 0; k < 3; ++k) jacobian[3 * i + k] = row[k];
      }
    }
    return true;
  }

 private:
  const WallDistanceField& target_;
  std::vector<Eigen::Vector2d> points_;
  bool inverse_;
  double b_;              // Cauchy scale squared
  double flat_residual_;  // the residual where the field is flat (at the truncation value)
};

std::vector<Eigen::Vector2d> ToDouble(const std::vector<Eigen::Vector2f>& points) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(p.cast<double>());
  return out;
}

// Every k-th point, k chosen so that at most max_points are used.
std::vector<Eigen::Vector2d> EveryKth(const std::vector<Eigen::Vector2d>& points,
                                      const LocalAlignmentOptions& options) {
  const std::size_t max_points = std::max(options.max_points, 1);
  const std::size_t step = std::max<std::size_t>((points.size() + max_points - 1) / max_points, 1);
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size() / step + 1);
  for (std::size_t k = 0; k < points.size(); k += step) out.push_back(points[k]);
  return out;
}

// Adds the residuals of `points` against `target`; returns how many.
int AddResiduals(ceres::Problem& problem, double* pose, const WallDistanceField& target,
                 const std::vector<Eigen::Vector2d>& points, bool inverse,
                 const LocalAlignmentOptions& options) {
  std::vector<Eigen::Vector2d> used = EveryKth(points, options);
  const int n = static_cast<int>(used.size());
  if (n == 0) return 0;
  problem.AddResidualBlock(
      new WallDistanceCost(target, std::move(used), inverse, options.loss_scale_cells), nullptr,
      pose);
  return n;
}

}  // namespace

AlignmentTarget::AlignmentTarget(const OccupancyGrid& grid, double truncation_cells)
    : AlignmentTarget(OccupiedCellCenters(grid), truncation_cells) {}

AlignmentTarget::AlignmentTarget(const std::vector<Eigen::Vector2f>& wall_centres,
                                 double truncation_cells)
    : field(wall_centres, truncation_cells), wall_points(ToDouble(wall_centres)) {}

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
