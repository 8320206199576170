#include "core/grid_geometry.hpp"

#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace fleetmerge {

GridGeometry::GridGeometry(double resolution_m, const Eigen::Array2i& size_cells,
                           const Pose2& T_map_grid)
    : resolution_m_(resolution_m), size_cells_(size_cells), T_map_grid_(T_map_grid) {
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m)) {
    std::ostringstream msg;
    msg << "grid resolution must be a finite number > 0 m, got " << resolution_m;
    throw Error(msg.str());
  }
  if ((size_cells < 0).any()) {
    std::ostringstream msg;
    msg << "grid size must be >= 0 cells, got " << size_cells.x() << " x " << size_cells.y();
    throw Error(msg.str());
  }
}

Eigen::Array2i GridGeometry::CellOfGridPoint(const Eigen::Vector2d& p_grid) const {
  return (p_grid.array() / resolution_m_).floor().cast<int>();
}

}  // namespace fleetmerge
