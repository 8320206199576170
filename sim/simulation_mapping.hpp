// One simulated robot's own occupancy grid, built from its scans at its (estimated) poses as a
// SLAM front end would: an axis-aligned grid in the robot's map frame, so the building appears
// rotated in it. Each beam counts a miss in every cell it crosses before its end and a hit (a
// return) or a miss (no return) in the cell where it ends; a cell is occupied when its hits
// reach `occupied_ratio` of its visits (GMapping's counting model, occ_thresh 0.25), free when
// visited otherwise, unknown when never visited.
#pragma once

#include <opencv2/core.hpp>

#include "core/grid_geometry.hpp"
#include "core/occupancy_grid.hpp"
#include "sim/simulation_lidar.hpp"

namespace fleetmerge {

class RobotMapper {
 public:
  // `geometry`: the grid the counts are kept on (axis-aligned in the map frame, large enough for
  // everything the robot can see; beams leaving it are cut at its edge).
  RobotMapper(const GridGeometry& geometry, double occupied_ratio);

  // Adds one scan taken at T_map_sensor (the sensor's pose in the robot's map frame).
  void Integrate(const LidarScan& scan, const Pose2& T_map_sensor);

  // The trinary map, cropped to the bounding box of its known cells (the grid frame moves, the
  // map frame does not). Empty (0 x 0) if nothing was observed.
  OccupancyGrid ToGrid() const;

 private:
  GridGeometry geometry_;
  double occupied_ratio_;
  cv::Mat1i hits_, visits_;
};

// A grid at `resolution_m`, axis-aligned in the map frame, that covers `building`'s whole grid
// as seen from a map frame at T_building_map, plus `margin_m` on every side.
GridGeometry MapperGeometry(const GridGeometry& building, const Pose2& T_building_map,
                            double resolution_m, double margin_m);

}  // namespace fleetmerge
