#include "core/occupancy_grid.hpp"

#include <sstream>

#include "core/error.hpp"
#include "core/image_masks.hpp"

namespace fleetmerge {

OccupancyGrid::OccupancyGrid(const GridGeometry& geometry, CellState fill)
    : geometry_(geometry),
      cells_(geometry.height(), geometry.width(), static_cast<std::uint8_t>(fill)) {}

OccupancyGrid::OccupancyGrid(const GridGeometry& geometry, cv::Mat1b cells)
    : geometry_(geometry), cells_(std::move(cells)) {
  if (cells_.rows != geometry.height() || cells_.cols != geometry.width()) {
    std::ostringstream msg;
    msg << "occupancy grid: cell matrix is " << cells_.cols << " x " << cells_.rows
        << " but the geometry is " << geometry.width() << " x " << geometry.height();
    throw Error(msg.str());
  }
  double max_value = 0.0;
  if (!cells_.empty()) cv::minMaxLoc(cells_, nullptr, &max_value);
  if (max_value > static_cast<double>(CellState::kOccupied)) {
    throw Error("occupancy grid: cell values must be 0 (unknown), 1 (free) or 2 (occupied)");
  }
}

std::vector<Eigen::Array2i> OccupancyGrid::CellsIn(CellState state) const {
  std::vector<Eigen::Array2i> out;
  const auto value = static_cast<std::uint8_t>(state);
  for (int j = 0; j < cells_.rows; ++j) {
    const std::uint8_t* row = cells_.ptr<std::uint8_t>(j);
    for (int i = 0; i < cells_.cols; ++i) {
      if (row[i] == value) out.emplace_back(i, j);
    }
  }
  return out;
}

int OccupancyGrid::Count(CellState state) const {
  return cells_.empty()
             ? 0
             : cv::countNonZero(CompareMask(cells_, cv::CMP_EQ, static_cast<int>(state)));
}

}  // namespace fleetmerge
