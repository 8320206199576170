// Lone links (beyond the paper): an accepted edge that is the only link between two groups of
// maps is a bridge of the pose graph. No cycle closes through it (fleet_graph.hpp) and, in the
// cases measured, no other pair's search confirmed one, so its own evidence is all there is.
//
// The edge thresholds (omega, overlap, walls) are set for edges that cycles and cross pairs then
// check. A map of another building built from the same modules (a second synthetic office, or a
// floor that repeats another) matches one map of a fleet by chance often enough: on 288
// simulated cases (146 with such a map), 11 wrong bridges passed the thresholds with omega
// 0.92-0.98 over 5600-21700 cells, 8 of them with wall agreement 0.80-0.87 (with the current
// pair search one more, at 0.882), while every true bridge had >= 0.897 (docs/accuracy.md, "Lone
// links"). So a bridge needs walls between the two. Neither omega, the overlap, nor the share of
// the smaller map it covers told them apart; wrong bridges at 0.90-0.96 remain possible.
//
// A component of two maps is exempt: its one edge is the whole merge of those two maps, not a
// map hanging on a fleet, and maps of one floor from different SLAM runs agree less (walls
// 0.83-0.88 for the Robotis corridor runs) while they are true.
//
// So is an edge on the best hypothesis of a pair with a fixed map (a site map): the robot's whole
// map was searched for inside the whole building (FleetOptions::fixed_map_free_penalty), not a
// chance overlap of two parts. Robots simulated in 14 real buildings against the building's map
// (700 pairs, `scripts/fixed_base_accuracy.sh`): the one wrong best hypothesis had omega 0.89 and
// walls 0.18, while 36 of Willow Garage's 50 right ones have walls 0.83-0.89 and would be cut.
// The robot of the next building that each of those 140 cases holds had a pair with the base
// of walls 0.72 at most (a Nav2 warehouse robot in the Nav2 depot), and none was accepted.
#pragma once

#include <optional>
#include <vector>

#include "pipeline/all_pairs.hpp"
#include "pipeline/corroboration.hpp"

namespace fleetmerge {

// An ambiguous pair (core/pose_evidence.hpp: its runner-up, a different pose, is as good) is an
// edge only when something else confirms the pose it was decided on: a cycle through it (the
// cycle checks of fleet_graph.hpp kept it), or, for a bridge, another pair across it that
// supports the solved poses (a verdict of corroboration.hpp). Returns the index in `pairs` of
// the first accepted ambiguous edge on its best hypothesis that nothing confirms, or none. A
// two-map component has nothing to confirm its edge with, so an ambiguous pair alone is not
// merged.
std::optional<int> UnconfirmedAmbiguousEdge(int map_count, const std::vector<PairOutcome>& pairs,
                                            const std::vector<PairVerdict>& verdicts);

// The index in `pairs` of the accepted bridge edge with the weakest walls among those of
// components of three or more maps whose walls are below min_wall_agreement, or none.
// `fixed_maps`: one flag per map (empty: none fixed); an edge on the best hypothesis of a pair
// with a fixed map is never named.
std::optional<int> WeakestBridge(int map_count, const std::vector<PairOutcome>& pairs,
                                 double min_wall_agreement,
                                 const std::vector<char>& fixed_maps = {});

}  // namespace fleetmerge
