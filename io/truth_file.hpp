// Ground truth of a simulated (or cut) multi-robot case, `truth.yaml`: which building each robot
// map shows, the pose of each map's frame in its building's frame, and how much every pair of
// maps of one building truly overlaps. Written by `fleetmerge simulate`, read by `fleetmerge
// eval`. Format (version fleetmerge-truth-1):
//
//   format: fleetmerge-truth-1
//   seed: 7
//   buildings:
//     - {name: office, source: synthetic office seed 7}
//   maps:
//     - {name: robot1, file: robot1.yaml, building: office, resolution: 0.05,
//        pose: {x: 12.3, y: -4.5, yaw: 0.7}}
//   overlaps:
//     - {a: robot1, b: robot2, cells: 5321, share: 0.31}
//
// A point p in map i's map frame (the frame its YAML `origin` is given in) is at
// T_building_map * p in the building's frame. `cells` counts building cells (at the building
// map's resolution) that both robots observed; `share` = cells / min(known cells of a, of b).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/pose2.hpp"

namespace fleetmerge {

struct TruthBuilding {
  std::string name;
  std::string source;  // the building map's YAML, or a description of a synthetic one
};

struct TruthMap {
  std::string name;            // the map's name in the job and in report.json
  std::filesystem::path file;  // as written; LoadTruth resolves it against truth.yaml's folder
  std::string building;        // a TruthBuilding name
  double resolution_m = 0.0;
  Pose2 T_building_map;
};

struct TruthOverlap {
  std::string a;  // map names, a listed before b in `maps`
  std::string b;
  long long cells = 0;
  double share = 0.0;
};

struct GroundTruth {
  std::uint32_t seed = 0;
  std::vector<TruthBuilding> buildings;
  std::vector<TruthMap> maps;
  std::vector<TruthOverlap> overlaps;
};

// Writes `truth` atomically to `path` (map files as given, normally relative to its folder).
// Throws fleetmerge::Error naming the path on failure.
void SaveTruth(const GroundTruth& truth, const std::filesystem::path& path);

// Reads and validates `path`: every key, type and reference (a map's building, an overlap's
// maps) is checked and a mistake fails with fleetmerge::Error naming the file, line and key.
// Map files are returned resolved against the folder of `path`.
GroundTruth LoadTruth(const std::filesystem::path& path);

}  // namespace fleetmerge
