// One fleet-merging job as described in a job file: which maps, where the output goes, the
// reference map and the method's parameters.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/pose2.hpp"
#include "job/fleet_options.hpp"
#include "job/pose_prior.hpp"

namespace fleetmerge {

struct JobMap {
  std::string name;              // given in the job, else from the path (io/map_names.hpp)
  std::filesystem::path source;  // as written in the job file (reported in report.json)
  std::filesystem::path path;    // resolved: relative paths are relative to the job file's folder
  std::string topic;             // a bag's map: its nav_msgs/OccupancyGrid topic; else empty
  // A fixed (base) map never moves: T_merged_map is its given pose in the merged frame.
  bool fixed = false;
  Pose2 T_merged_map;
  // A known start pose (job file keys initial_pose, initial_pose_sigma), or none.
  std::optional<PosePrior> prior;
};

struct Job {
  std::string name;  // the job's `name`, else "job <index>" (1-based)
  std::filesystem::path job_file;
  std::vector<JobMap> maps;
  std::filesystem::path output_dir;  // resolved like map paths
  // The job file's error for `cache_max_mb` without `cache` ("FILE: line N: key ...": empty
  // when there is none): merge --cache may still give the job its cache, else it is refused.
  std::string cache_bound_without_cache;
  std::string reference;  // a map name; default the first fixed map, else the first map
  // Frames of the transforms written beside report.json (pipeline/launch_files.hpp).
  std::string tf_parent_frame = "map";
  std::string tf_child_frame = "{name}/map";  // {name}: the map's name
  FleetOptions options;
};

// With fixed maps the merged frame is theirs: the reference is the first fixed map, and a job
// (file, command line or API) may not name another. Null when no map is fixed.
inline const JobMap* FirstFixedMap(const std::vector<JobMap>& maps) {
  for (const JobMap& map : maps) {
    if (map.fixed) return &map;
  }
  return nullptr;
}

// "'a', 'b', 'c'": the maps' names, for an error about a name that is none of them.
inline std::string QuotedMapNames(const std::vector<JobMap>& maps) {
  std::string names;
  for (const JobMap& map : maps) names += (names.empty() ? "'" : ", '") + map.name + "'";
  return names;
}

}  // namespace fleetmerge
