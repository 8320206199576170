// Distance from every cell to the nearest occupied cell of a map, truncated, with bicubic
// interpolation for Ceres: the target a map's walls are pulled onto in local refinement.
// Built once per map and shared by all the pairs that map is part of.
#pragma once

#include <ceres/cubic_interpolation.h>

#include <Eigen/Core>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "core/occupancy_grid.hpp"

namespace fleetmerge {

class WallDistanceField {
 public:
  using Grid = ceres::Grid2D<float, 1>;
  using Interpolator = ceres::BiCubicInterpolator<Grid>;

  // truncation_cells caps the distance: walls farther than that pull no more (and far outside
  // the grid the field is flat), so non-overlapping parts of the maps exert no force.
  WallDistanceField(const OccupancyGrid& grid, double truncation_cells);
  WallDistanceField(const WallDistanceField&) = delete;
  WallDistanceField& operator=(const WallDistanceField&) = delete;

  // Distance (cells) at a point of the grid frame given in cells; T may be a ceres::Jet.
  template <typename T>
  void Evaluate(const T& x_cells, const T& y_cells, T* distance) const {
    // Cell (i, j) has its centre at (i + .5, j + .5); the stored field starts at cell
    // `offset_` (the walls' bounding box less a margin). Beyond its edges the interpolator
    // repeats the border, which is the truncation value: flat, so no force.
    interpolator_->Evaluate(y_cells - (offset_.y() + 0.5), x_cells - (offset_.x() + 0.5), distance);
  }
  // The same with the gradient (d distance / d x, d distance / d y), for analytic Jacobians.
  void Evaluate(double x_cells, double y_cells, double* distance, double* d_dx,
                double* d_dy) const {
    interpolator_->Evaluate(y_cells - (offset_.y() + 0.5), x_cells - (offset_.x() + 0.5), distance,
                            d_dy, d_dx);
  }
  double truncation_cells() const { return truncation_cells_; }

 private:
  double truncation_cells_;
  Eigen::Array2i offset_;  // grid cell of distances_(0, 0)
  cv::Mat1f distances_;    // row r, column c = grid cell (c + offset_.x, r + offset_.y)
  std::unique_ptr<Grid> grid_;
  std::unique_ptr<Interpolator> interpolator_;
};

}  // namespace fleetmerge
