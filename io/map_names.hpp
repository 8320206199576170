// Names of a job's maps when the user gave none (merge --out, pair, job entries without `name`,
// bags). A map is named by its file stem; a bag with several map topics names each map by stem
// and topic ("fleet_robot1_map" for /robot1/map in fleet.bag). Maps whose names would collide
// (r1/map.yaml, r2/map.yaml: the map_saver layout, one folder per robot) are named instead by
// the shortest trailing folder path that makes every name unique ("r1", "r2"; "a/r1", "b/r1" if
// needed), with the topic appended for a bag's several maps. Unique names stay as they are.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace fleetmerge {

struct MapNameInput {
  std::filesystem::path path;
  std::string topic;  // appended to the name when not empty
};

// One name per input; none equals another or one of `taken` (names the user gave). Throws
// fleetmerge::Error when two inputs are the same path and topic.
std::vector<std::string> UniqueMapNames(const std::vector<MapNameInput>& inputs,
                                        const std::vector<std::string>& taken = {});

// "/robot1/map" -> "robot1_map".
std::string TopicForName(const std::string& topic);

}  // namespace fleetmerge
