#include "pipeline/all_pairs.hpp"

#include <algorithm>
#include <atomic>
#include <memory>
#include <mutex>

#include "core/hypothesis_generator.hpp"
#include "core/map_features.hpp"
#include "core/parallel.hpp"
#include "core/wall_agreement.hpp"
#include "pipeline/prepared_map.hpp"

namespace fleetmerge {
namespace {

PairOutcome ComputePair(const std::vector<std::unique_ptr<PreparedMap>>& maps, int a, int b,
                        const PairOptions& options) {
  PairOutcome outcome;
  outcome.a = a;
  outcome.b = b;
  const OccupancyGrid& ga = maps[a]->grid();
  const OccupancyGrid& gb = maps[b]->grid();
  const RankedHypotheses ranked = RankedCellHypotheses(*maps[a], *maps[b], options);
  for (const CellHypothesis& h : ranked.hypotheses) {
    outcome.hypotheses.push_back(ToPairHypothesis(ga, gb, h));
  }
  if (!outcome.hypotheses.empty()) {
    outcome.wall_agreement = outcome.hypotheses.front().wall_agreement;
    outcome.overlap_cells = outcome.hypotheses.front().overlap_cells;
  }
  outcome.margin_nats = ranked.margin_nats;
  outcome.ambiguous = ranked.ambiguous;
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
  // Each map's own work once, shared by its maps.size() - 1 pairs (pipeline/prepared_map.hpp).
  std::vector<std::unique_ptr<PreparedMap>> prepared(maps.size());
  ParallelFor(maps.size(), threads, [&](std::size_t m) {
    prepared[m] = std::make_unique<PreparedMap>(maps[m], options);
  });
  std::vector<PairOutcome> outcomes(jobs.size());
  std::atomic<int> done{0};
  std::mutex progress_mutex;
  ParallelFor(jobs.size(), threads, [&](std::size_t k) {
    outcomes[k] = ComputePair(prepared, jobs[k].first, jobs[k].second, options);
    const int finished = ++done;
    if (progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      progress("pairs", finished, static_cast<int>(jobs.size()));
    }
  });
  return outcomes;
}

}  // namespace fleetmerge
