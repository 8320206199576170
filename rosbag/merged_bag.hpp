// The merged result as a ROS 2 bag, rosbag2's Jazzy layout (metadata version 9, storage mcap):
// a folder holding metadata.yaml and merged_bag_0.mcap, which `ros2 bag play merged_bag` plays
// and Foxglove opens. It holds one message per topic, all at `stamp_ns`:
//   - each merged map as nav_msgs/msg/OccupancyGrid (rosbag/occupancy_grid_msg.hpp) on its topic,
//   - /tf_static: one tf2_msgs/msg/TFMessage with every static transform (rosbag/tf_message.hpp).
// Every topic is recorded as offered transient local, reliable, keep last 1 (map_server's and
// static_transform_publisher's QoS), so that `ros2 bag play` offers it latched as they do: a node
// that subscribes after the message was played still gets the map and the transforms.
// Schemas are "ros2msg" (rosbag/message_definitions.hpp, with the types' RIHS01 hashes as
// type_description_hash), messages "cdr".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "rosbag/tf_message.hpp"

namespace fleetmerge {

inline constexpr const char* kMergedBagFolder = "merged_bag";
inline constexpr const char* kMergedBagMetadataName = "metadata.yaml";
inline constexpr const char* kMergedBagMcapName = "merged_bag_0.mcap";

struct MergedBagMap {
  std::string topic;     // "/map"
  std::string frame_id;  // header.frame_id: the frame the map is served in
  const OccupancyGrid* grid = nullptr;
};

struct MergedBagFiles {
  std::string metadata_yaml;  // merged_bag/metadata.yaml
  std::string mcap;           // merged_bag/merged_bag_0.mcap
};

// Throws fleetmerge::Error when a topic is not a valid ROS topic name or appears twice.
MergedBagFiles MakeMergedBag(const std::vector<MergedBagMap>& maps,
                             const std::vector<StaticTransform>& transforms, std::int64_t stamp_ns);

}  // namespace fleetmerge
