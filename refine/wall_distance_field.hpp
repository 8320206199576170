// Distance from every cell to the nearest occupied cell of a map, truncated, with bicubic
// interpolation (Ceres' BiCubicInterpolator): the target a map's walls are pulled onto in local
// refinement. Built once per map and shared by all the pairs that map is part of.
#pragma once

#include <ceres/cubic_interpolation.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "core/occupancy_grid.hpp"

namespace fleetmerge {

class WallDistanceField {
 public:
  // ceres::Grid2D<float, 1> of the field (rows and columns from 0, clamped at the border)
  // without Grid2D's constructor checks: they are glog CHECKs, and glog (with gflags and
  // libunwind) would be loaded by every `fleetmerge pair` for them (~1.5 ms of start-up).
  struct Grid {
    enum { DATA_DIMENSION = 1 };
    const float* data;
    int rows, cols;
    void GetValue(int r, int c, double* f) const {
      *f =
          static_cast<double>(data[std::clamp(r, 0, rows - 1) * cols + std::clamp(c, 0, cols - 1)]);
    }
  };
  using Interpolator = ceres::BiCubicInterpolator<Grid>;

  // truncation_cells caps the distance: walls farther than that pull no more (and far outside
  // the grid the field is flat), so non-overlapping parts of the maps exert no force.
  WallDistanceField(const OccupancyGrid& grid, double truncation_cells);
  // The same field from the grid's OccupiedCellCenters, where the caller has them already.
  WallDistanceField(const std::vector<Eigen::Vector2f>& wall_centres, double truncation_cells);
  // A field made before (a cache's, pipeline/pair_cache.hpp) from what offset(), distances() and
  // flat() gave: the same field. Throws fleetmerge::Error when the two grids differ in size or
  // are empty.
  WallDistanceField(double truncation_cells, const Eigen::Array2i& offset_cells,
                    const cv::Mat1f& distances, const cv::Mat1b& flat);
  WallDistanceField(const WallDistanceField&) = delete;
  WallDistanceField& operator=(const WallDistanceField&) = delete;

  // Distance (cells) at a point of the grid frame given in cells, with its gradient (d distance
  // / d x, d distance / d y) for analytic Jacobians. Cell (i, j) has its centre at (i + .5,
  // j + .5); the stored field starts at cell `offset_` (the walls' bounding box less a margin),
  // and beyond its edges the interpolator repeats the border, which is the truncation value.
  // Returns true where the field is flat (the truncation value, gradient 0): there the
  // interpolation is skipped, with the result it would have given (bicubic Hermite splines
  // through equal samples are that value exactly, slope 0).
  bool Evaluate(double x_cells, double y_cells, double* distance, double* d_dx,
                double* d_dy) const {
    const double r = y_cells - (offset_.y() + 0.5), c = x_cells - (offset_.x() + 0.5);
    if (IsFlat(r, c)) {
      *distance = static_cast<double>(static_cast<float>(truncation_cells_));
      *d_dx = *d_dy = 0.0;
      return true;
    }
    interpolator_->Evaluate(r, c, distance, d_dy, d_dx);
    return false;
  }
  double truncation_cells() const { return truncation_cells_; }
  const Eigen::Array2i& offset() const { return offset_; }
  const cv::Mat1f& distances() const { return distances_; }
  const cv::Mat1b& flat() const { return flat_; }

 private:
  // Whether the 4 x 4 samples the interpolator reads at (r, c) (rows floor(r) - 1 ..
  // floor(r) + 2, clamped at the border) are all the truncation value. Most wall points of a
  // pair lie where the other map has no wall nearby (the maps overlap in part): perf put the
  // interpolation at 10-15 % of a fleet merge.
  bool IsFlat(double r, double c) const {
    if (!(r > -2.0 && r < flat_.rows + 1.0 && c > -2.0 && c < flat_.cols + 1.0)) {
      // Beyond the border the samples repeat it, which is the truncation value. NaN lands here
      // too: flat, where Ceres would convert floor(NaN) to int (undefined behaviour).
      return true;
    }
    // A stencil clamped at the border reads a subset of the clamped cell's own stencil.
    const int row = std::clamp(static_cast<int>(std::floor(r)), 0, flat_.rows - 1);
    const int col = std::clamp(static_cast<int>(std::floor(c)), 0, flat_.cols - 1);
    return flat_(row, col) != 0;
  }
  double truncation_cells_;
  Eigen::Array2i offset_;  // grid cell of distances_(0, 0)
  cv::Mat1f distances_;    // row r, column c = grid cell (c + offset_.x, r + offset_.y)
  cv::Mat1b flat_;         // 1 where the interpolation stencil at (r, c) is all truncation
  std::unique_ptr<Grid> grid_;
  std::unique_ptr<Interpolator> interpolator_;
};

}  // namespace fleetmerge
