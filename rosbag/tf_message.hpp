// tf2_msgs/msg/TFMessage (what /tf_static carries) encoded as ROS 2 CDR: one message holding
// every static transform, each a geometry_msgs/TransformStamped whose rotation is the planar
// yaw as a quaternion about z (z, roll and pitch 0, as in the launch files of the result set).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/pose2.hpp"

namespace fleetmerge {

struct StaticTransform {
  std::string parent_frame;  // header.frame_id
  std::string child_frame;   // child_frame_id
  Pose2 T_parent_child;      // pose of the child frame in the parent frame
};

std::string EncodeCdrTfMessage(const std::vector<StaticTransform>& transforms,
                               std::int64_t stamp_ns);

}  // namespace fleetmerge
