// MCAP files (https://mcap.dev/spec), the default storage of ROS 2 bags since Iron: read record
// by record through the data section (no summary needed, so files whose writer was killed read
// too). Chunks: uncompressed, zstd or lz4 (frame). ROS 2 channels carry CDR ("cdr" encoding)
// with the schema naming the type ("nav_msgs/msg/OccupancyGrid").
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rosbag/bag_types.hpp"

namespace fleetmerge {

std::vector<BagTopic> McapTopics(const std::filesystem::path& file);

// The message with the latest log time on `topic` (the later in the file on a tie).
std::optional<BagMessage> McapLastMessage(const std::filesystem::path& file,
                                          const std::string& topic);

}  // namespace fleetmerge
