#include "pipeline/pair_merge.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/acceptance_index.hpp"
#include "core/parallel.hpp"
#include "core/resample.hpp"
#include "core/translation_search.hpp"

namespace fleetmerge {
namespace {

Pose2 ScaleTranslation(const Pose2& T, double factor) {
  return Pose2(T.translation_m() * factor, T.yaw_rad());
}

// One map pair for refinement: alignment targets (distance fields) on grids `scale` times
// coarser than a and b (the cell-unit poses scale by 1 / scale), and b's known spans for omega
// at full resolution.
struct PairContext {
  PairContext(const PreparedMap& a, const PreparedMap& b, int scale)
      : a(a.grid()),
        b(b.grid()),
        scale(scale),
        target_a(a.Target(scale)),
        target_b(b.Target(scale)),
        b_spans(b.features().walls.known_spans) {}
  const OccupancyGrid& a;
  const OccupancyGrid& b;
  int scale;
  const AlignmentTarget& target_a;
  const AlignmentTarget& target_b;
  const RowSpans& b_spans;
};

// Refines each hypothesis and keeps the refined pose unless omega (at full resolution) says it
// got worse: the alignment cost and omega can disagree when the maps barely overlap.
// Each hypothesis on its own (in parallel on `threads`), so the result does not depend on them.
void RefineAll(const PairContext& pair, std::vector<CellHypothesis>& hypotheses,
               const LocalAlignmentOptions& options, std::int64_t min_overlap_cells, int threads) {
  ParallelFor(hypotheses.size(), threads, [&](std::size_t k) {
    CellHypothesis& h = hypotheses[k];
    const LocalAlignmentResult r = RefineAlignment(
        pair.target_a, pair.target_b, ScaleTranslation(h.T_ga_gb, 1.0 / pair.scale), options);
    if (!r.converged) return;
    const Pose2 T_ga_gb = ScaleTranslation(r.T_ga_gb, pair.scale);
    const Agreement agreement = CountAgreement(pair.a, pair.b, T_ga_gb, 1, &pair.b_spans);
    if (agreement.omega() >= h.omega - 0.01) {  // Eq. (1)
      h = {T_ga_gb, agreement.omega(), agreement.agree + agreement.disagree};
    }
  });
  SortHypotheses(hypotheses, min_overlap_cells);
}

// The coarse stage's grid scale: its basin (refine_truncation_cells coarse cells) must bridge
// the translation search's error, quick_basin_pixels of its pooled pixels.
int CoarseScale(const OccupancyGrid& a, const OccupancyGrid& b, const PairOptions& options) {
  const TranslationOptions& t = options.hypotheses.translation;
  if (t.method != TranslationMethod::kCorrelation2D) return 1;
  const double needed_cells = options.quick_basin_pixels * CorrelationPooling(a, b, t);
  return std::max(1, static_cast<int>(std::ceil(needed_cells / options.refine_truncation_cells)));
}

// Whether the pair is searched the other way round, b against a: when a is more than twice b's
// extent (a robot's map listed after a site map). Rotating the larger map over the smaller one
// found robots of 50 m paths in a 4000 x 4000 site where the other way round put 2 of 30 on
// rooms of other buildings (scripts/large_site_benchmark.sh with PATH_M 50); maps of similar
// size, a fleet's robots, are searched as given.
bool SearchedFromB(const OccupancyGrid& a, const OccupancyGrid& b) {
  return FixedExtentCells(a) > 2.0 * RotatedExtentCells(b);
}

}  // namespace

PairHypothesis ToPairHypothesis(const OccupancyGrid& a, const OccupancyGrid& b,
                                const CellHypothesis& h) {
  return {MapPoseFromCellPose(a.geometry(), b.geometry(), h.T_ga_gb), h.omega, h.overlap_cells,
          h.wall_agreement, h.evidence_nats};
}

RankedHypotheses RankedCellHypotheses(const OccupancyGrid& a, const OccupancyGrid& b,
                                      const PairOptions& options, int threads) {
  std::unique_ptr<PreparedMap> prepared[2];
  const OccupancyGrid* grids[2] = {&a, &b};
  ParallelFor(2, threads, [&](std::size_t k) {
    prepared[k] = std::make_unique<PreparedMap>(*grids[k], options);
    // The final refinement's target, made here in parallel (a map without walls has none).
    if (options.refine && !prepared[k]->features().walls.centres.empty()) prepared[k]->Target(1);
  });
  return RankedCellHypotheses(*prepared[0], *prepared[1], options, threads);
}

RankedHypotheses RankedCellHypotheses(const PreparedMap& prepared_a, const PreparedMap& prepared_b,
                                      const PairOptions& options, int threads) {
  const OccupancyGrid& a = prepared_a.grid();
  const OccupancyGrid& b = prepared_b.grid();
  if (SearchedFromB(a, b)) {  // and not back again: b's side is under half a's
    RankedHypotheses ranked = RankedCellHypotheses(prepared_b, prepared_a, options, threads);
    for (CellHypothesis& h : ranked.hypotheses) h.T_ga_gb = h.T_ga_gb.inverse();
    return ranked;
  }
  const int wanted = options.hypotheses.max_hypotheses;
  HypothesisOptions generation = options.hypotheses;
  if (options.refine) generation.max_hypotheses *= std::max(options.candidates_per_hypothesis, 1);
  std::vector<CellHypothesis> hypotheses =
      GenerateHypotheses(prepared_a.features(), prepared_b.features(), generation, threads);
  if (options.refine && !hypotheses.empty()) {
    // Coarse-to-fine: every candidate on coarse grids with a wide basin, then the best at full
    // resolution.
    const int scale = CoarseScale(a, b, options);
    const PreparedMap* both[2] = {&prepared_a, &prepared_b};
    ParallelFor(2, threads, [&](std::size_t k) { both[k]->Target(scale); });
    RefineAll(PairContext(prepared_a, prepared_b, scale), hypotheses, options.quick_refine,
              options.hypotheses.min_overlap_cells, threads);
    const std::size_t best = std::min<std::size_t>(options.final_refine_count, hypotheses.size());
    std::vector<CellHypothesis> head(hypotheses.begin(), hypotheses.begin() + best);
    RefineAll(PairContext(prepared_a, prepared_b, 1), head, options.final_refine,
              options.hypotheses.min_overlap_cells, threads);
    std::copy(head.begin(), head.end(), hypotheses.begin());
    SortHypotheses(hypotheses, options.hypotheses.min_overlap_cells);
    // Several candidates may have converged onto one pose.
    hypotheses = RemoveDuplicates(std::move(hypotheses), options.hypotheses);
  }
  // Ranked before the cut, so that a runner-up beyond `wanted` still tells a coin toss.
  RankedHypotheses ranked =
      RankByEvidence(prepared_a.features(), prepared_b.features(), std::move(hypotheses),
                     options.hypotheses.min_overlap_cells, threads);
  if (static_cast<int>(ranked.hypotheses.size()) > wanted) {
    ranked.hypotheses.resize(std::max(wanted, 0));
  }
  return ranked;
}

PairResult MergePair(const OccupancyGrid& a, const OccupancyGrid& b, const PairOptions& options,
                     int threads) {
  PairResult result;
  const double ra = a.geometry().resolution_m(), rb = b.geometry().resolution_m();
  result.resolution_m = std::min(ra, rb);
  result.resampled = std::abs(ra - rb) > 1e-9 * result.resolution_m;
  // A copy for the map already at the finer resolution (ResampleToResolution's contract).
  OccupancyGrid same[2];
  const OccupancyGrid* grids[2] = {&a, &b};
  ParallelFor(2, threads, [&](std::size_t k) {
    same[k] = ResampleToResolution(*grids[k], result.resolution_m);
  });
  const OccupancyGrid& a_same = same[0];
  const OccupancyGrid& b_same = same[1];
  const RankedHypotheses ranked = RankedCellHypotheses(a_same, b_same, options, threads);
  for (const CellHypothesis& h : ranked.hypotheses) {
    result.hypotheses.push_back(ToPairHypothesis(a_same, b_same, h));
  }
  result.margin_nats = ranked.margin_nats;
  result.ambiguous = ranked.ambiguous;
  return result;
}

}  // namespace fleetmerge
