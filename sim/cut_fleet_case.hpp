// A multi-robot case folder with ground truth, cut from one building map by CutFleet
// (sim/ground_truth_pair.hpp): robot1.yaml .. robotK.yaml (+ .pgm), truth.yaml
// (io/truth_file.hpp, with every pair's true overlap) and job.yaml (`fleetmerge merge job.yaml`
// writes to merged/). Used by the eval tests and by `fleetmerge bench cut-fleet`; any case
// folder with a truth.yaml (e.g. from `fleetmerge simulate`) works the same in eval and bench.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "io/truth_file.hpp"
#include "sim/ground_truth_pair.hpp"

namespace fleetmerge {

// Building cells (at the building's resolution) known in both maps, for every pair, a before b
// (pairs with no common known cell are left out). `share` = cells / min(known cells of a, b),
// the known cells of a map counted on the building's grid too.
std::vector<TruthOverlap> TrueOverlaps(const OccupancyGrid& building,
                                       const std::vector<OccupancyGrid>& maps,
                                       const std::vector<std::string>& names,
                                       const std::vector<Pose2>& T_building_map);

// Cuts `robots` maps from `building` (seeded) and writes the case into `dir` (created).
// `building_name` and `source` go into truth.yaml. Returns the truth as written (map files
// resolved against `dir`). Refuses (fleetmerge::Error) to overwrite any of `protected_inputs`
// (the building map's YAML and image) before writing anything.
GroundTruth WriteCutFleetCase(const OccupancyGrid& building, const std::string& building_name,
                              const std::string& source, int robots, std::uint32_t seed,
                              const std::filesystem::path& dir, const CutFleetOptions& options = {},
                              const std::vector<std::filesystem::path>& protected_inputs = {});

}  // namespace fleetmerge
