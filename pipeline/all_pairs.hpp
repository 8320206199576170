// Stage 1 of fleet merging: pairwise hypotheses for every pair of maps, on a thread pool. Each
// pair is computed independently and deterministically (sampling is seeded), and stored at its
// own index, so the result does not depend on the number of threads.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/wall_agreement.hpp"
#include "pipeline/pair_merge.hpp"

namespace fleetmerge {

// Called after each finished unit of work of a stage (from the worker threads, serialised).
using ProgressFn = std::function<void(const std::string& stage, int done, int total)>;

struct PairOutcome {
  int a = 0, b = 0;                        // map indices, a < b
  std::vector<PairHypothesis> hypotheses;  // pose of b's map frame in a's, best first
  std::int64_t overlap_cells = 0;          // cells known in both under the best hypothesis
  double wall_agreement = 0.0;             // core/wall_agreement.hpp, of the best hypothesis
  double margin_nats = 0.0;                // PairResult's: the best's lead in evidence
  bool ambiguous = false;                  // PairResult's: the runner-up is as good
  bool accepted = false;                   // an edge of the final pose graph
  int edge_hypothesis = -1;                // the hypothesis the edge uses (0 = the best)
  // Refused by the known start poses: its best passes the thresholds, but every hypothesis
  // contradicts the priors (pipeline/pose_priors.hpp; the hypotheses stay).
  bool refused_by_priors = false;
  // The hypotheses the priors dropped, with their rank in the search (1-based, as the note
  // names them) and how many sigmas they are from the priors; they stay in the report.
  struct Dropped {
    int search_rank = 0;
    double sigmas = 0.0;
    PairHypothesis hypothesis;
  };
  std::vector<Dropped> dropped_by_priors;
  std::string note;  // why it was rejected or replaced
  double best_omega() const { return hypotheses.empty() ? 0.0 : hypotheses.front().omega; }
};

class PairCache;  // pipeline/pair_cache.hpp

// The pairs with a fixed map and how they are searched (FleetOptions::fixed_map_free_penalty).
struct FixedMapPairs {
  std::vector<char> fixed;  // one per map: 1 for a fixed map
  PairOptions options;      // for a pair with at least one fixed map
};

// All pairs (a < b, in row order) of maps that share one resolution. threads <= 0: all cores.
// A pair with a map `fixed_maps` flags is searched with its options, the others with `options`;
// the two may differ only in what a pair's search does with the maps, not in how each map is
// prepared (pipeline/prepared_map.hpp). With a cache, pairs found there are taken as they are,
// the others computed and stored, and only the maps of computed pairs are prepared: the same
// outcomes as without it. With `walls`, each prepared map's walls (MapWalls, for the judging of
// the solved pairs that follows, pipeline/corroboration.hpp) are handed on there once its last
// pair is done, instead of being made again from its cells; the maps not prepared (every pair
// from the cache) are left nullopt.
std::vector<PairOutcome> ComputeAllPairs(const std::vector<OccupancyGrid>& maps,
                                         const PairOptions& options, int threads,
                                         const ProgressFn& progress = {},
                                         PairCache* cache = nullptr,
                                         const FixedMapPairs* fixed_maps = nullptr,
                                         std::vector<std::optional<MapWalls>>* walls = nullptr);

}  // namespace fleetmerge
