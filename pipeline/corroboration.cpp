#include "pipeline/corroboration.hpp"

#include <cmath>

#include "core/acceptance_index.hpp"
#include "core/hypothesis_generator.hpp"
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

std::vector<Corroboration> CorroborateMaps(const std::vector<OccupancyGrid>& maps,
                                           const std::vector<PairOutcome>& pairs,
                                           const FleetGraph& graph, std::int64_t min_overlap_cells,
                                           double min_wall_agreement,
                                           const PoseGraphOptions& options) {
  std::vector<Corroboration> verdicts(maps.size());
  for (const PairOutcome& pair : pairs) {
    const int a = pair.a, b = pair.b;
    if (graph.component_of[a] != graph.component_of[b]) continue;
    const Pose2 T_a_b = graph.T_component_map[a].inverse() * graph.T_component_map[b];
    const Pose2 T_ga_gb = CellPoseFromMapPose(maps[a].geometry(), maps[b].geometry(), T_a_b);
    const Agreement overlap = CountAgreement(maps[a], maps[b], T_ga_gb, 2);
    // Stride 2 visits a quarter of b's cells.
    if (4 * (overlap.agree + overlap.disagree) < min_overlap_cells) continue;
    // A pair search can miss a true pose where the maps share little; the walls at the solved
    // pose then still agree.
    const bool agrees = SomeHypothesisAgrees(pair, a, T_a_b, options) ||
                        SymmetricWallAgreement(maps[a], maps[b], T_ga_gb) >= min_wall_agreement;
    for (const int m : {a, b}) (agrees ? verdicts[m].supporters : verdicts[m].conflicts)++;
  }
  return verdicts;
}

int LeastCorroboratedMap(const std::vector<Corroboration>& verdicts) {
  int worst = -1;
  for (int m = 0; m < static_cast<int>(verdicts.size()); ++m) {
    const Corroboration& v = verdicts[m];
    if (v.conflicts <= v.supporters) continue;
    if (worst < 0 ||
        v.conflicts - v.supporters > verdicts[worst].conflicts - verdicts[worst].supporters) {
      worst = m;
    }
  }
  return worst;
}

}  // namespace fleetmerge
