// A simulated test case in memory: the robot maps and their ground truth. sim/simulation.hpp
// makes one; io/simulated_case_file.hpp writes it as a case folder.
#pragma once

#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "io/truth_file.hpp"

namespace fleetmerge {

struct SimulatedCase {
  std::vector<OccupancyGrid> maps;  // robot1..robotK (the building's), then the foreign robot's
  std::vector<std::string> names;   // "robot1", ...; names[i] is maps[i]'s name and file stem
  // truth.maps[i] describes maps[i] (file "<name>.yaml"); truth.overlaps lists every pair of maps
  // of one building (a before b), zero overlaps included.
  GroundTruth truth;
  // Each robot's path in its building's frame (the true poses at which it scanned), for tests
  // and pictures; paths[i] belongs to maps[i].
  std::vector<std::vector<Pose2>> paths;
};

}  // namespace fleetmerge
