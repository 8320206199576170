// Corroboration of the solved fleet (beyond the paper): a map placed in a component must agree
// with the independent pair searches of the maps it then overlaps.
//
// A map of another building can match one map of the fleet by chance (similar corridors and rooms
// give omega >= 0.95 and wall agreement >= 0.8 for one pose) and hang on that single edge, where
// no cycle can check it. But if it truly were there, every other map that sees the same place
// would have found it there too: their pair searches, which recover true poses nearly always, put
// a hypothesis at the implied pose. So each map m counts, over the other maps n of its component
// that overlap it by at least min_overlap_cells under the solved poses, the supporters (some
// hypothesis of the pair (n, m) within the edge tolerances of the solved relative pose, or the
// two maps' walls agree there: a pair search can miss a true pose where two maps share little)
// and the conflicts (neither).
#pragma once

#include <cstdint>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "pipeline/all_pairs.hpp"
#include "pipeline/fleet_graph.hpp"
#include "refine/pose_graph.hpp"

namespace fleetmerge {

struct Corroboration {
  int supporters = 0;
  int conflicts = 0;
};

// Per map. `maps` share one resolution; `pairs` as from ComputeAllPairs; a map alone in its
// component gets {0, 0}.
std::vector<Corroboration> CorroborateMaps(const std::vector<OccupancyGrid>& maps,
                                           const std::vector<PairOutcome>& pairs,
                                           const FleetGraph& graph, std::int64_t min_overlap_cells,
                                           double min_wall_agreement,
                                           const PoseGraphOptions& options);

// The map with the largest majority of conflicts over supporters, or -1 if no map has more
// conflicts than supporters (a tie keeps the map: a pair search can miss a true pose).
int LeastCorroboratedMap(const std::vector<Corroboration>& verdicts);

}  // namespace fleetmerge
