// `fleetmerge simulate` as a library: multi-robot test cases with known answers. K robots start
// at random free places of a building map, explore it along collision-free paths, scan it with a
// simulated 2-D lidar and each build a partial occupancy grid in a random frame of its own, as
// SLAM would; the case holds the robot maps and the ground truth (truth.yaml's contents: the
// pose of every map's frame in its building's frame, the true overlap of every pair).
//
// The steps live in simulation_lidar (ray casting), simulation_explore (clearance, starts,
// frontier-like goals and paths), simulation_mapping (one robot's grid) and simulation_robot
// (one robot's run); this file assembles the case. Writing it to disk: io/simulated_case_file.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "io/simulated_case.hpp"
#include "sim/simulation_options.hpp"
#include "sim/synthetic_office.hpp"

namespace fleetmerge {

// A building the robots explore: its map (kFree = traversable, kOccupied = walls; kUnknown stops
// a beam without a return), its name in truth.yaml and where it came from.
struct SimulationBuilding {
  OccupancyGrid grid;
  std::string name;    // "office", "foreign", ...
  std::string source;  // the map's YAML path, or "synthetic office seed 7"
};

// The synthetic office floor of `seed` as a building named `name`.
SimulationBuilding OfficeBuilding(std::uint32_t seed, const std::string& name = "office",
                                  const OfficeOptions& office = {});

// Simulates options.robots robots in `building` and, with `foreign`, one more robot (named
// robot<K+1>, building foreign->name) that explored `foreign` instead: it overlaps no other map
// and must stay unmerged. Deterministic for options.seed (robots run in parallel, each from its
// own seeded stream). Throws fleetmerge::Error for invalid options (ValidateSimulationOptions),
// a building without room for a robot (no free cell with the clearance), or a list of
// resolutions whose length fits neither 1 nor the number of robots (foreign one included).
SimulatedCase SimulateFleet(const SimulationBuilding& building, const SimulationOptions& options,
                            const std::optional<SimulationBuilding>& foreign = std::nullopt);

// The building cells a map knows: 255 where the centre of a cell of `building_geometry`,
// mapped into the map's frame by T_building_map^-1, falls on a known (free or occupied) cell of
// `map`, else 0. truth.yaml's overlap `cells` of a pair is the number of cells set in both
// masks, and `share` divides it by the smaller mask's count.
cv::Mat1b KnownMaskInBuilding(const GridGeometry& building_geometry, const OccupancyGrid& map,
                              const Pose2& T_building_map);

}  // namespace fleetmerge
