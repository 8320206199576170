// One simulated robot's run: it explores the building (frontier-like goals, collision-free
// paths), scans every options.scan_spacing_m of path and maps each scan at its SLAM pose
// estimate in its own map frame. The estimate follows the true motion through odometry
// increments with an optional random-walk drift, and each scan gets an independent jitter
// (options.pose_noise); the estimate starts exact, so T_building_map stays the map's true pose.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "sim/simulation_options.hpp"

namespace fleetmerge {

struct RobotRun {
  OccupancyGrid map;                      // in the robot's map frame, cropped to its known cells
  std::vector<Pose2> T_building_scanner;  // true poses of the scans, in the building's frame
};

// `walkable`: the cells the robot may cross (TraversableCells, or its territory), `start` one of
// them. The map gets cells of `resolution_m`; its frame is at T_building_map.
RobotRun RunRobot(const OccupancyGrid& building, const cv::Mat1b& walkable,
                  const Eigen::Array2i& start, const Pose2& T_building_map, double resolution_m,
                  const SimulationOptions& options, std::uint32_t seed);

}  // namespace fleetmerge
