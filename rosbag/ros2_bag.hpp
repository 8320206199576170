// ROS 2 bags: a folder holding metadata.yaml (rosbag2_bagfile_information) and its storage files
// (.db3: rosbag/sqlite_bag.hpp, .mcap: rosbag/mcap_file.hpp), or one storage file given alone. Read
// metadata keys: version (Humble writes 5, Jazzy 9), storage_identifier, relative_file_paths,
// compression_format/_mode; the QoS profiles (a YAML string in Humble, a list in Jazzy) and
// type hashes are not needed to read maps and are not parsed. Compression: mode MESSAGE with
// zstd is read; mode FILE (whole .db3.zstd / .mcap.zstd files) is refused with a message.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rosbag/bag_types.hpp"

namespace fleetmerge {

// A folder, or a file ending in .db3 or .mcap.
bool IsRos2BagPath(const std::filesystem::path& path);

struct Ros2Bag {
  std::filesystem::path path;                // as given
  std::vector<std::filesystem::path> files;  // storage files, in recording order
  bool message_zstd = false;                 // compression_mode MESSAGE, format zstd
};

// Reads metadata.yaml (for a folder) and checks every storage file exists. Throws
// fleetmerge::Error naming the folder or file and what was expected.
Ros2Bag OpenRos2Bag(const std::filesystem::path& path);

// Topics of all its files (counts summed).
std::vector<BagTopic> Ros2BagTopics(const Ros2Bag& bag);

// The latest message on `topic` over all files, decompressed.
std::optional<BagMessage> Ros2BagLastMessage(const Ros2Bag& bag, const std::string& topic);

}  // namespace fleetmerge
