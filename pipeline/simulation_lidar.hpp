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
#include "pipeline/portable_rng.hpp"
#include "pipeline/simulation_options.hpp"

namespace fleetmerge {

// Visits the cells that the segment from p0 to p1 crosses, p0's cell first; points are in cell
// units of a grid frame (cell (i, j) spans [i, i+1) x [j, j+1)). visit(cell, t_enter) gets the
// distance from p0 (in cells) at which the segment enters the cell (0 for p0's cell) and returns
// false to stop early.
template <typename Visit>
void TraverseSegment(const Eigen::Vector2d& p0, const Eigen::Vector2d& p1, Visit&& visit) {
  const Eigen::Vector2d delta = p1 - p0;
  const double length = delta.norm();
  Eigen::Array2i cell(static_cast<int>(std::floor(p0.x())), static_cast<int>(std::floor(p0.y())));
  const Eigen::Array2i last(static_cast<int>(std::floor(p1.x())),
                            static_cast<int>(std::floor(p1.y())));
  if (!visit(cell, 0.0) || length == 0.0) return;
  const Eigen::Vector2d dir = delta / length;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  int step[2];
  double t_max[2], t_delta[2];  // distance to the next boundary per axis; between boundaries
  for (int a = 0; a < 2; ++a) {
    step[a] = dir[a] > 0 ? 1 : -1;
    if (dir[a] == 0.0) {
      t_max[a] = t_delta[a] = kInf;
      continue;
    }
    const double boundary = dir[a] > 0 ? std::floor(p0[a]) + 1.0 : std::floor(p0[a]);
    t_max[a] = (boundary - p0[a]) / dir[a];
    t_delta[a] = std::abs(1.0 / dir[a]);
  }
  while (!(cell == last).all()) {
    const int a = t_max[0] < t_max[1] ? 0 : 1;
    const double t_enter = t_max[a];
    if (t_enter > length) return;  // rounding: p1 lies on a boundary
    cell[a] += step[a];
    t_max[a] += t_delta[a];
    if (!visit(cell, t_enter)) return;
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
