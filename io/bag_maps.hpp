// Maps recorded in robot bags: every nav_msgs/OccupancyGrid topic of a ROS 1 bag
// (rosbag/ros1_bag.hpp) or a ROS 2 bag (rosbag/ros2_bag.hpp) gives one map, its LAST message (the
// latest receive time: the map the robot had at the end of its mission).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "io/map_io.hpp"

namespace fleetmerge {

// A ROS 1 bag (.bag), a ROS 2 bag folder, or one of its files (.db3, .mcap).
bool IsBagPath(const std::filesystem::path& path);

// The bag's OccupancyGrid topics, sorted. With `wanted` (topics, the leading '/' optional)
// only those of them the bag has. Throws fleetmerge::Error naming the bag when it has no
// OccupancyGrid topic (listing the topics and types it has; octomap_msgs topics are named out of
// scope), or none of `wanted` (listing its map topics).
std::vector<std::string> BagMapTopics(const std::filesystem::path& bag,
                                      const std::vector<std::string>& wanted = {});

// The last OccupancyGrid on `topic` as a map (rosbag/occupancy_grid_msg.hpp): metadata.yaml_path is
// the bag, metadata.image_path empty, and `bag` says where it came from. Throws
// fleetmerge::Error naming the bag and topic and what was wrong.
LoadedMap LoadBagMap(const std::filesystem::path& bag, const std::string& topic,
                     std::int64_t max_cells = kDefaultMaxMapCells);

}  // namespace fleetmerge
