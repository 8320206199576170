#include "refine/local_alignment.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "core/point_sampling.hpp"  // OccupiedCellCenters

namespace fleetmerge {
namespace {

// sin and cos of the yaw, cached per thread: every residual of a problem (up to 2 x 1500) asks
// for the same yaw at each evaluation, and sincos was 6 % of a fleet merge (perf). The values are
// the ones std::sin and std::cos give, so results do not change. Keyed on the bits of the yaw
// (-0.0 and 0.0 have different sines).
void SinCosOfYaw(double yaw_rad, double* s, double* c) {
  thread_local std::uint64_t last_bits = 0x7ff8dead0000beefULL;  // a NaN: never a real key
  thread_local double last_s = 0.0, last_c = 0.0;
  std::uint64_t bits = 0;
  std::memcpy(&bits, &yaw_rad, sizeof bits);
  if (bits != last_bits) {
    last_s = std::sin(yaw_rad);
    last_c = std::cos(yaw_rad);
    last_bits = bits;
  }
  *s = last_s;
  *c = last_c;
}

// ceres::sin and ceres::cos (ceres/jet.h) with the scalar parts from SinCosOfYaw.
void SinCos(double yaw_rad, double* s, double* c) { SinCosOfYaw(yaw_rad, s, c); }
template <int N>
void SinCos(const ceres::Jet<double, N>& yaw, ceres::Jet<double, N>* s, ceres::Jet<double, N>* c) {
  double sa = 0.0, ca = 0.0;
  SinCosOfYaw(yaw.a, &sa, &ca);
  *s = ceres::Jet<double, N>(sa, ca * yaw.v);
  *c = ceres::Jet<double, N>(ca, -sa * yaw.v);
}

// r = D_target(T p) for a wall point p of the moving map; with `inverse`, r = D_target(T^-1 p).
// pose = (x_cells, y_cells, yaw_rad) of T = T_ga_gb.
struct WallDistanceResidual {
  WallDistanceResidual(const WallDistanceField& target, const Eigen::Vector2d& p, bool inverse)
      : target(target), p(p), inverse(inverse) {}

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    T s, c;
    SinCos(pose[2], &s, &c);
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
