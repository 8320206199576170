#include "io/bag_maps.hpp"

#include <algorithm>
#include <optional>

#include "core/error.hpp"
#include "rosbag/occupancy_grid_msg.hpp"
#include "rosbag/ros1_bag.hpp"
#include "rosbag/ros2_bag.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

bool IsOccupancyGridType(const std::string& type) {
  return type == "nav_msgs/OccupancyGrid" || type == "nav_msgs/msg/OccupancyGrid";
}

bool IsOctomapType(const std::string& type) { return type.rfind("octomap_msgs/", 0) == 0; }

std::string WithSlash(const std::string& topic) {
  return !topic.empty() && topic.front() == '/' ? topic : "/" + topic;
}

std::vector<BagTopic> Topics(const fs::path& bag) {
  return IsRos1BagPath(bag) ? Ros1BagTopics(bag) : Ros2BagTopics(OpenRos2Bag(bag));
}

std::string Join(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : ", ") + w;
  return out;
}

}  // namespace

bool IsBagPath(const fs::path& path) { return IsRos1BagPath(path) || IsRos2BagPath(path); }

std::vector<std::string> BagMapTopics(const fs::path& bag, const std::vector<std::string>& wanted) {
  const std::vector<BagTopic> topics = Topics(bag);
  std::vector<std::string> maps, all;
  bool octomap = false;
  for (const BagTopic& t : topics) {
    all.push_back(t.name + " (" + t.type + ")");
    if (IsOccupancyGridType(t.type)) maps.push_back(t.name);
    octomap = octomap || IsOctomapType(t.type);
  }
  if (maps.empty()) {
    std::string message = bag.string() + ": no nav_msgs/OccupancyGrid topic; the bag has " +
                          (all.empty() ? std::string("no topics") : Join(all));
    if (octomap) {
      message +=
          "; octomap_msgs topics are not read from bags (out of scope): save the octree "
          "with octomap_saver and merge the .bt/.ot file";
    }
    throw Error(message);
  }
  std::sort(maps.begin(), maps.end());
  if (wanted.empty()) return maps;
  std::vector<std::string> picked;
  for (const std::string& m : maps) {
    for (const std::string& w : wanted) {
      if (WithSlash(w) == WithSlash(m)) {
        picked.push_back(m);
        break;
      }
    }
  }
  if (picked.empty()) {
    throw Error(bag.string() + ": has none of the topics asked for (" + Join(wanted) +
                "); its nav_msgs/OccupancyGrid topics are " + Join(maps));
  }
  return picked;
}

LoadedMap LoadBagMap(const fs::path& bag, const std::string& topic, std::int64_t max_cells) {
  const std::string context = bag.string() + ": topic " + topic;
  std::optional<BagMessage> message;
  std::string type;
  bool ros1 = IsRos1BagPath(bag);
  if (ros1) {
    for (const BagTopic& t : Ros1BagTopics(bag)) {
      if (t.name == topic) type = t.type;
    }
    if (IsOccupancyGridType(type)) message = Ros1BagLastMessage(bag, topic);
  } else {
    const Ros2Bag ros2 = OpenRos2Bag(bag);
    for (const BagTopic& t : Ros2BagTopics(ros2)) {
      if (t.name == topic) type = t.type;
    }
    if (IsOccupancyGridType(type)) message = Ros2BagLastMessage(ros2, topic);
  }
  if (type.empty()) throw Error(context + ": the bag has no such topic");
  if (!IsOccupancyGridType(type)) {
    throw Error(context + ": has type " + type + ", expected nav_msgs/OccupancyGrid");
  }
  if (!message) throw Error(context + ": has no message");
  const OccupancyGridMsg msg = ros1 ? DecodeRos1OccupancyGrid(message->data, context)
                                    : DecodeCdrOccupancyGrid(message->data, context);
  LoadedMap loaded;
  loaded.grid = OccupancyGridFromMsg(msg, context, max_cells);
  loaded.metadata.yaml_path = bag;
  loaded.metadata.resolution_m = loaded.grid.geometry().resolution_m();
  loaded.metadata.origin = loaded.grid.geometry().T_map_grid();
  BagMapInfo info;
  info.bag = bag;
  info.topic = topic;
  info.type = type;
  info.frame_id = msg.frame_id;
  info.log_time_ns = message->log_time_ns;
  info.stamp_ns = msg.stamp_ns;
  loaded.bag = info;
  return loaded;
}

}  // namespace fleetmerge
