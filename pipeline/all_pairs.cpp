#include "pipeline/all_pairs.hpp"

#include <algorithm>
#include <atomic>
#include <memory>
#include <mutex>

#include "core/hypothesis_generator.hpp"
#include "core/map_features.hpp"
#include "core/wall_agreement.hpp"
#include "core/parallel.hpp"
#include "pipeline/prepared_map.hpp"

namespace fleetmerge {
namespace {

// Omega differences this small are noise (a few hundred cells of a map's edges), while the walls
// are selective: among hypotheses tied with the best, the one whose walls agree best leads. Seen
// in a simulated office with little overlap: a wrong pose at omega 0.976 (walls 0.92, 3000 cells)
// ranked above the true one at 0.974 (walls 0.97, 14700 cells).
constexpr double kOmegaTie = 0.01;

// Moves to the front the hypothesis tied with the best (omega within kOmegaTie, enough overlap)
// whose walls agree best; returns its wall agreement.
double PromoteBestWalls(const MapFeatures& a, const MapFeatures& b,
                        std::vector<CellHypothesis>& ranked, std::int64_t min_overlap_cells) {
  std::size_t best = 0;
  double best_walls = SymmetricWallAgreement(a, b, ranked.front().T_ga_gb);
  for (std::size_t k = 1; k < ranked.size(); ++k) {
    if (ranked[k].omega < ranked.front().omega - kOmegaTie) break;
    if (ranked[k].overlap_cells < min_overlap_cells) continue;
    const double walls = SymmetricWallAgreement(a, b, ranked[k].T_ga_gb);
    if (walls > best_walls) best = k, best_walls = walls;
  }
  std::rotate(ranked.begin(), ranked.begin() + best, ranked.begin() + best + 1);
  return best_walls;
}

PairOutcome ComputePair(const std::vector<std::unique_ptr<PreparedMap>>& maps, int a, int b,
                        const PairOptions& options) {
  PairOutcome outcome;
  outcome.a = a;
  outcome.b = b;
  const OccupancyGrid& ga = maps[a]->grid();
  const OccupancyGrid& gb = maps[b]->grid();
  std::vector<CellHypothesis> ranked = RankedCellHypotheses(*maps[a], *maps[b], options);
  if (!ranked.empty()) {
    outcome.wall_agreement = PromoteBestWalls(maps[a]->features(), maps[b]->features(), ranked,
                                              options.hypotheses.min_overlap_cells);
    outcome.overlap_cells = ranked.front().overlap_cells;
  }
  for (const CellHypothesis& h : ranked) {
    outcome.hypotheses.push_back(
        {MapPoseFromCellPose(ga.geometry(), gb.geometry(), h.T_ga_gb), h.omega});
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
