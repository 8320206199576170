// A simulated multi-robot case on disk (`fleetmerge simulate`'s output folder): each robot's map
// (<name>.yaml + <name>.pgm), truth.yaml (io/truth_file.hpp) and job.yaml, a job for
// `fleetmerge merge` over all the maps writing to `merged/` beside it. A case with a fixed base
// (io/simulated_case.hpp) also has base.yaml + base.pgm, first in job.yaml and truth.yaml.
#pragma once

#include <filesystem>
#include <vector>

#include "io/simulated_case.hpp"

namespace fleetmerge {

struct WrittenCase {
  std::vector<std::filesystem::path> map_yamls;
  std::filesystem::path base_yaml;  // empty without a fixed base
  std::filesystem::path truth_yaml;
  std::filesystem::path job_yaml;
};

// The case's truth as truth.yaml holds it: with a fixed base, the base first among the maps and
// its overlaps first (so that eval scores each robot, the pair's second map, by its own cells).
GroundTruth WrittenTruth(const SimulatedCase& simulated);

// Creates `dir` if needed and writes every file atomically: the maps first, then truth.yaml,
// then job.yaml, so a job.yaml present means the case is complete. Refuses (fleetmerge::Error)
// to overwrite any of `protected_inputs` (the building maps) before writing anything.
WrittenCase WriteSimulatedCase(const SimulatedCase& simulated, const std::filesystem::path& dir,
                               const std::vector<std::filesystem::path>& protected_inputs = {});

}  // namespace fleetmerge
