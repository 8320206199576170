#include "pipeline/weak_bridges.hpp"

#include <algorithm>

#include "pipeline/fleet_graph.hpp"

namespace fleetmerge {
namespace {

// The pair's walls are measured for its best hypothesis. An edge on another one was chosen by
// the cycles it closed; as a bridge those are gone, and it has no measured walls.
double EdgeWalls(const PairOutcome& p) { return p.edge_hypothesis == 0 ? p.wall_agreement : 0.0; }

}  // namespace

std::optional<int> WeakestBridge(int map_count, const std::vector<PairOutcome>& pairs,
                                 double min_wall_agreement, const std::vector<char>& fixed_maps) {
  const auto with_fixed_map = [&](const PairOutcome& p) {
    return !fixed_maps.empty() && (fixed_maps[p.a] || fixed_maps[p.b]);
  };
  const std::vector<int> component_of = Components(map_count, pairs);
  std::vector<int> component_size(map_count, 0);
  for (const int c : component_of) ++component_size[c];
  std::optional<int> weakest;
  for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
    const PairOutcome& p = pairs[k];
    if (!p.accepted || component_size[component_of[p.a]] < 3) continue;
    if (p.edge_hypothesis == 0 && with_fixed_map(p)) continue;
    const double walls = EdgeWalls(p);
    if (walls >= min_wall_agreement) continue;
    if (weakest && walls >= EdgeWalls(pairs[*weakest])) continue;
    const std::vector<int> without = Components(map_count, pairs, k);
    if (without[p.a] != without[p.b]) weakest = k;
  }
  return weakest;
}

std::optional<int> UnconfirmedAmbiguousEdge(int map_count, const std::vector<PairOutcome>& pairs,
                                            const std::vector<PairVerdict>& verdicts) {
  for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
    const PairOutcome& p = pairs[k];
    // An edge on another hypothesis was chosen by the cycles it closes: confirmed.
    if (!p.accepted || !p.ambiguous || p.edge_hypothesis != 0) continue;
    const std::vector<int> without = Components(map_count, pairs, k);
    if (without[p.a] == without[p.b]) continue;  // a cycle passes through it
    const auto across = [&](const PairVerdict& v) {
      if (v.a == p.a && v.b == p.b) return false;  // the pair itself
      return (without[v.a] == without[p.a] && without[v.b] == without[p.b]) ||
             (without[v.a] == without[p.b] && without[v.b] == without[p.a]);
    };
    const bool confirmed = std::any_of(verdicts.begin(), verdicts.end(),
                                       [&](const auto& v) { return v.agrees && across(v); });
    if (!confirmed) return k;
  }
  return std::nullopt;
}

}  // namespace fleetmerge
