// The simulator's 2-D lidar: beams ray-cast against a building's occupancy grid, and the grid
// traversal both the lidar and the robots' mapping use.
//
// TraverseSegment is Amanatides and Woo's DDA ("A Fast Voxel Traversal Algorithm for Ray
// Tracing", 1987): it visits every cell a segment crosses, in order, so a beam cannot slip
// between two diagonally touching wall cells (a Bresenham line can) and each visited cell comes
// with the distance at which the beam enters it (the range of a wall's surface).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "sim/portable_rng.hpp"
#include "sim/simulation_options.hpp"

namespace fleetmerge {

// Visits the cells that the segment from p0 to p1 crosses, p0's cell first; points are in cell
// units of a grid frame (cell (i, j) spans [i, i+1) x [j, j+1)). visit(i, j, t_enter) gets the
// distance from p0 (in cells) at which the segment enters the cell (0 for p0's cell) and returns
// false to stop early. Plain ints and doubles in the loop: it is the simulator's inner loop.
template <typename Visit>
void TraverseSegment(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, Visit&& visit) {
  const double dx = p1.x() - p0.x(), dy = p1.y() - p0.y();
  const double length = std::sqrt(dx * dx + dy * dy);
  int i = static_cast<int>(std::floor(p0.x())), j = static_cast<int>(std::floor(p0.y()));
  const int last_i = static_cast<int>(std::floor(p1.x()));
  const int last_j = static_cast<int>(std::floor(p1.y()));
  if (!visit(i, j, 0.0) || length == 0.0) return;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const int step_i = dx > 0 ? 1 : -1, step_j = dy > 0 ? 1 : -1;
  // Distance along the segment to the next vertical (i) and horizontal (j) cell boundary, and
  // between two boundaries of each kind.
  const double delta_i = dx == 0.0 ? kInf : std::abs(length / dx);
  const double delta_j = dy == 0.0 ? kInf : std::abs(length / dy);
  double next_i = dx == 0.0 ? kInf : ((dx > 0 ? i + 1.0 : double(i)) - p0.x()) * (length / dx);
  double next_j = dy == 0.0 ? kInf : ((dy > 0 ? j + 1.0 : double(j)) - p0.y()) * (length / dy);
  while (i != last_i || j != last_j) {
    double t_enter = 0.0;
    if (next_i < next_j) {
      t_enter = next_i;
      i += step_i;
      next_i += delta_i;
    } else {
      t_enter = next_j;
      j += step_j;
      next_j += delta_j;
    }
    if (t_enter > length) return;  // rounding: p1 lies on a boundary
    if (!visit(i, j, t_enter)) return;
  }
}

// One scan: per beam, the range and whether it ended on a wall (a return) or not (nothing within
// range, or the beam left the building's known cells: no return, the range is where it stopped).
struct LidarScan {
  double first_angle_rad = 0.0;    // beam k points at first_angle_rad + k * angle_step_rad
  double angle_step_rad = 0.0;     // in the sensor frame
  std::vector<double> ranges_m;    // per beam
  std::vector<unsigned char> hit;  // per beam: 1 = return from an occupied cell
};

// Casts options.beams beams from T_building_sensor (the sensor's pose in the building's map
// frame) through `building` and adds Gaussian range noise to the returns. A beam stops at the
// first occupied cell (return at its surface), unknown cell or the grid's edge (no return), or at
// range_m. If `seen` (the building's size, CV_8U) is given, every cell a beam reached is set
// to 255: what this scan observed of the building.
LidarScan CastScan(const OccupancyGrid& building, const Pose2& T_building_sensor,
                   const LidarOptions& options, PortableRng& rng, cv::Mat1b* seen = nullptr);

}  // namespace fleetmerge
