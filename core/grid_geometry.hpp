// The one place that converts between map-frame points (metres) and grid cells.
//
// ROS map_server convention: `origin` is the pose, in the map frame, of the lower-left corner of
// cell (0, 0). Cell (i, j) is column i counted from the left and row j counted from the BOTTOM
// (io/ flips image rows on load). Its centre is origin * ((i + 0.5) r, (j + 0.5) r). The "grid
// frame" is the frame attached to that corner, axis-aligned with the cells.
#pragma once

#include <Eigen/Core>

#include "core/pose2.hpp"

namespace fleetmerge {

class GridGeometry {
 public:
  GridGeometry() = default;
  // Throws fleetmerge::Error unless resolution_m > 0 and both sizes >= 0.
  GridGeometry(double resolution_m, const Eigen::Array2i& size_cells, const Pose2& T_map_grid = {});

  double resolution_m() const { return resolution_m_; }
  const Eigen::Array2i& size() const { return size_cells_; }
  int width() const { return size_cells_.x(); }
  int height() const { return size_cells_.y(); }
  // Pose of the grid frame (lower-left corner of cell (0, 0)) in the map frame.
  const Pose2& T_map_grid() const { return T_map_grid_; }

  bool Contains(const Eigen::Array2i& cell) const {
    return (cell >= 0).all() && (cell < size_cells_).all();
  }
  // Centre of a cell, in the grid frame and in the map frame.
  Eigen::Vector2d CellCenterInGrid(const Eigen::Array2i& cell) const {
    return (cell.cast<double>() + 0.5).matrix() * resolution_m_;
  }
  Eigen::Vector2d CellCenter(const Eigen::Array2i& cell) const {
    return T_map_grid_ * CellCenterInGrid(cell);
  }
  // The cell containing a point (it may lie outside the grid: check with Contains).
  Eigen::Array2i CellOfGridPoint(const Eigen::Vector2d& p_grid) const;
  Eigen::Array2i CellOf(const Eigen::Vector2d& p_map) const {
    return CellOfGridPoint(T_map_grid_.inverse() * p_map);
  }

 private:
  double resolution_m_ = 0.05;
  Eigen::Array2i size_cells_ = Eigen::Array2i::Zero();
  Pose2 T_map_grid_;
};

}  // namespace fleetmerge
