#include "rosbag/merged_bag.hpp"

#include <set>
#include <sstream>

#include "core/error.hpp"
#include "rosbag/mcap_writer.hpp"
#include "rosbag/message_definitions.hpp"
#include "rosbag/occupancy_grid_msg.hpp"

namespace fleetmerge {
namespace {

struct Topic {
  std::string name, type, type_hash;
};

// RMW_DURATION_INFINITE as rosbag2 records it for publishers without a deadline or lifespan.
constexpr const char* kInfinite = "\n    sec: 9223372036\n    nsec: 854775807\n";

// The offered QoS of one publisher, as a rosbag2 (metadata version 9) YAML list; each line
// after the first is indented by `indent`.
std::string LatchedQosYaml(const std::string& indent) {
  std::string text = std::string("- history: keep_last\n  depth: 1\n  reliability: reliable\n") +
                     "  durability: transient_local\n  deadline:" + kInfinite +
                     "  lifespan:" + kInfinite + "  liveliness: automatic\n" +
                     "  liveliness_lease_duration:" + kInfinite +
                     "  avoid_ros_namespace_conventions: false\n";
  std::string out;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    out += (out.empty() ? "" : indent) + line + "\n";
  }
  return out;
}

// rosbag2_bagfile_information's body (what rosbag2 also stores in the MCAP's "rosbag2" metadata
// record as serialized_metadata).
std::string BagInformation(const std::vector<Topic>& topics, std::int64_t stamp_ns) {
  std::ostringstream y;
  y << "version: 9\n"
    << "storage_identifier: mcap\n"
    << "duration:\n  nanoseconds: 0\n"
    << "starting_time:\n  nanoseconds_since_epoch: " << stamp_ns << "\n"
    << "message_count: " << topics.size() << "\n"
    << "topics_with_message_count:\n";
  for (const Topic& t : topics) {
    y << "  - topic_metadata:\n"
      << "      name: " << t.name << "\n"
      << "      type: " << t.type << "\n"
      << "      serialization_format: cdr\n"
      << "      offered_qos_profiles:\n        " << LatchedQosYaml("        ")
      << "      type_description_hash: " << t.type_hash << "\n"
      << "    message_count: 1\n";
  }
  y << "compression_format: \"\"\n"
    << "compression_mode: \"\"\n"
    << "relative_file_paths:\n  - " << kMergedBagMcapName << "\n"
    << "files:\n"
    << "  - path: " << kMergedBagMcapName << "\n"
    << "    starting_time:\n      nanoseconds_since_epoch: " << stamp_ns << "\n"
    << "    duration:\n      nanoseconds: 0\n"
    << "    message_count: " << topics.size() << "\n"
    << "custom_data: ~\n"
    << "ros_distro: jazzy\n";
  return y.str();
}

std::string Indented(const std::string& text, const std::string& indent) {
  std::string out;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) out += indent + line + "\n";
  return out;
}

void CheckTopic(const std::string& topic, std::set<std::string>& seen) {
  const bool valid = topic.size() > 1 && topic[0] == '/' && topic.back() != '/' &&
                     topic.find("//") == std::string::npos &&
                     topic.find_first_not_of(
                         "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                         "0123456789_/") == std::string::npos;
  if (!valid) {
    throw Error("merged bag: '" + topic +
                "' is not a ROS topic name (expected /name with letters, digits, _ and /)");
  }
  if (!seen.insert(topic).second) throw Error("merged bag: topic " + topic + " appears twice");
}

}  // namespace

MergedBagFiles MakeMergedBag(const std::vector<MergedBagMap>& maps,
                             const std::vector<StaticTransform>& transforms,
                             std::int64_t stamp_ns) {
  std::set<std::string> seen = {"/tf_static"};
  McapWriter mcap("ros2", "fleetmerge");
  // What rosbag2_storage_mcap stores per channel: the offered QoS (YAML) and the type hash.
  const auto channel_metadata = [](const char* type_hash) {
    return std::map<std::string, std::string>{{"offered_qos_profiles", LatchedQosYaml("")},
                                              {"topic_type_hash", type_hash}};
  };
  std::vector<Topic> topics;
  const auto time_ns = static_cast<std::uint64_t>(stamp_ns);
  if (!maps.empty()) {
    const std::uint16_t schema =
        mcap.AddSchema("nav_msgs/msg/OccupancyGrid", "ros2msg", kOccupancyGridDefinition);
    for (const MergedBagMap& map : maps) {
      CheckTopic(map.topic, seen);
      const std::uint16_t channel =
          mcap.AddChannel(schema, map.topic, "cdr", channel_metadata(kOccupancyGridTypeHash));
      mcap.AddMessage(channel, time_ns, time_ns,
                      EncodeCdrOccupancyGrid(*map.grid, map.frame_id, stamp_ns));
      topics.push_back({map.topic, "nav_msgs/msg/OccupancyGrid", kOccupancyGridTypeHash});
    }
  }
  const std::uint16_t tf_schema =
      mcap.AddSchema("tf2_msgs/msg/TFMessage", "ros2msg", kTfMessageDefinition);
  const std::uint16_t tf_channel =
      mcap.AddChannel(tf_schema, "/tf_static", "cdr", channel_metadata(kTfMessageTypeHash));
  mcap.AddMessage(tf_channel, time_ns, time_ns, EncodeCdrTfMessage(transforms, stamp_ns));
  topics.push_back({"/tf_static", "tf2_msgs/msg/TFMessage", kTfMessageTypeHash});

  const std::string information = BagInformation(topics, stamp_ns);
  mcap.AddMetadata("rosbag2", {{"serialized_metadata", information}});
  return {"rosbag2_bagfile_information:\n" + Indented(information, "  "), mcap.Finish()};
}

}  // namespace fleetmerge
