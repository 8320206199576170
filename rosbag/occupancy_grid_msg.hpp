// nav_msgs/OccupancyGrid as recorded in bags (ROS 1 and ROS 2 carry the same fields), decoded
// from its wire form, and its conversion to the grid fleetmerge merges; and the inverse, a grid
// encoded as a ROS 2 message (for the result set's merged_bag/, rosbag/merged_bag.hpp).
//
// Conversion follows map_saver's defaults, so that a map read from a bag is the map a user gets
// by `map_saver` then loading the YAML: a cell value v (occupancy percent) is free when
// 0 <= v <= 25, occupied when v >= 65, unknown otherwise (-1, 26..64, and anything above 100).
// The origin pose's yaw comes from its quaternion (a map is planar; z, roll and pitch are
// dropped). Grid row 0 of the message is the bottom row, as in core/ (no flip).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "core/occupancy_grid.hpp"

namespace fleetmerge {

struct OccupancyGridMsg {
  std::int64_t stamp_ns = 0;  // header.stamp
  std::string frame_id;       // header.frame_id
  double resolution_m = 0.0;  // float32 on the wire
  std::uint32_t width = 0, height = 0;
  double origin_x_m = 0.0, origin_y_m = 0.0, origin_z_m = 0.0;
  double qx = 0.0, qy = 0.0, qz = 0.0, qw = 1.0;
  std::string_view data;  // width * height int8 cells, row-major from the bottom row
};

// ROS 1 serialization (little-endian, no alignment). `context` names the bag and topic in errors.
OccupancyGridMsg DecodeRos1OccupancyGrid(std::string_view bytes, const std::string& context);

// ROS 2 CDR (XCDR1 plain, little- or big-endian encapsulation header; fields aligned to their
// size relative to the end of the 4-byte header).
OccupancyGridMsg DecodeCdrOccupancyGrid(std::string_view bytes, const std::string& context);

// Checks the message (finite resolution > 0, finite origin, a unit-ish quaternion, data size ==
// width * height, at most max_cells cells) and converts it. Throws fleetmerge::Error starting
// with `context` saying what was wrong.
OccupancyGrid OccupancyGridFromMsg(const OccupancyGridMsg& msg, const std::string& context,
                                   std::int64_t max_cells);

// The grid as a ROS 2 CDR nav_msgs/msg/OccupancyGrid, as map_server publishes a map: free 0,
// occupied 100, unknown -1, row-major from the bottom row (no flip, as in core/); info.origin
// the grid's T_map_grid with its yaw as a quaternion about z; header.stamp and
// info.map_load_time `stamp_ns`. OccupancyGridFromMsg of its decoding gives the grid back.
std::string EncodeCdrOccupancyGrid(const OccupancyGrid& grid, const std::string& frame_id,
                                   std::int64_t stamp_ns);

}  // namespace fleetmerge
