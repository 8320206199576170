// Corroboration of the solved fleet (beyond the paper): a map placed in a component must agree
// with the independent pair searches of the maps it then overlaps.
//
// A map of another building can match one map of the fleet by chance (similar corridors and rooms
// give omega >= 0.95 and wall agreement >= 0.8 for one pose) and hang on that single edge, where
// no cycle can check it. But if it truly were there, every other map that sees the same place
// would have found it there too: their pair searches, which recover true poses nearly always, put
// a hypothesis at the implied pose. So every pair (n, m) of a component that overlaps by at
// least min_overlap_cells under the solved poses is judged: it supports them (some hypothesis of
// the pair within the edge tolerances of the solved relative pose, or the two maps' walls agree
// there: a pair search can miss a true pose where two maps share little) or conflicts (neither).
// A map, or a group of maps, that the cross pairs contradict more than they support is split off
// (MostContradictedSplit).
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/wall_agreement.hpp"
#include "pipeline/all_pairs.hpp"
#include "pipeline/fleet_graph.hpp"
#include "refine/pose_graph.hpp"

namespace fleetmerge {

// One pair of maps of one component that overlap by at least min_overlap_cells under the solved
// poses: whether it supports them (agrees) or conflicts.
struct PairVerdict {
  int a = 0, b = 0;  // map indices
  bool agrees = false;
  double wall_agreement = 0.0;  // at the solved poses (core/wall_agreement.hpp)
  // Cells known in both there (counted on every other row and column, times 4).
  std::int64_t overlap_cells = 0;
};

// `walls` holds MapWalls(maps[m]) for every map (made once: the judging runs every round of
// the fleet's checks). The pairs are judged on `threads` threads (<= 0: all cores); the verdicts
// are the same, in pair order, for any count.
std::vector<PairVerdict> JudgeSolvedPairs(const std::vector<OccupancyGrid>& maps,
                                          const std::vector<MapWalls>& walls,
                                          const std::vector<PairOutcome>& pairs,
                                          const FleetGraph& graph, std::int64_t min_overlap_cells,
                                          double min_wall_agreement,
                                          const PoseGraphOptions& options, int threads = 1);

// A split of one component in two: the maps of the smaller side, and the verdicts of the pairs
// across it.
struct ComponentSplit {
  std::vector<int> detached;
  int conflicts = 0;
  int supporters = 0;
  double supporter_walls = 0.0;      // sum of the cross supporters' wall agreement
  std::int64_t conflict_cells = 0;   // sum of the cross conflicts' overlap_cells
  std::int64_t supporter_cells = 0;  // and of the cross supporters'
};

// The split of a component whose cross pairs conflict most (conflicts - supporters > 0; a tie
// between the two counts keeps the component whole: a pair search can miss a true pose), or
// none. A split whose supporters overlap on more cells than its conflicts is kept whole too: a
// pair that agrees over 86,000 cells is not outvoted by two that disagree over a few thousand
// each (racks, or walls seen from their other side, differ there: the seeds 51-68 set's Stata
// fleet 61, and the Nav2 warehouse with a fixed base and 4 robots, seed 1). A wrong edge can join a
// single map (a robot of another building) or a whole group of maps that agree among themselves
// (two robots of the other building that see the same place give two consistent wrong edges, no
// cycle contradicts them); either way the maps on the two sides that overlap under the solved poses
// contradict each other, and cutting between them resolves it. Components of up to
// max_exhaustive_maps (at most 20) maps try every split; larger ones, every single map. Among equal
// margins the split whose cross supporters have the weaker walls wins (of two groups joined
// wrongly, the true pairs inside each agree better than the chance ones between them), then the one
// detaching fewer maps.
std::optional<ComponentSplit> MostContradictedSplit(const std::vector<PairVerdict>& verdicts,
                                                    const std::vector<int>& component_of,
                                                    int max_exhaustive_maps = 16);

}  // namespace fleetmerge
