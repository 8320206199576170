// From what a user lists (map YAMLs, octrees, bags) to a job's maps: a map file is one map, a
// bag one map per nav_msgs/OccupancyGrid topic (io/bag_maps.hpp; `topics` picks some), and maps
// without a given name are named by io/map_names.hpp. Shared by merge --out, pair, extract and
// job files, so that one input gets one name everywhere.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "io/map_io.hpp"
#include "job/job.hpp"

namespace fleetmerge {

struct MapInput {
  std::filesystem::path source;     // as the user wrote it
  std::filesystem::path path;       // resolved
  std::string name;                 // empty: named from the path
  std::vector<std::string> topics;  // bags: only these topics (empty: every map topic)
};

// Throws fleetmerge::Error naming the input: a bag without map topics, a name given to a bag
// entry with several map topics, a file listed twice.
std::vector<JobMap> ExpandMapInputs(const std::vector<MapInput>& inputs);

// Loads one job map: its bag topic (io/bag_maps.hpp), else a map_server YAML.
// The path a map is named by (io/map_names.hpp): its own, but a ROS 2 bag's storage file with
// metadata.yaml beside it is named by its bag's folder, and "robot1/" by "robot1".
std::filesystem::path NamingPath(const std::filesystem::path& path);

LoadedMap LoadJobMap(const JobMap& map, std::int64_t max_cells = kDefaultMaxMapCells);

}  // namespace fleetmerge
