#include "pipeline/launch_files.hpp"

#include <cstdio>
#include <set>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

std::string Number(double v) {
  char text[40];
  std::snprintf(text, sizeof(text), "%.12g", v == 0.0 ? 0.0 : v);  // no "-0"
  return text;
}

// A node name from a map name: [A-Za-z0-9_] only.
std::string NodeName(const std::string& map_name) {
  std::string out = "fleetmerge_tf_";
  for (const char c : map_name) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return out;
}

}  // namespace

std::vector<MapTransform> MapTransforms(const Job& job, const FleetResult& result,
                                        std::vector<std::string>& unmerged) {
  std::vector<MapTransform> out;
  for (std::size_t c = 0; c < result.components.size(); ++c) {
    const FleetComponent& component = result.components[c];
    for (int m : component.maps) {
      if (!component.merged) {
        unmerged.push_back(job.maps[m].name);
        continue;
      }
      out.push_back({job.maps[m].name, ParentFrame(job, static_cast<int>(c)),
                     ChildFrame(job, job.maps[m].name), result.T_component_map[m]});
    }
  }
  return out;
}

std::string ChildFrame(const Job& job, const std::string& map_name) {
  std::string frame = job.tf_child_frame;
  for (std::size_t at; (at = frame.find("{name}")) != std::string::npos;) {
    frame.replace(at, 6, map_name);
  }
  return frame;
}

std::string ParentFrame(const Job& job, int component) {
  return component == 0 ? job.tf_parent_frame
                        : job.tf_parent_frame + "_" + std::to_string(component);
}

void CheckTransformFrames(const Job& job) {
  const auto check = [&](const std::string& frame, const char* what) {
    if (frame.empty() || frame.find_first_of(" \t\n\"'<>&") != std::string::npos) {
      throw Error(std::string(what) + " '" + frame +
                  "' is not a valid frame id (expected a non-empty name without spaces, quotes "
                  "or <>&)");
    }
  };
  check(job.tf_parent_frame, "the parent frame (tf_parent)");
  std::set<std::string> children;
  for (const JobMap& map : job.maps) {
    const std::string child = ChildFrame(job, map.name);
    check(child, "the child frame (tf_child)");
    if (!children.insert(child).second || child == job.tf_parent_frame) {
      throw Error("the child frame pattern (tf_child) '" + job.tf_child_frame + "' gives map '" +
                  map.name + "' the frame '" + child +
                  "', which another frame has; put {name} in it");
    }
  }
}

std::string Ros2TransformsLaunch(const Job& job, const FleetResult& result) {
  std::vector<std::string> unmerged;
  const std::vector<MapTransform> transforms = MapTransforms(job, result, unmerged);
  std::string out =
      "# fleetmerge: static transforms from the merged map frame to each robot's map frame\n"
      "# (job '" +
      job.name + "'). ROS 2 (Humble and later): ros2 launch " + kRos2LaunchFile +
      "\n# Serve merged_<c>.yaml with nav2_map_server in the parent frame (frame_id).\n";
  for (const auto& name : unmerged) out += "# map '" + name + "' was not merged: no transform\n";
  out += "launch:\n";
  for (const MapTransform& t : transforms) {
    out +=
        "  - node:\n      pkg: tf2_ros\n      exec: static_transform_publisher\n"
        "      name: " +
        NodeName(t.map_name) + "\n      args: \"--x " + Number(t.T_parent_child.x_m()) + " --y " +
        Number(t.T_parent_child.y_m()) + " --z 0 --yaw " + Number(t.T_parent_child.yaw_rad()) +
        " --pitch 0 --roll 0 --frame-id " + t.parent_frame + " --child-frame-id " + t.child_frame +
        "\"\n";
  }
  if (transforms.empty()) out += "  []\n";
  return out;
}

// Text for inside an XML comment, where "--" may not appear (names are the user's).
std::string XmlCommentText(std::string text) {
  for (std::size_t at; (at = text.find("--")) != std::string::npos;) text[at + 1] = '_';
  return text;
}

std::string Ros1TransformsLaunch(const Job& job, const FleetResult& result) {
  std::vector<std::string> unmerged;
  const std::vector<MapTransform> transforms = MapTransforms(job, result, unmerged);
  std::string out =
      "<?xml version=\"1.0\"?>\n<!-- fleetmerge: static transforms from the merged map frame "
      "to each robot's map frame (job '" +
      XmlCommentText(job.name) + "'). ROS 1: roslaunch " + kRos1LaunchFile +
      "\n     Serve merged_<c>.yaml with map_server in the parent frame (_frame_id). -->\n";
  for (const auto& name : unmerged)
    out += "<!-- map '" + XmlCommentText(name) + "' was not merged: no transform -->\n";
  out += "<launch>\n";
  for (const MapTransform& t : transforms) {
    // tf2_ros static_transform_publisher: x y z yaw pitch roll frame_id child_frame_id
    out += "  <node pkg=\"tf2_ros\" type=\"static_transform_publisher\" name=\"" +
           NodeName(t.map_name) + "\" args=\"" + Number(t.T_parent_child.x_m()) + " " +
           Number(t.T_parent_child.y_m()) + " 0 " + Number(t.T_parent_child.yaw_rad()) + " 0 0 " +
           t.parent_frame + " " + t.child_frame + "\"/>\n";
  }
  out += "</launch>\n";
  return out;
}

}  // namespace fleetmerge
