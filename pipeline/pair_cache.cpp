#include "pipeline/pair_cache.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <vector>

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

bool IsFraction(double value) { return value >= 0.0 && value <= 1.0; }  // false for NaN

constexpr std::uint32_t kPairPayloadTag = 0x70616972;         // "pair"
constexpr std::uint32_t kPreparationPayloadTag = 0x70726570;  // "prep"
// A field's cells as 1 byte each: the index of its distance in a table of the field's distinct
// values (bits 0-6) and its flat bit (bit 7). The truncated field holds the truncation value and
// the distances of a disc's cell offsets (refine/wall_distance_field.cpp): ~20 values at the
// default truncation, so a fifth of the bytes of floats and flags. A field of more values (a
// large truncation) is kept as its floats and flags.
constexpr std::uint8_t kIndexedCells = 0, kRawCells = 1;
constexpr std::size_t kMaxTableValues = 128;
constexpr std::uint8_t kFlatBit = 0x80;

void AppendDistanceField(std::string& bytes, const WallDistanceField& field) {
  const cv::Mat1f& distances = field.distances();
  const cv::Mat1b& flat = field.flat();
  AppendRaw(bytes, static_cast<std::int32_t>(field.offset().x()));
  AppendRaw(bytes, static_cast<std::int32_t>(field.offset().y()));
  AppendRaw(bytes, static_cast<std::int32_t>(distances.rows));
  AppendRaw(bytes, static_cast<std::int32_t>(distances.cols));
  // One pass: the table of distinct values (by their bits, as they are read back) and each
  // cell's index into it, given up for floats and flags once the table would overflow.
  std::vector<std::uint32_t> table;
  std::string cells(static_cast<std::size_t>(distances.rows) * distances.cols, '\0');
  std::size_t at = 0;
  for (int r = 0; r < distances.rows && table.size() <= kMaxTableValues; ++r) {
    const float* row = distances.ptr<float>(r);
    const std::uint8_t* flat_row = flat.ptr<std::uint8_t>(r);
    std::uint32_t last = 0;
    std::size_t last_index = 0;
    bool have_last = false;
    for (int c = 0; c < distances.cols; ++c) {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &row[c], sizeof bits);
      if (!have_last || bits != last) {
        last = bits, have_last = true;
        last_index = std::find(table.begin(), table.end(), bits) - table.begin();
        if (last_index == table.size()) table.push_back(bits);
        if (table.size() > kMaxTableValues) break;
      }
      cells[at++] = static_cast<char>(last_index | (flat_row[c] != 0 ? kFlatBit : 0));
    }
  }
  if (table.size() > kMaxTableValues) {
    AppendRaw(bytes, kRawCells);
    for (int r = 0; r < distances.rows; ++r) {
      AppendRawArray(bytes, distances.ptr<float>(r), static_cast<std::size_t>(distances.cols));
    }
    for (int r = 0; r < flat.rows; ++r) {
      AppendRawArray(bytes, flat.ptr<std::uint8_t>(r), static_cast<std::size_t>(flat.cols));
    }
    return;
  }
  AppendRaw(bytes, kIndexedCells);
  AppendRaw(bytes, static_cast<std::uint32_t>(table.size()));
  AppendRawArray(bytes, table.data(), table.size());
  bytes += cells;
}

// A KeptTarget's field from AppendDistanceField's bytes; false for bytes that are not such a field.
bool ReadDistanceField(RawBytesReader& reader, KeptTarget& target) {
  std::int32_t x = 0, y = 0, rows = 0, cols = 0;
  std::uint8_t encoding = 0;
  if (!reader.Read(x) || !reader.Read(y) || !reader.Read(rows) || !reader.Read(cols) ||
      !reader.Read(encoding) || rows <= 0 || cols <= 0 ||
      static_cast<std::int64_t>(rows) * cols > (std::int64_t{1} << 31)) {
    return false;
  }
  const std::size_t cells = static_cast<std::size_t>(rows) * cols;
  // At least a byte a cell must follow: a forged size allocates nothing.
  if (reader.remaining() < cells) return false;
  target.offset_cells = Eigen::Array2i(x, y);
  target.distances.create(rows, cols);
  target.flat.create(rows, cols);
  if (encoding == kRawCells) {
    if (!reader.ReadArray(target.distances.ptr<float>(), cells) ||
        !reader.ReadArray(target.flat.ptr<std::uint8_t>(), cells)) {
      return false;
    }
    const float* distance = target.distances.ptr<float>();
    for (std::size_t k = 0; k < cells; ++k) {
      if (!(distance[k] >= 0.0f) || !std::isfinite(distance[k])) return false;
    }
    return true;
  }
  if (encoding != kIndexedCells) return false;
  std::uint32_t count = 0;
  if (!reader.Read(count) || count == 0 || count > kMaxTableValues) return false;
  std::vector<float> table(count);
  if (!reader.ReadArray(table.data(), count)) return false;
  for (const float d : table) {
    if (!(d >= 0.0f) || !std::isfinite(d)) return false;
  }
  const auto* bytes = reinterpret_cast<const std::uint8_t*>(reader.View(cells));
  if (bytes == nullptr) return false;
  // Each byte's distance, flag and validity looked up, without a branch per cell (decoding was
  // most of a kept preparation's cost).
  std::array<float, 256> distance_of{};
  std::array<std::uint8_t, 256> flat_of{}, invalid{};
  for (int byte = 0; byte < 256; ++byte) {
    const unsigned index = static_cast<unsigned>(byte) & ~unsigned{kFlatBit};
    invalid[byte] = index >= count;
    distance_of[byte] = index < count ? table[index] : 0.0f;
    flat_of[byte] = (byte & kFlatBit) != 0 ? 255 : 0;  // cv::compare's true
  }
  float* distance = target.distances.ptr<float>();
  std::uint8_t* flat = target.flat.ptr<std::uint8_t>();
  std::uint8_t any_invalid = 0;
  for (std::size_t k = 0; k < cells; ++k) {
    distance[k] = distance_of[bytes[k]];
    flat[k] = flat_of[bytes[k]];
    any_invalid |= invalid[bytes[k]];
  }
  return any_invalid == 0;
}

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
  // Builds between releases share a version: a code change that alters any pair's hypotheses or
  // any map's kept preparation (not only their speed) bumps this, so that a cache never mixes
  // the two builds' entries.
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
    // Values no pair search gives are not trusted: a finite pose whose yaw is already wrapped
    // into (-pi, pi] (which Pose2's wrapping keeps bit for bit, so the payload written back is
    // this one), omega and wall agreement fractions, a count of cells. The evidence may be NaN
    // (not measured) and the margin infinite (no runner-up).
    if (!std::isfinite(x) || !std::isfinite(y) || !(yaw > -M_PI && yaw <= M_PI) ||
        !IsFraction(h.omega) || h.overlap_cells < 0 || !IsFraction(h.wall_agreement)) {
      return std::nullopt;
    }
    h.T_a_b = Pose2(x, y, yaw);
    outcome.hypotheses.push_back(h);
  }
  std::uint8_t ambiguous = 0;
  if (!reader.Read(outcome.overlap_cells) || !reader.Read(outcome.wall_agreement) ||
      !reader.Read(outcome.margin_nats) || !reader.Read(ambiguous) || ambiguous > 1 ||
      !reader.AtEnd() || outcome.overlap_cells < 0 || !IsFraction(outcome.wall_agreement)) {
    return std::nullopt;
  }
  outcome.ambiguous = ambiguous == 1;
  return outcome;
}

std::string PreparationPayload(const PreparedMap& prepared) {
  std::string bytes;
  AppendRaw(bytes, kPreparationPayloadTag);
  const std::vector<double>& spectrum = prepared.features().hough_spectrum;
  AppendRaw(bytes, static_cast<std::uint32_t>(spectrum.size()));
  AppendRawArray(bytes, spectrum.data(), spectrum.size());
  const std::map<int, const AlignmentTarget*> targets = prepared.Targets();
  AppendRaw(bytes, static_cast<std::uint32_t>(targets.size()));
  for (const auto& [scale, target] : targets) {
    AppendRaw(bytes, static_cast<std::int32_t>(scale));
    AppendDistanceField(bytes, target->field);
    // Scale 1's wall cells are the map's own (MapFeatures::walls.centres), made with the map.
    const std::size_t walls = scale == 1 ? 0 : target->wall_points.size();
    AppendRaw(bytes, static_cast<std::uint32_t>(walls));
    for (std::size_t k = 0; k < walls; ++k) {
      // Cell centres i + 0.5, made as floats (refine/local_alignment.hpp): exact back and forth.
      AppendRaw(bytes, static_cast<float>(target->wall_points[k].x()));
      AppendRaw(bytes, static_cast<float>(target->wall_points[k].y()));
    }
  }
  return bytes;
}

std::optional<KeptPreparation> ParsePreparation(const std::string& payload) {
  RawBytesReader reader(payload);
  std::uint32_t tag = 0, count = 0;
  if (!reader.Read(tag) || tag != kPreparationPayloadTag || !reader.Read(count)) {
    return std::nullopt;
  }
  KeptPreparation kept;
  if (count > payload.size() / sizeof(double)) return std::nullopt;
  kept.hough_spectrum.resize(count);
  if (!reader.ReadArray(kept.hough_spectrum.data(), count)) return std::nullopt;
  for (const double v : kept.hough_spectrum) {
    if (!std::isfinite(v)) return std::nullopt;
  }
  std::uint32_t targets = 0;
  if (!reader.Read(targets) || targets > payload.size()) return std::nullopt;
  for (std::uint32_t t = 0; t < targets; ++t) {
    std::int32_t scale = 0;
    KeptTarget target;
    std::uint32_t walls = 0;
    if (!reader.Read(scale) || scale < 1 || kept.targets.count(scale) > 0 ||
        !ReadDistanceField(reader, target) || !reader.Read(walls) || (scale == 1 && walls != 0) ||
        walls > payload.size() / sizeof(Eigen::Vector2f)) {
      return std::nullopt;
    }
    target.wall_centres.resize(walls);
    for (Eigen::Vector2f& w : target.wall_centres) {
      if (!reader.Read(w.x()) || !reader.Read(w.y()) || !std::isfinite(w.x()) ||
          !std::isfinite(w.y())) {
        return std::nullopt;
      }
    }
    kept.targets.emplace(scale, std::move(target));
  }
  if (!reader.AtEnd()) return std::nullopt;
  return kept;
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

template <typename Parse>
auto PairCache::Find(const ContentDigest& key, const Parse& parse) -> decltype(parse("")) {
  const std::optional<std::string> payload = folder_.Read(key);
  if (!payload) return std::nullopt;
  auto parsed = parse(*payload);
  if (!parsed) folder_.Discard(key);  // a sound entry of another layout: never trusted
  return parsed;
}

void PairCache::Store(const ContentDigest& key, const std::string& payload) {
  try {
    folder_.Write(key, payload);
  } catch (const Error& e) {
    if (write_failures_++ == 0) {
      const std::lock_guard<std::mutex> lock(error_mutex_);
      first_write_error_ = e.what();
    }
  }
}

std::optional<PairOutcome> PairCache::FindPair(const ContentDigest& options, const ContentDigest& a,
                                               const ContentDigest& b) {
  return Find(PairKey(options, a, b), ParsePairOutcome);
}

void PairCache::StorePair(const ContentDigest& options, const ContentDigest& a,
                          const ContentDigest& b, const PairOutcome& outcome) {
  Store(PairKey(options, a, b), PairOutcomePayload(outcome));
}

ContentDigest PairCache::PreparationKey(const ContentDigest& options, const ContentDigest& map) {
  ContentHash hash;
  hash.Update("map preparation\n");
  hash.Update(options.data(), options.size());
  hash.Update(map.data(), map.size());
  return hash.Finish();
}

std::optional<KeptPreparation> PairCache::FindPreparation(const ContentDigest& options,
                                                          const ContentDigest& map) {
  std::optional<KeptPreparation> kept = Find(PreparationKey(options, map), ParsePreparation);
  if (kept) ++preparations_kept_;
  return kept;
}

void PairCache::StorePreparation(const ContentDigest& options, const ContentDigest& map,
                                 const PreparedMap& prepared) {
  Store(PreparationKey(options, map), PreparationPayload(prepared));
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
  stats.preparations_kept = preparations_kept_;
  stats.rejected = folder_.rejected();
  stats.eviction = eviction_;
  stats.write_failures = write_failures_;
  const std::lock_guard<std::mutex> lock(error_mutex_);
  stats.first_write_error = first_write_error_;
  return stats;
}

}  // namespace fleetmerge
