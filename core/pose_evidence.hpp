// How much evidence two maps give for one pose, against chance, and how the hypotheses of a pair
// are ranked with it (beyond the paper).
//
// Omega (Eq. 1) is a share: the agreeing fraction of the cells both maps know. In a repetitive
// building two different poses can both reach omega 0.988 within 0.001 of each other (a
// Willow Garage-like office: the true pose ranked third), and the share alone cannot say which
// explains more of the maps. The evidence counts instead: each cell known in both maps and each
// wall landing on the other map's known cells is an observation, scored by the log-likelihood
// ratio of "the pose is right" against "the maps lie at random", with chance rates measured on
// the two maps themselves:
//
//   cells: agree * ln(q_c / p_c) + disagree * ln((1 - q_c) / (1 - p_c)),
//          p_c = o_a o_b + (1 - o_a)(1 - o_b)   (o = a map's occupied share of its known cells)
//   walls, each way: near * ln(q_w / p_w) + far * ln((1 - q_w) / (1 - p_w)),
//          p_w = the share of walls near walls with the same pose 4 cells off along each axis:
//          the rotation search has aligned the walls' directions, so a wrong translation meets
//          walls far more often than the map's share of near-wall cells would say
//
// q_c = 0.99 and q_w = 0.98 are what a right pose gives (omega and wall agreement of right poses
// measured on real maps: 0.97-0.99 and 0.83-1.00, docs/method.md), at the upper ends so that
// disagreement weighs. Neighbouring cells are not independent (a
// wall is 1-2 cells thick, the wall tolerance is a cell), so the sum is divided by the cells of
// a 3 x 3 neighbourhood: the result is in nats of roughly independent evidence.
//
// Ranking: a hypothesis tied with the best on omega (within kOmegaTie, with enough overlap) is
// ranked among them by its evidence; the others keep omega's order. The pair is ambiguous when
// its runner-up is tied so and the best leads it by less than kAmbiguousMarginNats: the maps
// cannot tell the two poses apart, and the answer would be a coin toss.
#pragma once

#include <cstdint>
#include <vector>

#include "core/hypothesis_generator.hpp"
#include "core/map_features.hpp"

namespace fleetmerge {

// Omega differences this small are noise (a few hundred cells of a map's edges): seen in a
// simulated office with little overlap, a wrong pose at omega 0.976 (walls 0.92, 3000 cells)
// ranked above the true one at 0.974 (walls 0.97, 14700 cells).
inline constexpr double kOmegaTie = 0.01;

// ln(20): the best pose is less than 20 times as likely as the runner-up.
inline constexpr double kAmbiguousMarginNats = 3.0;

// Log-likelihood ratio (nats, see above) of hypothesis h (omega and overlap set) of maps a, b.
// Also sets h.wall_agreement (SymmetricWallAgreement).
double MeasureEvidence(const MapFeatures& a, const MapFeatures& b, CellHypothesis& h);

struct RankedHypotheses {
  std::vector<CellHypothesis> hypotheses;  // best first
  // Evidence of the best minus that of the runner-up (nats); +infinity without a runner-up.
  // Negative only when the runner-up is clearly worse on omega (beyond kOmegaTie) but has more
  // evidence, e.g. a larger overlap that agrees less: omega decided that pair.
  double margin_nats = 0.0;
  bool ambiguous = false;  // the runner-up, a different pose, is tied with the best
};

// Ranks the hypotheses (see above): sets every hypothesis' wall agreement, and the evidence of
// those it compares (the tie and the runner-up; NaN for the others). `sorted` is in
// SortHypotheses' order and free of duplicates (each a different pose). The hypotheses are
// measured on `threads` threads (<= 0: all cores), each on its own: the same result for any count.
RankedHypotheses RankByEvidence(const MapFeatures& a, const MapFeatures& b,
                                std::vector<CellHypothesis> sorted, std::int64_t min_overlap_cells,
                                int threads = 1);

}  // namespace fleetmerge
