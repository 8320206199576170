// A three-state occupancy grid (Section III: traversable, occupied, unknown) on a GridGeometry.
// Cells are stored in a CV_8UC1 matrix whose row j is grid row j counted from the bottom (the
// map frame's +y), so cells()(j, i) is cell (i, j): no image-row flip inside core/.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "core/grid_geometry.hpp"

namespace fleetmerge {

// The largest map (in cells) loaded unless the user raises the limit (--max-map-cells, job key
// max_map_cells): 10000 x 10000 cells, 500 m x 500 m at 5 cm, 40 times the largest real map we
// have (gdc_floor2_full, 2.5 M cells). Merging holds several float/double images per map (Hough
// voting, distance fields, FFT correlation), tens of bytes per cell, so this is already a
// multi-gigabyte job; a corrupt header claiming 100000 x 100000 cells is refused outright.
inline constexpr std::int64_t kDefaultMaxMapCells = 100'000'000;

enum class CellState : std::uint8_t { kUnknown = 0, kFree = 1, kOccupied = 2 };

class OccupancyGrid {
 public:
  OccupancyGrid() = default;
  explicit OccupancyGrid(const GridGeometry& geometry, CellState fill = CellState::kUnknown);
  // Takes a CV_8UC1 matrix of CellState values (rows from the bottom); throws if the type, size
  // or a value is wrong.
  OccupancyGrid(const GridGeometry& geometry, cv::Mat1b cells);

  const GridGeometry& geometry() const { return geometry_; }
  int width() const { return geometry_.width(); }
  int height() const { return geometry_.height(); }

  CellState at(const Eigen::Array2i& cell) const {
    return static_cast<CellState>(cells_(cell.y(), cell.x()));
  }
  // State of a cell, kUnknown outside the grid.
  CellState StateOrUnknown(const Eigen::Array2i& cell) const {
    return geometry_.Contains(cell) ? at(cell) : CellState::kUnknown;
  }
  void set(const Eigen::Array2i& cell, CellState state) {
    cells_(cell.y(), cell.x()) = static_cast<std::uint8_t>(state);
  }

  const cv::Mat1b& cells() const { return cells_; }
  cv::Mat1b& mutable_cells() { return cells_; }

  std::vector<Eigen::Array2i> CellsIn(CellState state) const;
  int Count(CellState state) const;

 private:
  GridGeometry geometry_;
  cv::Mat1b cells_;
};

// The cell (floor(x), floor(y)) of a point in a grid's cell units, when it is one of the grid's,
// found without std::floor: x86-64's baseline, which Debian's packages target, has no rounding
// instruction and emulates floor in about a dozen instructions a coordinate. A coordinate is
// outside [0, size) exactly when its floor is, and inside it the int cast is the floor: the same
// cells. Made once per loop (the lookups of wall counts and overlap centres).
class CellOfPoint {
 public:
  explicit CellOfPoint(const OccupancyGrid& grid) : width_(grid.width()), height_(grid.height()) {}
  // False when p is outside the grid (or not a number).
  bool operator()(const Eigen::Vector2d& p, int* i, int* j) const {
    if (!(p.x() >= 0.0 && p.y() >= 0.0 && p.x() < width_ && p.y() < height_)) return false;
    *i = static_cast<int>(p.x());
    *j = static_cast<int>(p.y());
    return true;
  }

 private:
  double width_, height_;
};

}  // namespace fleetmerge
