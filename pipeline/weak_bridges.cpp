#include "pipeline/weak_bridges.hpp"

#include <numeric>

namespace fleetmerge {
namespace {

// Union-find over the accepted edges other than pairs[skip] (-1: all).
struct Connectivity {
  Connectivity(int map_count, const std::vector<PairOutcome>& pairs, int skip) : parent(map_count) {
    std::iota(parent.begin(), parent.end(), 0);
    for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
      if (k != skip && pairs[k].accepted) parent[Find(pairs[k].a)] = Find(pairs[k].b);
    }
  }
  int Find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  std::vector<int> parent;
};

// The pair's walls are measured for its best hypothesis. An edge on another one was chosen by
// the cycles it closed; as a bridge those are gone, and it has no measured walls.
double EdgeWalls(const PairOutcome& p) { return p.edge_hypothesis == 0 ? p.wall_agreement : 0.0; }

}  // namespace

std::optional<int> WeakestBridge(int map_count, const std::vector<PairOutcome>& pairs,
                                 double min_wall_agreement) {
  Connectivity all(map_count, pairs, -1);
  std::vector<int> component_size(map_count, 0);
  for (int m = 0; m < map_count; ++m) ++component_size[all.Find(m)];
  std::optional<int> weakest;
  for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
    const PairOutcome& p = pairs[k];
    if (!p.accepted || component_size[all.Find(p.a)] < 3) continue;
    const double walls = EdgeWalls(p);
    if (walls >= min_wall_agreement) continue;
    if (weakest && walls >= EdgeWalls(pairs[*weakest])) continue;
    Connectivity without(map_count, pairs, k);
    if (without.Find(p.a) != without.Find(p.b)) weakest = k;
  }
  return weakest;
}

}  // namespace fleetmerge
