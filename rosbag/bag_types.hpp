// What the bag readers (rosbag/ros1_bag.hpp, rosbag/ros2_bag.hpp) report: a bag's topics and one
// message's serialized bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace fleetmerge {

struct BagTopic {
  std::string name;            // "/map"
  std::string type;            // "nav_msgs/OccupancyGrid" (ROS 1), "nav_msgs/msg/OccupancyGrid"
  std::uint64_t messages = 0;  // 0 when the bag does not say (unindexed ROS 1 bags count them)
};

struct BagMessage {
  std::int64_t log_time_ns = 0;  // when the recorder received it
  std::string data;              // serialized: ROS 1 wire format or CDR
};

}  // namespace fleetmerge
