#include "rosbag/tf_message.hpp"

#include <cmath>

#include "rosbag/byte_writer.hpp"
#include "rosbag/ros_time.hpp"

namespace fleetmerge {

std::string EncodeCdrTfMessage(const std::vector<StaticTransform>& transforms,
                               std::int64_t stamp_ns) {
  const RosTime stamp = RosTimeOf(stamp_ns);
  CdrWriter w;
  w.Put(static_cast<std::uint32_t>(transforms.size()));
  for (const StaticTransform& t : transforms) {
    w.Put(stamp.sec);
    w.Put(stamp.nanosec);
    w.String(t.parent_frame);
    w.String(t.child_frame);
    const double half_yaw = 0.5 * t.T_parent_child.yaw_rad();
    for (double v : {t.T_parent_child.x_m(), t.T_parent_child.y_m(), 0.0,  // translation
                     0.0, 0.0, std::sin(half_yaw), std::cos(half_yaw)}) {  // rotation x y z w
      w.Put(v);
    }
  }
  return w.bytes();
}

}  // namespace fleetmerge
