// The ROS 2 message definitions (schema encoding "ros2msg") of the messages fleetmerge writes,
// in the form rosbag2_storage_mcap stores them in an MCAP Schema record: the type's .msg text,
// then each type it uses, once, depth first in name order, after a line of 80 '=' and a line
// "MSG: <package>/<Type>". Field lines only (the distributed .msg files' comments are left out);
// the fields are those of Humble and Jazzy, which agree for these types.
#pragma once

namespace fleetmerge {

extern const char* const kOccupancyGridDefinition;  // nav_msgs/msg/OccupancyGrid
extern const char* const kTfMessageDefinition;      // tf2_msgs/msg/TFMessage

}  // namespace fleetmerge
