// The ROS 2 message definitions (schema encoding "ros2msg") of the messages fleetmerge writes,
// in the form rosbag2_storage_mcap stores them in an MCAP Schema record: the type's .msg text,
// then each type it uses, once, depth first in name order, after a line of 80 '=' and a line
// "MSG: <package>/<Type>". Field lines only (the distributed .msg files' comments are left out);
// the fields are those of Humble and Jazzy, which agree for these types.
#pragma once

namespace fleetmerge {

extern const char* const kOccupancyGridDefinition;  // nav_msgs/msg/OccupancyGrid
extern const char* const kTfMessageDefinition;      // tf2_msgs/msg/TFMessage

// Their type hashes (REP 2011, "RIHS01_" + SHA-256 of the type description: the type and each
// type it uses, sorted by name, as JSON without default values), as rosidl generates them for
// Jazzy; rosbag2 records them as type_description_hash. tests/rosbag/merged_bag_check.mjs
// recomputes them from the definitions above.
extern const char* const kOccupancyGridTypeHash;
extern const char* const kTfMessageTypeHash;

}  // namespace fleetmerge
