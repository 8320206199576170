#include "pipeline/pair_cache.hpp"

#include <cstring>

#include "core/error.hpp"
#include "io/raw_bytes.hpp"

namespace fleetmerge {
namespace {

// A named field of the options' key: the names keep two layouts that happen to have the same
// bytes apart.
template <typename T>
void AppendField(std::string& bytes, const char* name, const T& value) {
  bytes += name;
  bytes += '=';
  AppendRaw(bytes, value);
}

void AppendSampling(std::string& bytes, const char* name, const SamplingOptions& s) {
  bytes += name;
  AppendField(bytes, ".mode", static_cast<int>(s.mode));
  AppendField(bytes, ".fraction", s.fraction);
  AppendField(bytes, ".step", s.step);
  // The seed picks the points of random sampling only (core/point_sampling.cpp); with every
  // point (the default) or every k-th it changes nothing, so it does not split the cache.
  if (s.mode == SamplingMode::kRandomFraction) AppendField(bytes, ".seed", s.seed);
}

void AppendAlignment(std::string& bytes, const char* name, const LocalAlignmentOptions& a) {
  bytes += name;
  AppendField(bytes, ".max_points", a.max_points);
  AppendField(bytes, ".max_iterations", a.max_iterations);
  AppendField(bytes, ".loss_scale_cells", a.loss_scale_cells);
  AppendField(bytes, ".function_tolerance", a.function_tolerance);
}

constexpr std::uint32_t kPairPayloadTag = 0x70616972;  // "pair"

}  // namespace

ContentDigest MapDigest(const OccupancyGrid& grid) {
  const GridGeometry& g = grid.geometry();
  std::string header = "occupancy grid";
  AppendField(header, "width", g.width());
  AppendField(header, "height", g.height());
  AppendField(header, "resolution_m", g.resolution_m());
  AppendField(header, "origin_x_m", g.T_map_grid().x_m());
  AppendField(header, "origin_y_m", g.T_map_grid().y_m());
  AppendField(header, "origin_yaw_rad", g.T_map_grid().yaw_rad());
  ContentHash hash;
  hash.Update(header);
  const cv::Mat1b& cells = grid.cells();
  // The same digest for any split of the bytes: one update where the rows are contiguous.
  if (cells.isContinuous()) {
    hash.Update(cells.data, cells.total());
  } else {
    for (int row = 0; row < cells.rows; ++row) hash.Update(cells.ptr(row), cells.cols);
  }
  return hash.Finish();
}

ContentDigest PairOptionsDigest(const PairOptions& o, const std::string& version) {
  // Every field that can change a pair's hypotheses; a field added to PairOptions (or to the
  // options it holds) must be added here, or caches would return another setting's pairs.
  const HypothesisOptions& h = o.hypotheses;
  std::string bytes = "fleetmerge " + version + "\n";
  // Builds between releases share a version: a code change that alters any pair's hypotheses
  // (not only their speed) bumps this, so that a cache never mixes the two builds' pairs.
  // 2: the refinement solved with ceres::TinySolver (refine/local_alignment.cpp).
  // 3: the translation search's 5 x 5 blur by core/image_filters (float rounding differs from
  //    OpenCV's; refined poses move by ~1e-6 m).
  // 4: the key layout: sampling seeds only with random sampling.
  // 5: the translation search's pooling counts the larger map's extent up to twice the smaller's
  //    (core/translation_search.cpp, PoolingFor).
  // 6: a map more than twice the other's extent is searched from the other (pipeline/pair_merge).
  constexpr int kPairResultsRevision = 6;
  AppendField(bytes, "pair_results_revision", kPairResultsRevision);
  AppendField(bytes, "hough.n_theta", h.hough.n_theta);
  AppendField(bytes, "hough.rho_step_cells", h.hough.rho_step_cells);
  AppendSampling(bytes, "hough_sampling", h.hough_sampling);
  AppendSampling(bytes, "spectra_sampling", h.spectra_sampling);
  AppendField(bytes, "rotation_peaks", h.rotation_peaks);
  AppendField(bytes, "translation.method", static_cast<int>(h.translation.method));
  AppendField(bytes, "translation.candidates", h.translation.candidates);
  AppendField(bytes, "translation.coarse_max_side", h.translation.coarse_max_side);
  AppendField(bytes, "translation.free_penalty", h.translation.free_penalty);
  AppendField(bytes, "max_hypotheses", h.max_hypotheses);
  AppendField(bytes, "duplicate_yaw_rad", h.duplicate_yaw_rad);
  AppendField(bytes, "duplicate_translation_cells", h.duplicate_translation_cells);
  AppendField(bytes, "min_overlap_cells", h.min_overlap_cells);
  AppendField(bytes, "refine", o.refine);
  AppendField(bytes, "refine_truncation_cells", o.refine_truncation_cells);
  AppendField(bytes, "quick_basin_pixels", o.quick_basin_pixels);
  AppendField(bytes, "candidates_per_hypothesis", o.candidates_per_hypothesis);
  AppendAlignment(bytes, "quick_refine", o.quick_refine);
  AppendAlignment(bytes, "final_refine", o.final_refine);
  AppendField(bytes, "final_refine_count", o.final_refine_count);
  return ContentHashOf(bytes);
}

std::string PairOutcomePayload(const PairOutcome& outcome) {
  std::string bytes;
  AppendRaw(bytes, kPairPayloadTag);
  AppendRaw(bytes, static_cast<std::uint32_t>(outcome.hypotheses.size()));
  for (const PairHypothesis& h : outcome.hypotheses) {
    AppendRaw(bytes, h.T_a_b.x_m());
    AppendRaw(bytes, h.T_a_b.y_m());
    AppendRaw(bytes, h.T_a_b.yaw_rad());
    AppendRaw(bytes, h.omega);
    AppendRaw(bytes, h.overlap_cells);
    AppendRaw(bytes, h.wall_agreement);
    AppendRaw(bytes, h.evidence_nats);
  }
  AppendRaw(bytes, outcome.overlap_cells);
  AppendRaw(bytes, outcome.wall_agreement);
  AppendRaw(bytes, outcome.margin_nats);
  AppendRaw(bytes, static_cast<std::uint8_t>(outcome.ambiguous));
  return bytes;
}

std::optional<PairOutcome> ParsePairOutcome(const std::string& payload) {
  RawBytesReader reader(payload);
  std::uint32_t tag = 0, count = 0;
  if (!reader.Read(tag) || tag != kPairPayloadTag || !reader.Read(count)) return std::nullopt;
  // Each hypothesis takes 56 bytes: a count beyond the payload's size is garbage.
  if (count > payload.size() / 56) return std::nullopt;
  PairOutcome outcome;
  for (std::uint32_t k = 0; k < count; ++k) {
    double x = 0, y = 0, yaw = 0;
    PairHypothesis h;
    if (!reader.Read(x) || !reader.Read(y) || !reader.Read(yaw) || !reader.Read(h.omega) ||
        !reader.Read(h.overlap_cells) || !reader.Read(h.wall_agreement) ||
        !reader.Read(h.evidence_nats)) {
      return std::nullopt;
    }
    // Stored yaws are already wrapped into (-pi, pi], which Pose2's wrapping keeps bit for bit.
    h.T_a_b = Pose2(x, y, yaw);
    outcome.hypotheses.push_back(h);
  }
  std::uint8_t ambiguous = 0;
  if (!reader.Read(outcome.overlap_cells) || !reader.Read(outcome.wall_agreement) ||
      !reader.Read(outcome.margin_nats) || !reader.Read(ambiguous) || ambiguous > 1 ||
      !reader.AtEnd()) {
    return std::nullopt;
  }
  outcome.ambiguous = ambiguous == 1;
  return outcome;
}

PairCache::PairCache(const std::filesystem::path& dir, const std::string& version,
                     const CacheFolderOptions& options)
    : version_(version), folder_(dir, version, options) {}

ContentDigest PairCache::PairKey(const ContentDigest& options, const ContentDigest& a,
                                 const ContentDigest& b) {
  ContentHash hash;
  hash.Update("pair hypotheses\n");
  hash.Update(options.data(), options.size());
  hash.Update(a.data(), a.size());
  hash.Update(b.data(), b.size());
  return hash.Finish();
}

std::optional<PairOutcome> PairCache::FindPair(const ContentDigest& options, const ContentDigest& a,
                                               const ContentDigest& b) {
  const ContentDigest key = PairKey(options, a, b);
  const std::optional<std::string> payload = folder_.Read(key);
  if (!payload) return std::nullopt;
  std::optional<PairOutcome> outcome = ParsePairOutcome(*payload);
  if (!outcome) folder_.Discard(key);  // a sound entry of another layout: never trusted
  return outcome;
}

void PairCache::StorePair(const ContentDigest& options, const ContentDigest& a,
                          const ContentDigest& b, const PairOutcome& outcome) {
  try {
    folder_.Write(PairKey(options, a, b), PairOutcomePayload(outcome));
  } catch (const Error& e) {
    if (write_failures_++ == 0) {
      const std::lock_guard<std::mutex> lock(error_mutex_);
      first_write_error_ = e.what();
    }
  }
}

void PairCache::Close() {
  if (closed_) return;
  closed_ = true;
  eviction_ = folder_.Evict();
  folder_.Unlock();
}

void PairCache::CountPairs(int cached, int computed, int maps_prepared) {
  pairs_cached_ += cached;
  pairs_computed_ += computed;
  maps_prepared_ += maps_prepared;
}

PairCacheStats PairCache::stats() const {
  PairCacheStats stats;
  stats.pairs_cached = pairs_cached_;
  stats.pairs_computed = pairs_computed_;
  stats.maps_prepared = maps_prepared_;
  stats.rejected = folder_.rejected();
  stats.eviction = eviction_;
  stats.write_failures = write_failures_;
  const std::lock_guard<std::mutex> lock(error_mutex_);
  stats.first_write_error = first_write_error_;
  return stats;
}

}  // namespace fleetmerge
