// Re-runs that reuse earlier work: every pair's hypotheses (pipeline/all_pairs.hpp), kept in a
// cache folder (io/cache_folder.hpp) across runs. Fleets merge maps of one site day after day;
// with the cache a re-run computes only the pairs it has not seen: adding one map to N costs
// N pairs instead of (N + 1) N / 2.
//
// A pair's entry is keyed by the content hash (io/content_hash.hpp) of
//   - both maps' contents as the pair search sees them (MapDigest: size, resolution, origin and
//     every cell, after resampling to the job's resolution), in the pair's order (a before b),
//   - every PairOptions field that can change a pair's hypotheses (PairOptionsDigest; MergeFleet
//     copies min_overlap_cells in; a sampling seed only with random sampling), and
//   - fleetmerge's version (a new version may compute other hypotheses).
// What the entry holds is exactly what ComputeAllPairs returns for the pair (doubles as their
// bytes), so a merge with the cache is the merge without it, bit for bit.
//
// Beside the pairs, each map's preparation for the pair search (pipeline/prepared_map.hpp): a
// map new to the cache is paired with maps it has seen, whose Hough spectra and alignment
// targets (the preparation's dearest parts, KeptPreparation) are read back instead of made
// again. Its entry is keyed by the pair options' digest and the map's (a map is prepared the
// same way whatever it is paired with) and holds the values as their bytes: the pairs are the
// same bit for bit. docs/speed.md ("Re-runs") has what it saves.
#pragma once

#include <atomic>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string>

#include "core/occupancy_grid.hpp"
#include "io/cache_folder.hpp"
#include "io/content_hash.hpp"
#include "job/pair_options.hpp"
#include "pipeline/all_pairs.hpp"
#include "pipeline/prepared_map.hpp"

namespace fleetmerge {

// The digest of a map's geometry (size, resolution, origin) and cells.
ContentDigest MapDigest(const OccupancyGrid& grid);
// The digest of every PairOptions field and of `version`.
ContentDigest PairOptionsDigest(const PairOptions& options, const std::string& version);

// The hypotheses and scores of a pair (not its indices, nor the fleet's decisions on it), and
// back. ParsePairOutcome returns nullopt for bytes that are not such a payload.
std::string PairOutcomePayload(const PairOutcome& outcome);
std::optional<PairOutcome> ParsePairOutcome(const std::string& payload);

// What a cache keeps of a prepared map (KeptPreparation: its Hough spectrum and the targets made
// so far, by scale), and back. The values are their bytes, so the map prepared again from them
// gives its pairs the same hypotheses bit for bit. ParsePreparation returns nullopt for bytes
// that are not such a payload.
std::string PreparationPayload(const PreparedMap& prepared);
std::optional<KeptPreparation> ParsePreparation(const std::string& payload);

// Counts of one job's use of the cache.
struct PairCacheStats {
  int pairs_cached = 0;       // taken from the cache
  int pairs_computed = 0;     // computed (and stored)
  int maps_prepared = 0;      // maps prepared for the pairs computed (pipeline/prepared_map.hpp)
  int preparations_kept = 0;  // of those, prepared from what the cache kept of them
  int rejected = 0;           // entries found corrupt, truncated, foreign or of another version
  CacheEviction eviction;     // older entries evicted for the size bound, never this job's
  int write_failures = 0;     // entries that could not be stored (the job goes on without them)
  std::string first_write_error;
};

class PairCache {
 public:
  // Opens (creates, locks) the cache folder; see CacheFolder for the errors. `version` is
  // fleetmerge's (FLEETMERGE_VERSION_STRING; tests give others).
  PairCache(const std::filesystem::path& dir, const std::string& version,
            const CacheFolderOptions& options);

  // For a job with these pair options: the pair of maps with these digests (a before b), or
  // nullopt. The outcome's indices are left 0: the caller sets them.
  std::optional<PairOutcome> FindPair(const ContentDigest& options, const ContentDigest& a,
                                      const ContentDigest& b);
  // Stores the pair. A failure (a full disk) does not fail the job, whose result is already
  // computed: it is counted, and the first message kept, in stats().
  void StorePair(const ContentDigest& options, const ContentDigest& a, const ContentDigest& b,
                 const PairOutcome& outcome);
  // The same for a map's preparation (keyed by the pair options and the map's digest): what the
  // cache kept of it, or nullopt; and keeping it (what PreparationPayload holds), a failure
  // counted as StorePair's.
  std::optional<KeptPreparation> FindPreparation(const ContentDigest& options,
                                                 const ContentDigest& map);
  void StorePreparation(const ContentDigest& options, const ContentDigest& map,
                        const PreparedMap& prepared);
  // Evicts the least recently used entries beyond the size bound (CacheFolder::Evict) and
  // releases the folder for other jobs. MergeFleet closes its cache once the pairs are done, so
  // a job holds the cache only during its pair search. Nothing but stats() afterwards; a second
  // Close does nothing.
  void Close();

  const std::string& version() const { return version_; }
  const std::filesystem::path& dir() const { return folder_.dir(); }
  PairCacheStats stats() const;
  // Counted by ComputeAllPairs.
  void CountPairs(int cached, int computed, int maps_prepared);

 private:
  static ContentDigest PairKey(const ContentDigest& options, const ContentDigest& a,
                               const ContentDigest& b);
  static ContentDigest PreparationKey(const ContentDigest& options, const ContentDigest& map);
  // The entry under `key` parsed by `parse` (nullopt for bytes it refuses: then the entry is
  // discarded), or nullopt.
  template <typename Parse>
  auto Find(const ContentDigest& key, const Parse& parse) -> decltype(parse(""));
  // Writes the entry; a failure is counted (stats().write_failures), not thrown.
  void Store(const ContentDigest& key, const std::string& payload);
  std::string version_;
  CacheFolder folder_;
  bool closed_ = false;
  std::atomic<int> pairs_cached_{0}, pairs_computed_{0}, maps_prepared_{0}, write_failures_{0};
  std::atomic<int> preparations_kept_{0};
  CacheEviction eviction_;
  mutable std::mutex error_mutex_;
  std::string first_write_error_;
};

}  // namespace fleetmerge
