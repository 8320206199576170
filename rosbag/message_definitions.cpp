#include "rosbag/message_definitions.hpp"

namespace fleetmerge {

#define FLEETMERGE_MSG_SEPARATOR                                                       \
  "\n================================================================================" \
  "\nMSG: "

const char* const kOccupancyGridDefinition =
    "std_msgs/Header header\n"
    "MapMetaData info\n"
    "int8[] data\n" FLEETMERGE_MSG_SEPARATOR
    "nav_msgs/MapMetaData\n"
    "builtin_interfaces/Time map_load_time\n"
    "float32 resolution\n"
    "uint32 width\n"
    "uint32 height\n"
    "geometry_msgs/Pose origin\n" FLEETMERGE_MSG_SEPARATOR
    "builtin_interfaces/Time\n"
    "int32 sec\n"
    "uint32 nanosec\n" FLEETMERGE_MSG_SEPARATOR
    "geometry_msgs/Pose\n"
    "Point position\n"
    "Quaternion orientation\n" FLEETMERGE_MSG_SEPARATOR
    "geometry_msgs/Point\n"
    "float64 x\n"
    "float64 y\n"
    "float64 z\n" FLEETMERGE_MSG_SEPARATOR
    "geometry_msgs/Quaternion\n"
    "float64 x 0\n"
    "float64 y 0\n"
    "float64 z 0\n"
    "float64 w 1\n" FLEETMERGE_MSG_SEPARATOR
    "std_msgs/Header\n"
    "builtin_interfaces/Time stamp\n"
    "string frame_id\n";

const char* const kTfMessageDefinition =
    "geometry_msgs/TransformStamped[] transforms\n" FLEETMERGE_MSG_SEPARATOR
    "geometry_msgs/TransformStamped\n"
    "std_msgs/Header header\n"
    "string child_frame_id\n"
    "Transform transform\n" FLEETMERGE_MSG_SEPARATOR
    "geometry_msgs/Transform\n"
    "Vector3 translation\n"
    "Quaternion rotation\n" FLEETMERGE_MSG_SEPARATOR
    "geometry_msgs/Quaternion\n"
    "float64 x 0\n"
    "float64 y 0\n"
    "float64 z 0\n"
    "float64 w 1\n" FLEETMERGE_MSG_SEPARATOR
    "geometry_msgs/Vector3\n"
    "float64 x\n"
    "float64 y\n"
    "float64 z\n" FLEETMERGE_MSG_SEPARATOR
    "std_msgs/Header\n"
    "builtin_interfaces/Time stamp\n"
    "string frame_id\n" FLEETMERGE_MSG_SEPARATOR
    "builtin_interfaces/Time\n"
    "int32 sec\n"
    "uint32 nanosec\n";

#undef FLEETMERGE_MSG_SEPARATOR

const char* const kOccupancyGridTypeHash =
    "RIHS01_8d348150c12913a31ee0ec170fbf25089e4745d17035792a1ba94d6f0bc0cfc7";
const char* const kTfMessageTypeHash =
    "RIHS01_e369d0f05a23ae52508854b66f6aa0437f3449d652e8cbf22d5abe85d020f087";

}  // namespace fleetmerge
