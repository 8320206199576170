// ROS 1 bags (format 2.0, http://wiki.ros.org/Bags/Format/2.0), read by us rather than by
// librosbag_storage: ROS's reader pulls boost, console_bridge, roscpp_serialization and roslz4
// into the executable (start-up cost for every run, bagged or not), and it refuses bags that
// were never closed; this reader needs libbz2 and liblz4 only and reads both kinds.
//
// Indexed bags (closed by the recorder): the index at the bag header's index_pos gives the
// connections (topic, type) and per chunk the message count of each connection, so the last
// message of a topic decompresses only the chunks that may hold it. Bags without an index
// (index_pos 0: the recorder was killed) are read record by record in file order. Chunks:
// none, bz2, lz4. A record cut by the end of the file is an error in both kinds.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rosbag/bag_types.hpp"

namespace fleetmerge {

bool IsRos1BagPath(const std::filesystem::path& path);  // ends in .bag

std::vector<BagTopic> Ros1BagTopics(const std::filesystem::path& bag);

// The message with the latest receive time on `topic` (the later in the file on a tie); nullopt
// when the topic has none.
std::optional<BagMessage> Ros1BagLastMessage(const std::filesystem::path& bag,
                                             const std::string& topic);

}  // namespace fleetmerge
