// rosbag2's SQLite 3 storage (.db3): tables `topics` (id, name, type, serialization_format, ...)
// and `messages` (id, topic_id, timestamp, data). Humble writes schema 3, Jazzy schema 4 (adds
// message_definitions and type_description_hash); both have these columns, which are all we
// read. Opened read-only and immutable, so a bag on a read-only medium reads and is never
// modified (no journal or WAL file appears beside it).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rosbag/bag_types.hpp"

namespace fleetmerge {

std::vector<BagTopic> SqliteBagTopics(const std::filesystem::path& db3);

// The message with the latest timestamp on `topic` (the higher row id on a tie).
std::optional<BagMessage> SqliteBagLastMessage(const std::filesystem::path& db3,
                                               const std::string& topic);

}  // namespace fleetmerge
