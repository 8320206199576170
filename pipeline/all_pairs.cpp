#include "pipeline/all_pairs.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <memory>
#include <mutex>
#include <optional>

#include "core/error.hpp"
#include "core/hypothesis_generator.hpp"
#include "core/map_features.hpp"
#include "core/parallel.hpp"
#include "core/wall_agreement.hpp"
#include "pipeline/pair_cache.hpp"
#include "pipeline/pair_order.hpp"
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
                                         const ProgressFn& progress, PairCache* cache,
                                         const FixedMapPairs* fixed_maps,
                                         std::vector<std::optional<MapWalls>>* walls) {
  std::vector<std::pair<int, int>> jobs;
  for (int a = 0; a < static_cast<int>(maps.size()); ++a) {
    for (int b = a + 1; b < static_cast<int>(maps.size()); ++b) jobs.emplace_back(a, b);
  }
  if (fixed_maps && fixed_maps->fixed.size() != maps.size()) {
    throw Error("ComputeAllPairs: " + std::to_string(fixed_maps->fixed.size()) +
                " fixed-map flags for " + std::to_string(maps.size()) + " maps");
  }
  const auto with_fixed_map = [&](std::size_t k) {
    return fixed_maps && (fixed_maps->fixed[jobs[k].first] || fixed_maps->fixed[jobs[k].second]);
  };
  const auto options_of = [&](std::size_t k) -> const PairOptions& {
    return with_fixed_map(k) ? fixed_maps->options : options;
  };
  std::vector<PairOutcome> outcomes(jobs.size());
  std::vector<char> found(jobs.size(), 0);
  std::vector<ContentDigest> digests;
  ContentDigest options_digest[2] = {};  // without, with a fixed map
  const auto options_digest_of = [&](std::size_t k) -> const ContentDigest& {
    return options_digest[with_fixed_map(k) ? 1 : 0];
  };
  if (cache) {
    digests.resize(maps.size());
    ParallelFor(maps.size(), threads, [&](std::size_t m) { digests[m] = MapDigest(maps[m]); });
    options_digest[0] = PairOptionsDigest(options, cache->version());
    if (fixed_maps) options_digest[1] = PairOptionsDigest(fixed_maps->options, cache->version());
    ParallelFor(jobs.size(), threads, [&](std::size_t k) {
      const auto [a, b] = jobs[k];
      if (std::optional<PairOutcome> cached =
              cache->FindPair(options_digest_of(k), digests[a], digests[b])) {
        outcomes[k] = std::move(*cached);
        outcomes[k].a = a;
        outcomes[k].b = b;
        found[k] = 1;
      }
    });
  }
  std::vector<std::size_t> missing;
  std::vector<char> needed(maps.size(), 0);
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    if (found[k]) continue;
    missing.push_back(k);
    needed[jobs[k].first] = needed[jobs[k].second] = 1;
  }
  const int total = static_cast<int>(jobs.size());
  const int cached_count = total - static_cast<int>(missing.size());
  if (cache) {
    cache->CountPairs(cached_count, static_cast<int>(missing.size()),
                      static_cast<int>(std::count(needed.begin(), needed.end(), 1)));
  }
  if (progress && cached_count > 0) progress("pairs", cached_count, total);
  // Each map's own work once, shared by its pairs (pipeline/prepared_map.hpp): made by the first
  // pair that needs it and freed after its last one. A re-run that pairs one new map with N
  // cached ones then holds the new map and one old map per thread, not N + 1 prepared maps of
  // 3-5 MB each, and its threads reuse the freed memory instead of faulting in fresh pages.
  std::vector<std::unique_ptr<PreparedMap>> prepared(maps.size());
  std::vector<std::once_flag> made(maps.size());
  std::vector<char> from_cache(maps.size(), 0);  // prepared from what the cache kept
  std::vector<std::atomic<int>> pairs_left(maps.size());
  for (const std::size_t k : missing) {
    ++pairs_left[jobs[k].first];
    ++pairs_left[jobs[k].second];
  }
  // With a cache, a map's dearest preparation (its Hough spectrum and alignment targets) is
  // taken from the cache when it kept it, and kept after the map's last pair when this run made
  // any of it (pipeline/pair_cache.hpp). A map is prepared with `options` in either kind of pair.
  const auto prepare = [&](int m) {
    std::call_once(made[m], [&] {
      std::optional<KeptPreparation> kept;
      if (cache) kept = cache->FindPreparation(options_digest[0], digests[m]);
      prepared[m] = kept ? std::make_unique<PreparedMap>(maps[m], options, std::move(*kept))
                         : std::make_unique<PreparedMap>(maps[m], options);
      from_cache[m] = kept.has_value();
    });
  };
  if (walls) {
    walls->clear();
    walls->resize(maps.size());
  }
  const auto release = [&](int m) {
    if (--pairs_left[m] != 0) return;
    if (cache && (!from_cache[m] || prepared[m]->targets_made() > 0)) {
      cache->StorePreparation(options_digest[0], digests[m], *prepared[m]);
    }
    if (walls) (*walls)[m].emplace(prepared[m]->TakeWalls());  // its own slot: no other thread's
    prepared[m].reset();
  };
  // Threads take the pairs whose maps no other thread is preparing first (pipeline/pair_order.hpp).
  std::vector<std::pair<int, int>> missing_pairs;
  for (const std::size_t k : missing) missing_pairs.push_back(jobs[k]);
  PairOrder order(std::move(missing_pairs), maps.size());
  // A pair that throws is reported as it would be in row order: the first such pair's error.
  std::vector<std::exception_ptr> errors(missing.size());
  std::atomic<int> done{cached_count};
  std::mutex progress_mutex;
  ParallelFor(missing.size(), threads, [&](std::size_t) {
    const std::size_t i = order.Take();
    const std::size_t k = missing[i];
    const auto [a, b] = jobs[k];
    try {
      prepare(a);
      order.Prepared(a);
      prepare(b);
      order.Prepared(b);
      outcomes[k] = ComputePair(prepared, a, b, options_of(k));
      release(a);
      release(b);
      if (cache) cache->StorePair(options_digest_of(k), digests[a], digests[b], outcomes[k]);
    } catch (...) {
      errors[i] = std::current_exception();
      return;
    }
    const int finished = ++done;
    if (progress) {
      const std::lock_guard<std::mutex> lock(progress_mutex);
      progress("pairs", finished, total);
    }
  });
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
  return outcomes;
}

}  // namespace fleetmerge
