// The transforms a merge found, as ROS launch files of static transforms, written beside
// report.json: each map of a merged component gets a tf2_ros static_transform_publisher from the
// component's merged frame (the frame merged_<c>.yaml is served in) to the robot's map frame.
//   transforms.launch.yaml  ROS 2 (YAML launch; `ros2 launch transforms.launch.yaml`)
//   transforms.launch       ROS 1 (XML; `roslaunch transforms.launch`)
// Frames: the parent is job.tf_parent_frame ("map") for component 0 and
// "<tf_parent_frame>_<c>" for component c > 0; the child is job.tf_child_frame with "{name}"
// replaced by the map's name ("robot1/map"). Maps left unmerged (a component of one map, not
// fixed and without a prior, in a job of several) get no transform: the files say so in a
// comment. Planar poses: z, roll, pitch 0.
#pragma once

#include <string>
#include <vector>

#include "job/job.hpp"
#include "pipeline/fleet_merge.hpp"

namespace fleetmerge {

inline constexpr const char* kRos2LaunchFile = "transforms.launch.yaml";
inline constexpr const char* kRos1LaunchFile = "transforms.launch";

std::string Ros2TransformsLaunch(const Job& job, const FleetResult& result);
std::string Ros1TransformsLaunch(const Job& job, const FleetResult& result);

// One merged map's static transform: from its component's frame to the map's frame.
struct MapTransform {
  std::string map_name, parent_frame, child_frame;
  Pose2 T_parent_child;
};

// Every merged map's transform, in job order within each component (the order the launch files
// list them; the result set's merged_bag/ publishes the same ones on /tf_static). The names of
// maps left unmerged go to `unmerged`.
std::vector<MapTransform> MapTransforms(const Job& job, const FleetResult& result,
                                        std::vector<std::string>& unmerged);

// The child frame of a map ("{name}" replaced) and the parent frame of a component.
std::string ChildFrame(const Job& job, const std::string& map_name);
std::string ParentFrame(const Job& job, int component);

// Throws fleetmerge::Error unless the frame names are valid ROS frame ids (non-empty, no space
// or quote) and the child pattern names every map differently.
void CheckTransformFrames(const Job& job);

}  // namespace fleetmerge
