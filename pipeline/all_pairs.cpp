#include "pipeline/all_pairs.hpp"

#include <atomic>
#include <mutex>

#include "core/hypothesis_generator.hpp"
#include "core/wall_agreement.hpp"
#include "pipeline/parallel.hpp"

namespace fleetmerge {
namespace {

PairOutcome ComputePair(const std::vector<OccupancyGrid>& maps, int a, int b,
                        const PairOptions& options) {
  PairOutcome outcome;
  outcome.a = a;
  outcome.b = b;
  const OccupancyGrid& ga = maps[a];
  const OccupancyGrid& gb = maps[b];
  const std::vector<CellHypothesis> ranked = RankedCellHypotheses(ga, gb, options);
  for (const CellHypothesis& h : ranked) {
    outcome.hypotheses.push_back(
        {MapPoseFromCellPose(ga.geometry(), gb.geometry(), h.T_ga_gb), h.omega});
  }
  if (!ranked.empty()) {
    outcome.overlap_cells = ranked.front().overlap_cells;
    outcome.wall_agreement = SymmetricWallAgreement(ga, gb, ranked.front().T_ga_gb);
  }
  return outcome;
}

}  // namespace

std::vector<PairOutcome> ComputeAllPairs(const std::vector<OccupancyGrid>& maps,
                                         const PairOptions& options, int threads,
                                         const ProgressFn& progress) {
  std::vector<std::pair<int, int>> jobs;
  for (int a = 0; a < static_cast<int>(maps.size()); ++a) {
    for (int b = a + 1; b < static_cast<int>(maps.size()); ++b) jobs.emplace_back(a, b);
  }
  std::vector<PairOutcome> outcomes(jobs.size());
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  ParallelFor(jobs.size(), threads, [&](std::size_t k) {
    outcomes[k] = ComputePair(maps, jobs[k].first, jobs[k].second, options);
    const int finished = ++done;
    if (progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      progress("pairs", finished, static_cast<int>(jobs.size()));
    }
  });
  return outcomes;
}

}  // namespace fleetmerge
