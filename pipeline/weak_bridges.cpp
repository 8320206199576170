#include "pipeline/weak_bridges.hpp"

#include "pipeline/fleet_graph.hpp"

namespace fleetmerge {
namespace {

// The pair's walls are measured for its best hypothesis. An edge on another one was chosen by
// the cycles it closed; as a bridge those are gone, and it has no measured walls.
double EdgeWalls(const PairOutcome& p) { return p.edge_hypothesis == 0 ? p.wall_agreement : 0.0; }

}  // namespace

std::optional<int> WeakestBridge(int map_count, const std::vector<PairOutcome>& pairs,
                                 double min_wall_agreement) {
  const std::vector<int> component_of = Components(map_count, pairs);
  std::vector<int> component_size(map_count, 0);
  for (const int c : component_of) ++component_size[c];
  std::optional<int> weakest;
  for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
    const PairOutcome& p = pairs[k];
    if (!p.accepted || component_size[component_of[p.a]] < 3) continue;
    const double walls = EdgeWalls(p);
    if (walls >= min_wall_agreement) continue;
    if (weakest && walls >= EdgeWalls(pairs[*weakest])) continue;
    const std::vector<int> without = Components(map_count, pairs, k);
    if (without[p.a] != without[p.b]) weakest = k;
  }
  return weakest;
}

}  // namespace fleetmerge
