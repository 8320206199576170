#include "pipeline/pair_merge.hpp"

#include <algorithm>

#include "core/acceptance_index.hpp"
#include "core/resample.hpp"

namespace fleetmerge {
namespace {

void SortByOmega(std::vector<CellHypothesis>& hypotheses) {
  std::stable_sort(hypotheses.begin(), hypotheses.end(),
                   [](const auto& l, const auto& r) { return l.omega > r.omega; });
}

// Refines each hypothesis and keeps the refined pose unless omega says it got worse: the
// alignment cost and omega can disagree when the maps barely overlap.
struct PairContext {
  const OccupancyGrid& a;
  const OccupancyGrid& b;
  AlignmentTarget target_a, target_b;
  RowSpans b_spans;
};

void RefineAll(const PairContext& pair, std::vector<CellHypothesis>& hypotheses,
               const LocalAlignmentOptions& options) {
  const auto& [a, b, target_a, target_b, b_spans] = pair;
  for (auto& h : hypotheses) {
    const LocalAlignmentResult r = RefineAlignment(target_a, target_b, h.T_ga_gb, options);
    if (!r.converged) continue;
    const double omega = CountAgreement(a, b, r.T_ga_gb, 1, &b_spans).omega();  // Eq. (1)
    if (omega >= h.omega - 0.01) h = {r.T_ga_gb, omega};
  }
  SortByOmega(hypotheses);
}

}  // namespace

std::vector<CellHypothesis> RankedCellHypotheses(const OccupancyGrid& a, const OccupancyGrid& b,
                                                 const PairOptions& options) {
  std::vector<CellHypothesis> hypotheses = GenerateHypotheses(a, b, options.hypotheses);
  if (!options.refine || hypotheses.empty()) return hypotheses;
  const PairContext pair{a, b, AlignmentTarget(a, options.refine_truncation_cells),
                         AlignmentTarget(b, options.refine_truncation_cells), KnownRowSpans(b)};
  RefineAll(pair, hypotheses, options.quick_refine);
  const std::size_t best = std::min<std::size_t>(options.final_refine_count, hypotheses.size());
  std::vector<CellHypothesis> head(hypotheses.begin(), hypotheses.begin() + best);
  RefineAll(pair, head, options.final_refine);
  std::copy(head.begin(), head.end(), hypotheses.begin());
  SortByOmega(hypotheses);
  // Two hypotheses may have converged onto one pose.
  return RemoveDuplicates(std::move(hypotheses), options.hypotheses);
}

PairResult MergePair(const OccupancyGrid& a, const OccupancyGrid& b, const PairOptions& options) {
  PairResult result;
  const double ra = a.geometry().resolution_m(), rb = b.geometry().resolution_m();
  result.resolution_m = std::min(ra, rb);
  result.resampled = std::abs(ra - rb) > 1e-9 * result.resolution_m;
  const OccupancyGrid a_same = ra > result.resolution_m && result.resampled
                                   ? ResampleToResolution(a, result.resolution_m)
                                   : a;
  const OccupancyGrid b_same = rb > result.resolution_m && result.resampled
                                   ? ResampleToResolution(b, result.resolution_m)
                                   : b;
  for (const auto& h : RankedCellHypotheses(a_same, b_same, options)) {
    result.hypotheses.push_back(
        {MapPoseFromCellPose(a_same.geometry(), b_same.geometry(), h.T_ga_gb), h.omega});
  }
  return result;
}

}  // namespace fleetmerge
