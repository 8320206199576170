// The overlapping pairs of a simulated fleet (sim/simulation.hpp) by map index, with the true
// pose between the two maps, for tests that judge pair results against the truth.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "core/pose2.hpp"
#include "io/simulated_case.hpp"

namespace fleetmerge::testing {

struct TruePair {
  int a = 0;  // indices into SimulatedCase::maps, a listed before b
  int b = 0;
  Pose2 T_a_b;  // truth: pose of b's map frame in a's map frame
};

// The truth's overlaps of at least `min_overlap_cells` building cells, in the truth's order.
inline std::vector<TruePair> TruePairs(const SimulatedCase& sim, std::int64_t min_overlap_cells) {
  std::map<std::string, int> index;
  for (std::size_t m = 0; m < sim.names.size(); ++m) index[sim.names[m]] = static_cast<int>(m);
  std::vector<TruePair> pairs;
  for (const TruthOverlap& o : sim.truth.overlaps) {
    if (o.cells < min_overlap_cells) continue;
    const int a = index.at(o.a), b = index.at(o.b);
    pairs.push_back(
        {a, b, sim.truth.maps[a].T_building_map.inverse() * sim.truth.maps[b].T_building_map});
  }
  return pairs;
}

}  // namespace fleetmerge::testing
