// A simulated test case in memory: the robot maps and their ground truth. sim/simulation.hpp
// makes one; io/simulated_case_file.hpp writes it as a case folder.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "io/truth_file.hpp"
#include "job/pose_prior.hpp"

namespace fleetmerge {

// The building's own map as the case's fixed base map (SimulationOptions::fixed_base), as a site
// job merges robots against the site map: written as base.yaml, first in job.yaml (`fixed: true`
// at the identity, so the merged frame is the building's) and first in truth.yaml, so that
// `fleetmerge eval` scores each robot against it.
struct SimulatedBase {
  OccupancyGrid map;                   // the building's map, cells as read
  TruthMap truth;                      // "base", base.yaml, at the identity in its building
  std::vector<TruthOverlap> overlaps;  // with every robot of its building (base is `a`)
};

struct SimulatedCase {
  std::vector<OccupancyGrid> maps;  // robot1..robotK (the building's), then the foreign robot's
  std::vector<std::string> names;   // "robot1", ...; names[i] is maps[i]'s name and file stem
  // truth.maps[i] describes maps[i] (file "<name>.yaml"); truth.overlaps lists every pair of maps
  // of one building (a before b), zero overlaps included.
  GroundTruth truth;
  // Each robot's path in its building's frame (the true poses at which it scanned), for tests
  // and pictures; paths[i] belongs to maps[i].
  std::vector<std::vector<Pose2>> paths;
  std::optional<SimulatedBase> base;
  // Known start poses (SimulationOptions::priors), in the building's frame: priors[i] belongs to
  // maps[i]; empty without priors.
  PosePriors priors;
};

}  // namespace fleetmerge
