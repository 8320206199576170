#include "refine/local_alignment.hpp"

#include <ceres/tiny_solver.h>

#include <algorithm>
#include <cmath>

#include "core/point_sampling.hpp"  // OccupiedCellCenters

namespace fleetmerge {
namespace {

// Both directions' wall points as one residual vector, with analytic derivatives, for
// ceres::TinySolver: three parameters and a few thousand residuals. Ceres' general solver spent
// about half as long on its per-residual bookkeeping (validity checks, Jacobian copies and
// scaling, a QR of the N x 3 Jacobian) as on the residuals themselves (docs/speed.md);
// TinySolver solves the 3 x 3 normal equations.
//
// The Cauchy loss is folded into the residuals: r_i = sign(d_i) sqrt(rho(d_i^2)), so that
// 1/2 sum r_i^2 = 1/2 sum rho(d_i^2) is the robust cost of the per-point formulation, with
// d_i = D_a(T p_i) for b's wall points p_i and D_b(T^-1 q_i) for a's wall points q_i, and
// rho(s) = b log(1 + s / b), b = loss_scale^2 (ceres::CauchyLoss). Parameters: the pose
// (x_cells, y_cells, yaw_rad) of T = T_ga_gb.
class WallDistanceResiduals {
 public:
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = 3 };

  WallDistanceResiduals(const AlignmentTarget& a, const AlignmentTarget& b,
                        const LocalAlignmentOptions& options)
      : field_a_(a.field),
        field_b_(b.field),
        points_b_(EveryKth(b.wall_points, options)),
        points_a_(EveryKth(a.wall_points, options)),
        b_(options.loss_scale_cells * options.loss_scale_cells),
        flat_a_(FlatResidual(a.field)),
        flat_b_(FlatResidual(b.field)) {}

  int NumResiduals() const { return static_cast<int>(points_b_.size() + points_a_.size()); }

  // `jacobian`: NumResiduals() x 3, column-major (TinySolver's layout), or null.
  bool operator()(const double* pose, double* residuals, double* jacobian) const {
    const int n = NumResiduals();
    const int n_b = static_cast<int>(points_b_.size());
    Direction</*kInverse=*/false>(pose, points_b_, field_a_, flat_a_, residuals, jacobian, n);
    Direction</*kInverse=*/true>(pose, points_a_, field_b_, flat_b_, residuals + n_b,
                                 jacobian != nullptr ? jacobian + n_b : nullptr, n);
    return true;
  }

 private:
  // The residuals of one direction's points against `target`, from row 0 of `residuals` and
  // `jacobian` (whose columns are n apart).
  template <bool kInverse>
  void Direction(const double* pose, const std::vector<Eigen::Vector2d>& points,
                 const WallDistanceField& target, double flat_residual, double* residuals,
                 double* jacobian, int n) const {
    const double s = std::sin(pose[2]), c = std::cos(pose[2]);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector2d& p = points[i];
      // The point in the target's grid and its derivatives by (x, y, yaw).
      double x, y;
      Eigen::Matrix<double, 2, 3> dxy_dpose;
      if (!kInverse) {  // T p = R p + t
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
      if (target.Evaluate(x, y, &d, &dd_dx, &dd_dy)) {
        // No wall of the target near the point: the truncation's constant residual, no slope.
        residuals[i] = flat_residual;
        if (jacobian != nullptr) {
          for (int k = 0; k < 3; ++k) jacobian[i + k * n] = 0.0;
        }
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
        for (int k = 0; k < 3; ++k) jacobian[i + k * n] = row[k];
      }
    }
  }

  // Every k-th point, k chosen so that at most max_points are used.
  static std::vector<Eigen::Vector2d> EveryKth(const std::vector<Eigen::Vector2d>& points,
                                               const LocalAlignmentOptions& options) {
    const std::size_t max_points = std::max(options.max_points, 1);
    const std::size_t step =
        std::max<std::size_t>((points.size() + max_points - 1) / max_points, 1);
    std::vector<Eigen::Vector2d> out;
    out.reserve(points.size() / step + 1);
    for (std::size_t k = 0; k < points.size(); k += step) out.push_back(points[k]);
    return out;
  }
  // The residual where the field is flat (at the truncation value).
  double FlatResidual(const WallDistanceField& field) const {
    const double truncation = static_cast<float>(field.truncation_cells());  // as the field
    return std::sqrt(b_ * std::log1p(truncation * truncation / b_));
  }

  const WallDistanceField& field_a_;
  const WallDistanceField& field_b_;
  std::vector<Eigen::Vector2d> points_b_;  // pulled onto a's walls
  std::vector<Eigen::Vector2d> points_a_;  // pulled onto b's walls
  double b_;                               // Cauchy scale squared
  double flat_a_, flat_b_;
};

std::vector<Eigen::Vector2d> ToDouble(const std::vector<Eigen::Vector2f>& points) {
  std::vector<Eigen::Vector2d> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(p.cast<double>());
  return out;
}

}  // namespace

AlignmentTarget::AlignmentTarget(const OccupancyGrid& grid, double truncation_cells)
    : AlignmentTarget(OccupiedCellCenters(grid), truncation_cells) {}

AlignmentTarget::AlignmentTarget(const std::vector<Eigen::Vector2f>& wall_centres,
                                 double truncation_cells)
    : field(wall_centres, truncation_cells), wall_points(ToDouble(wall_centres)) {}

AlignmentTarget::AlignmentTarget(const std::vector<Eigen::Vector2f>& wall_centres,
                                 double truncation_cells, const Eigen::Array2i& offset_cells,
                                 const cv::Mat1f& distances, const cv::Mat1b& flat)
    : field(truncation_cells, offset_cells, distances, flat), wall_points(ToDouble(wall_centres)) {}

LocalAlignmentResult RefineAlignment(const AlignmentTarget& a, const AlignmentTarget& b,
                                     const Pose2& T_ga_gb_initial,
                                     const LocalAlignmentOptions& options) {
  const WallDistanceResiduals residuals(a, b, options);
  const int n = residuals.NumResiduals();
  Eigen::Vector3d pose(T_ga_gb_initial.x_m(), T_ga_gb_initial.y_m(), T_ga_gb_initial.yaw_rad());
  LocalAlignmentResult result;
  if (n == 0) {
    result.T_ga_gb = T_ga_gb_initial;
    result.converged = true;
    return result;
  }
  // TinySolver stops on an absolute change of 2 x cost, so the relative tolerance is scaled by
  // the starting cost (the refinement starts near its minimum: the cost falls by ~1 %).
  Eigen::VectorXd start(n);
  residuals(pose.data(), start.data(), nullptr);
  ceres::TinySolver<WallDistanceResiduals> solver;
  solver.options.max_num_iterations = options.max_iterations + 1;  // counts the first evaluation
  solver.options.function_tolerance = options.function_tolerance * start.squaredNorm();
  const auto& summary = solver.Solve(residuals, &pose);

  result.T_ga_gb = Pose2(pose[0], pose[1], pose[2]);
  result.cost = summary.final_cost / n;
  result.converged = std::isfinite(summary.final_cost) && pose.allFinite();
  return result;
}

}  // namespace fleetmerge
