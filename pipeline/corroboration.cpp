#include "pipeline/corroboration.hpp"

#include <algorithm>
#include <cmath>

#include "core/acceptance_index.hpp"
#include "core/error.hpp"
#include "core/hypothesis_generator.hpp"
#include "core/parallel.hpp"
#include "core/wall_agreement.hpp"

namespace fleetmerge {
namespace {

// Whether one of the pair's hypotheses puts m at T_n_m (tolerances doubled, as for a triangle:
// two pairwise errors and the solve's).
bool SomeHypothesisAgrees(const PairOutcome& pair, int n, const Pose2& T_n_m,
                          const PoseGraphOptions& options) {
  for (const PairHypothesis& h : pair.hypotheses) {
    const Pose2 T = pair.a == n ? h.T_a_b : h.T_a_b.inverse();
    const Pose2 delta = T.inverse() * T_n_m;
    if (std::abs(delta.yaw_rad()) <= 2.0 * options.max_edge_yaw_error_rad &&
        delta.translation_m().norm() <= 2.0 * options.max_edge_translation_error_m) {
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<PairVerdict> JudgeSolvedPairs(const std::vector<OccupancyGrid>& maps,
                                          const std::vector<MapWalls>& walls,
                                          const std::vector<PairOutcome>& pairs,
                                          const FleetGraph& graph, std::int64_t min_overlap_cells,
                                          double min_wall_agreement,
                                          const PoseGraphOptions& options, int threads) {
  if (walls.size() != maps.size()) throw Error("internal: wall features for another fleet");
  std::vector<std::optional<PairVerdict>> judged(pairs.size());
  ParallelFor(pairs.size(), threads, [&](std::size_t k) {
    const PairOutcome& pair = pairs[k];
    const int a = pair.a, b = pair.b;
    if (graph.component_of[a] != graph.component_of[b]) return;
    const Pose2 T_a_b = graph.T_component_map[a].inverse() * graph.T_component_map[b];
    const Pose2 T_ga_gb = CellPoseFromMapPose(maps[a].geometry(), maps[b].geometry(), T_a_b);
    const Agreement overlap = CountAgreement(maps[a], maps[b], T_ga_gb, 2, &walls[b].known_spans);
    // Stride 2 visits a quarter of b's cells.
    if (4 * (overlap.agree + overlap.disagree) < min_overlap_cells) return;
    // A pair search can miss a true pose where the maps share little; the walls at the solved
    // pose then still agree.
    const double wall_agreement = SymmetricWallAgreement(walls[a], walls[b], T_ga_gb);
    const bool agrees =
        SomeHypothesisAgrees(pair, a, T_a_b, options) || wall_agreement >= min_wall_agreement;
    judged[k] = PairVerdict{a, b, agrees, wall_agreement, 4 * (overlap.agree + overlap.disagree)};
  });
  std::vector<PairVerdict> verdicts;
  for (const auto& v : judged) {
    if (v) verdicts.push_back(*v);
  }
  return verdicts;
}

namespace {

// The verdicts across the split of `members` into those with side[m] and the others; the side
// with fewer maps is named (on a tie, the one without members[0]).
ComponentSplit CrossVerdicts(const std::vector<PairVerdict>& inside,
                             const std::vector<int>& members, const std::vector<bool>& side,
                             int side_size) {
  ComponentSplit split;
  for (const PairVerdict& v : inside) {
    if (side[v.a] == side[v.b]) continue;
    (v.agrees ? split.supporters : split.conflicts)++;
    (v.agrees ? split.supporter_cells : split.conflict_cells) += v.overlap_cells;
    if (v.agrees) split.supporter_walls += v.wall_agreement;
  }
  const bool named = 2 * side_size <= static_cast<int>(members.size());
  for (const int m : members) {
    if (side[m] == named) split.detached.push_back(m);
  }
  return split;
}

bool Better(const ComponentSplit& candidate, const std::optional<ComponentSplit>& best) {
  const int margin = candidate.conflicts - candidate.supporters;
  if (margin <= 0) return false;
  // The supporters overlap on more cells: one pair that agrees over most of a map outweighs a
  // few that disagree over slivers of it (where racks or walls seen from the other side differ).
  if (candidate.supporter_cells > candidate.conflict_cells) return false;
  if (!best) return true;
  const int best_margin = best->conflicts - best->supporters;
  if (margin != best_margin) return margin > best_margin;
  if (candidate.supporter_walls != best->supporter_walls) {
    return candidate.supporter_walls < best->supporter_walls;
  }
  return candidate.detached.size() < best->detached.size();
}

}  // namespace

std::optional<ComponentSplit> MostContradictedSplit(const std::vector<PairVerdict>& verdicts,
                                                    const std::vector<int>& component_of,
                                                    int max_exhaustive_maps) {
  const int map_count = static_cast<int>(component_of.size());
  std::optional<ComponentSplit> best;
  for (int c = 0; c < map_count; ++c) {
    std::vector<int> members;
    for (int m = 0; m < map_count; ++m) {
      if (component_of[m] == c) members.push_back(m);
    }
    std::vector<PairVerdict> inside;
    for (const PairVerdict& v : verdicts) {
      if (component_of[v.a] == c) inside.push_back(v);
    }
    const int n = static_cast<int>(members.size());
    if (n < 2 || inside.empty()) continue;
    std::vector<bool> side(map_count, false);
    // 2^(n-1) splits: capped so that the mask fits and the count stays small.
    if (n <= std::min(max_exhaustive_maps, 20)) {
      // members[0] stays off the mask: each split is visited once (2^(n-1) - 1 of them).
      for (std::uint32_t mask = 1; mask < (1u << (n - 1)); ++mask) {
        int side_size = 0;
        for (int k = 1; k < n; ++k) {
          side[members[k]] = (mask >> (k - 1)) & 1u;
          side_size += side[members[k]];
        }
        const ComponentSplit split = CrossVerdicts(inside, members, side, side_size);
        if (Better(split, best)) best = split;
      }
    } else {
      for (const int m : members) {
        std::fill(side.begin(), side.end(), false);
        side[m] = true;
        const ComponentSplit split = CrossVerdicts(inside, members, side, 1);
        if (Better(split, best)) best = split;
      }
    }
  }
  return best;
}

}  // namespace fleetmerge
