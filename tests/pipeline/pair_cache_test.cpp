// The pair cache (pipeline/pair_cache.hpp) on robots cut from a real building: a merge with the
// cache is the merge without it (poses, pairs, merged cells, bit for bit), a re-run computes no
// pair, one map more computes only its pairs, and bad entries (garbage, truncated, foreign,
// another version's) are rebuilt, never trusted.
#include "pipeline/pair_cache.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/map_io.hpp"
#include "pipeline/fleet_merge.hpp"
#include "pipeline/prepared_map.hpp"
#include "sim/ground_truth_pair.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;

constexpr const char* kVersion = "test-version";

std::vector<const OccupancyGrid*> FirstMaps(const GroundTruthFleet& fleet, std::size_t count) {
  std::vector<const OccupancyGrid*> out;
  for (std::size_t m = 0; m < count; ++m) out.push_back(&fleet.maps[m]);
  return out;
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void ExpectSamePose(const Pose2& a, const Pose2& b, const std::string& what) {
  EXPECT_TRUE(SameBits(a.x_m(), b.x_m())) << what;
  EXPECT_TRUE(SameBits(a.y_m(), b.y_m())) << what;
  EXPECT_TRUE(SameBits(a.yaw_rad(), b.yaw_rad())) << what;
}

// Everything a merge reports, compared bit for bit.
void ExpectSameMerge(const FleetResult& expected, const FleetResult& actual) {
  ASSERT_EQ(expected.pairs.size(), actual.pairs.size());
  for (std::size_t k = 0; k < expected.pairs.size(); ++k) {
    const PairOutcome& e = expected.pairs[k];
    const PairOutcome& a = actual.pairs[k];
    const std::string pair = std::to_string(e.a) + "-" + std::to_string(e.b);
    EXPECT_EQ(a.a, e.a);
    EXPECT_EQ(a.b, e.b);
    ASSERT_EQ(a.hypotheses.size(), e.hypotheses.size()) << pair;
    for (std::size_t h = 0; h < e.hypotheses.size(); ++h) {
      const std::string what = pair + " hypothesis " + std::to_string(h);
      ExpectSamePose(e.hypotheses[h].T_a_b, a.hypotheses[h].T_a_b, what);
      EXPECT_TRUE(SameBits(e.hypotheses[h].omega, a.hypotheses[h].omega)) << what;
      EXPECT_EQ(e.hypotheses[h].overlap_cells, a.hypotheses[h].overlap_cells) << what;
      EXPECT_TRUE(SameBits(e.hypotheses[h].wall_agreement, a.hypotheses[h].wall_agreement));
      EXPECT_TRUE(SameBits(e.hypotheses[h].evidence_nats, a.hypotheses[h].evidence_nats));
    }
    EXPECT_EQ(a.overlap_cells, e.overlap_cells) << pair;
    EXPECT_TRUE(SameBits(a.wall_agreement, e.wall_agreement)) << pair;
    EXPECT_TRUE(SameBits(a.margin_nats, e.margin_nats)) << pair;
    EXPECT_EQ(a.ambiguous, e.ambiguous) << pair;
    EXPECT_EQ(a.accepted, e.accepted) << pair;
    EXPECT_EQ(a.edge_hypothesis, e.edge_hypothesis) << pair;
    EXPECT_EQ(a.note, e.note) << pair;
  }
  EXPECT_EQ(actual.component_of, expected.component_of);
  ASSERT_EQ(actual.T_component_map.size(), expected.T_component_map.size());
  for (std::size_t m = 0; m < expected.T_component_map.size(); ++m) {
    ExpectSamePose(expected.T_component_map[m], actual.T_component_map[m],
                   "map " + std::to_string(m));
  }
  ASSERT_EQ(actual.components.size(), expected.components.size());
  for (std::size_t c = 0; c < expected.components.size(); ++c) {
    const auto& e = expected.components[c].merged;
    const auto& a = actual.components[c].merged;
    ASSERT_EQ(a.has_value(), e.has_value()) << "component " << c;
    if (!e) continue;
    ASSERT_EQ(a->width(), e->width());
    ASSERT_EQ(a->height(), e->height());
    ExpectSamePose(e->geometry().T_map_grid(), a->geometry().T_map_grid(), "merged origin");
    EXPECT_EQ(cv::countNonZero(a->cells() != e->cells()), 0) << "component " << c;
  }
}

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A sound entry file's key and payload (io/cache_folder.hpp's layout).
struct EntryParts {
  ContentDigest key{};
  std::string payload;
};
EntryParts PartsOf(const fs::path& entry) {
  const std::string bytes = ReadBytes(entry);
  std::size_t at = 16 + 4 + 4;  // magic, format, byte order
  std::uint32_t version_size = 0;
  std::memcpy(&version_size, bytes.data() + at, 4);
  at += 4 + version_size;
  EntryParts parts;
  std::memcpy(parts.key.data(), bytes.data() + at, 16);
  at += 16;
  std::uint64_t payload_size = 0;
  std::memcpy(&payload_size, bytes.data() + at, 8);
  parts.payload = bytes.substr(at + 8, payload_size);
  return parts;
}

// The sound entries in `dir` whose payload starts with `tag` ("pair": pairs, "prep": maps'
// preparations).
std::vector<fs::path> Entries(const fs::path& dir, const char* tag = "pair") {
  std::uint32_t want = 0;
  for (int k = 0; k < 4; ++k) want = (want << 8) | static_cast<std::uint8_t>(tag[k]);
  std::vector<fs::path> entries;
  for (const auto& f : fs::directory_iterator(dir)) {
    if (f.path().extension() != ".entry") continue;
    const std::string payload = PartsOf(f.path()).payload;
    std::uint32_t got = 0;
    if (payload.size() >= 4) std::memcpy(&got, payload.data(), 4);
    if (got == want) entries.push_back(f.path());
  }
  std::sort(entries.begin(), entries.end());
  return entries;
}
std::vector<fs::path> PreparationEntries(const fs::path& dir) { return Entries(dir, "prep"); }

void WriteBytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

class PairCacheTest : public ::testing::Test {
 protected:
  void SetUp() override {
    FLEETMERGE_REQUIRE_SHARED_MAPS();
    std::mt19937 rng(5);
    fleet_ = CutFleet(LoadMap(*testing::SharedMapsDir() / "intel_lab.yaml").grid, 5, rng);
    dir_ = testing::MakeTempDir("pair_cache") / "cache";
    options_.threads = 2;
  }
  // A merge of the first `count` robots with a fresh opening of the cache (as a new run would),
  // returning its counts in `stats`.
  FleetResult Cached(std::size_t count, PairCacheStats& stats,
                     const std::string& version = kVersion) const {
    PairCache cache(dir_, version, {});
    FleetResult result = MergeFleet(FirstMaps(fleet_, count), 0, options_, {}, &cache);
    stats = cache.stats();
    return result;
  }
  FleetResult Uncached(std::size_t count) const {
    return MergeFleet(FirstMaps(fleet_, count), 0, options_);
  }
  // As Cached, with the first map fixed at the identity.
  FleetResult CachedWithFixedFirst(std::size_t count, PairCacheStats& stats) const {
    PairCache cache(dir_, kVersion, {});
    FixedPoses fixed(count);
    fixed[0] = Pose2();
    FleetResult result = MergeFleet(FirstMaps(fleet_, count), 0, fixed, options_, {}, &cache);
    stats = cache.stats();
    return result;
  }
  GroundTruthFleet fleet_;
  fs::path dir_;
  FleetOptions options_;
};

TEST_F(PairCacheTest, ARerunTakesEveryPairFromTheCacheWithTheSameResult) {
  const FleetResult uncached = Uncached(4);
  PairCacheStats cold, warm;
  const FleetResult first = Cached(4, cold);
  EXPECT_EQ(cold.pairs_cached, 0);
  EXPECT_EQ(cold.pairs_computed, 6);
  EXPECT_EQ(cold.maps_prepared, 4);
  EXPECT_EQ(cold.preparations_kept, 0);
  EXPECT_EQ(Entries(dir_).size(), 6u);
  EXPECT_EQ(PreparationEntries(dir_).size(), 4u);  // each map's, kept after its last pair
  const FleetResult second = Cached(4, warm);
  EXPECT_EQ(warm.pairs_cached, 6);
  EXPECT_EQ(warm.pairs_computed, 0);
  EXPECT_EQ(warm.maps_prepared, 0);  // no pair to compute: no map prepared
  EXPECT_EQ(warm.rejected, 0);
  // The merge must have merged something for the comparison to mean anything.
  int merged = 0;
  for (const auto& c : uncached.components) merged += c.maps.size() >= 2;
  EXPECT_GE(merged, 1);
  ExpectSameMerge(uncached, first);
  ExpectSameMerge(uncached, second);
}

TEST_F(PairCacheTest, OneMapMoreComputesOnlyItsPairs) {
  PairCacheStats four, five;
  Cached(4, four);
  const FleetResult cached = Cached(5, five);
  EXPECT_EQ(five.pairs_cached, 6);
  EXPECT_EQ(five.pairs_computed, 4);
  EXPECT_EQ(five.maps_prepared, 5);      // each new pair has an old map in it
  EXPECT_EQ(five.preparations_kept, 4);  // the old maps' from the cache, the new one's made
  EXPECT_EQ(Entries(dir_).size(), 10u);
  EXPECT_EQ(PreparationEntries(dir_).size(), 5u);
  ExpectSameMerge(Uncached(5), cached);
}

// Pairs computed from kept preparations are the pairs computed from scratch: every pair entry
// removed, every map's preparation is taken from the cache and every pair computed again.
TEST_F(PairCacheTest, PairsFromKeptPreparationsAreThePairsWithout) {
  PairCacheStats first, second;
  Cached(4, first);
  for (const fs::path& entry : Entries(dir_)) fs::remove(entry);
  const FleetResult result = Cached(4, second);
  EXPECT_EQ(second.pairs_computed, 6);
  EXPECT_EQ(second.maps_prepared, 4);
  EXPECT_EQ(second.preparations_kept, 4);
  EXPECT_EQ(second.rejected, 0);
  ExpectSameMerge(Uncached(4), result);
}

// A bad preparation entry is not trusted either: garbage, truncated, corrupt (rejected by the
// cache folder's checks), a sound entry holding a pair's payload, and one whose payload is cut
// (rejected by ParsePreparation); each map is prepared again, with the same pairs.
TEST_F(PairCacheTest, BadPreparationEntriesAreRebuilt) {
  PairCacheStats first;
  Cached(4, first);
  const std::vector<fs::path> pairs = Entries(dir_);
  const std::vector<fs::path> preparations = PreparationEntries(dir_);
  ASSERT_EQ(preparations.size(), 4u);
  const EntryParts pair = PartsOf(pairs[0]);
  for (const fs::path& entry : pairs) fs::remove(entry);
  WriteBytes(preparations[0], "garbage");
  std::string bytes = ReadBytes(preparations[1]);
  WriteBytes(preparations[1], bytes.substr(0, bytes.size() / 2));
  const EntryParts cut = PartsOf(preparations[2]);
  WriteBytes(preparations[2],
             CacheEntryBytes(cut.key, kVersion, cut.payload.substr(0, cut.payload.size() - 1)));
  const EntryParts other = PartsOf(preparations[3]);
  WriteBytes(preparations[3], CacheEntryBytes(other.key, kVersion, pair.payload));
  PairCacheStats rebuilt;
  const FleetResult result = Cached(4, rebuilt);
  EXPECT_EQ(rebuilt.rejected, 4);
  EXPECT_EQ(rebuilt.preparations_kept, 0);
  EXPECT_EQ(rebuilt.pairs_computed, 6);
  ExpectSameMerge(Uncached(4), result);
  EXPECT_EQ(PreparationEntries(dir_).size(), 4u);  // written anew
}

TEST_F(PairCacheTest, GarbageTruncatedAndCorruptEntriesAreRebuilt) {
  PairCacheStats stats;
  Cached(4, stats);
  const std::vector<fs::path> entries = Entries(dir_);
  ASSERT_EQ(entries.size(), 6u);
  // Six ways an entry goes bad: garbage text, empty, truncated, one payload byte flipped, the
  // checksum flipped, and one byte more.
  const std::string good = ReadBytes(entries[0]);
  WriteBytes(entries[0], "this is not a cache entry\n");
  WriteBytes(entries[1], "");
  std::string bytes = ReadBytes(entries[2]);
  WriteBytes(entries[2], bytes.substr(0, bytes.size() / 2));
  bytes = ReadBytes(entries[3]);
  bytes[bytes.size() - 40] ^= 0x01;
  WriteBytes(entries[3], bytes);
  bytes = ReadBytes(entries[4]);
  bytes.back() ^= 0x80;
  WriteBytes(entries[4], bytes);
  WriteBytes(entries[5], ReadBytes(entries[5]) + "x");
  PairCacheStats rebuilt;
  const FleetResult result = Cached(4, rebuilt);
  EXPECT_EQ(rebuilt.rejected, 6);
  EXPECT_EQ(rebuilt.pairs_computed, 6);
  EXPECT_EQ(rebuilt.pairs_cached, 0);
  ExpectSameMerge(Uncached(4), result);
  EXPECT_EQ(ReadBytes(entries[0]), good);  // rewritten whole
  PairCacheStats again;
  Cached(4, again);
  EXPECT_EQ(again.pairs_cached, 6);
  EXPECT_EQ(again.rejected, 0);
}

TEST_F(PairCacheTest, AnEntryUnderAnotherPairsNameIsNotTrusted) {
  PairCacheStats stats;
  Cached(4, stats);
  const std::vector<fs::path> entries = Entries(dir_);
  ASSERT_EQ(entries.size(), 6u);
  // Every entry gets its neighbour's (sound) bytes: all six are foreign to their names.
  std::vector<std::string> bytes;
  for (const auto& e : entries) bytes.push_back(ReadBytes(e));
  for (std::size_t k = 0; k < entries.size(); ++k) WriteBytes(entries[k], bytes[(k + 1) % 6]);
  PairCacheStats foreign;
  const FleetResult result = Cached(4, foreign);
  EXPECT_EQ(foreign.rejected, 6);
  EXPECT_EQ(foreign.pairs_computed, 6);
  ExpectSameMerge(Uncached(4), result);
}

TEST_F(PairCacheTest, AnotherVersionsCacheIsIgnored) {
  PairCacheStats old_version, new_version;
  Cached(4, old_version, "0.0.1-old");
  EXPECT_EQ(old_version.pairs_computed, 6);
  Cached(4, new_version, kVersion);
  EXPECT_EQ(new_version.pairs_cached, 0);
  EXPECT_EQ(new_version.pairs_computed, 6);
  // Both versions' entries are kept side by side (each is found by its own version only).
  const std::vector<fs::path> before = Entries(dir_);
  ASSERT_EQ(before.size(), 12u);
  PairCacheStats stats;
  Cached(4, stats, kVersion);
  EXPECT_EQ(stats.pairs_cached, 6);
}

TEST_F(PairCacheTest, PairOptionsThatChangeHypothesesMissTheCache) {
  PairCacheStats first, other_overlap, other_theta;
  Cached(3, first);
  options_.min_overlap_cells += 1;  // MergeFleet copies it into the pair options
  Cached(3, other_overlap);
  EXPECT_EQ(other_overlap.pairs_cached, 0);
  EXPECT_EQ(other_overlap.pairs_computed, 3);
  options_.pair.hypotheses.hough.n_theta = 360;
  Cached(3, other_theta);
  EXPECT_EQ(other_theta.pairs_cached, 0);
  // Options that only change the fleet's decisions (not a pair's hypotheses) keep the pairs.
  options_.omega_threshold = 0.95;
  options_.threads = 1;
  PairCacheStats decisions;
  Cached(3, decisions);
  EXPECT_EQ(decisions.pairs_cached, 3);
}

// A pair with a fixed map is searched with its own free penalty
// (FleetOptions::fixed_map_free_penalty), so its entry is not another job's pair of the same
// maps without the map fixed, and the other way round.
TEST_F(PairCacheTest, PairsWithAFixedMapAreKeptApart) {
  PairCacheStats fixed_first, not_fixed, fixed_again;
  const FleetResult cached = CachedWithFixedFirst(3, fixed_first);
  EXPECT_EQ(fixed_first.pairs_computed, 3);
  Cached(3, not_fixed);
  EXPECT_EQ(not_fixed.pairs_cached, 1);  // robot2-robot3: neither map fixed
  EXPECT_EQ(not_fixed.pairs_computed, 2);
  CachedWithFixedFirst(3, fixed_again);
  EXPECT_EQ(fixed_again.pairs_cached, 3);
  FixedPoses fixed(3);
  fixed[0] = Pose2();
  ExpectSameMerge(MergeFleet(FirstMaps(fleet_, 3), 0, fixed, options_), cached);
}

// The seed picks the points of random sampling and nothing else: with every point (the default)
// or every k-th, jobs of different seeds (a job file's and the command line's) share entries.
TEST(PairOptionsDigest, TheSeedCountsOnlyForRandomSampling) {
  for (SamplingOptions HypothesisOptions::*sampling :
       {&HypothesisOptions::hough_sampling, &HypothesisOptions::spectra_sampling}) {
    const auto digest = [&](SamplingMode mode, std::uint32_t seed) {
      PairOptions o;
      (o.hypotheses.*sampling).mode = mode;
      (o.hypotheses.*sampling).fraction = 0.5;
      (o.hypotheses.*sampling).step = 2;
      (o.hypotheses.*sampling).seed = seed;
      return PairOptionsDigest(o, kVersion);
    };
    EXPECT_EQ(digest(SamplingMode::kAll, 0), digest(SamplingMode::kAll, 7));
    EXPECT_EQ(digest(SamplingMode::kEveryKth, 0), digest(SamplingMode::kEveryKth, 7));
    EXPECT_NE(digest(SamplingMode::kRandomFraction, 0), digest(SamplingMode::kRandomFraction, 7));
  }
}

TEST(PairOptionsDigest, ChangesWithEveryRefinementSetting) {
  const PairOptions defaults;
  const ContentDigest digest = PairOptionsDigest(defaults, kVersion);
  for (LocalAlignmentOptions PairOptions::*stage :
       {&PairOptions::quick_refine, &PairOptions::final_refine}) {
    const auto changed = [&](const auto& change) {
      PairOptions o = defaults;
      change(o.*stage);
      return PairOptionsDigest(o, kVersion) != digest;
    };
    EXPECT_TRUE(changed([](LocalAlignmentOptions& a) { a.max_points += 1; }));
    EXPECT_TRUE(changed([](LocalAlignmentOptions& a) { a.max_iterations += 1; }));
    EXPECT_TRUE(changed([](LocalAlignmentOptions& a) { a.loss_scale_cells *= 2.0; }));
    EXPECT_TRUE(changed([](LocalAlignmentOptions& a) { a.function_tolerance *= 0.1; }));
  }
}

// A bound below one job's pairs keeps them all (the job's re-run takes them from the cache) and
// reports it, instead of evicting the entries the job just wrote.
TEST_F(PairCacheTest, ABoundBelowTheJobsPairsKeepsThemAll) {
  CacheFolderOptions tiny;
  tiny.max_bytes = 1;
  PairCacheStats first, again;
  for (PairCacheStats* stats : {&first, &again}) {
    PairCache cache(dir_, kVersion, tiny);
    MergeFleet(FirstMaps(fleet_, 3), 0, options_, {}, &cache);
    *stats = cache.stats();
  }
  EXPECT_EQ(first.pairs_computed, 3);
  EXPECT_EQ(first.eviction.removed, 0);
  EXPECT_EQ(first.eviction.in_use, 6);  // 3 pairs and the 3 maps' preparations
  EXPECT_TRUE(first.eviction.over_bound);
  EXPECT_EQ(again.pairs_cached, 3);
  EXPECT_EQ(again.pairs_computed, 0);
  EXPECT_TRUE(again.eviction.over_bound);
}

TEST_F(PairCacheTest, TheCacheIsReleasedOnceThePairsAreDone) {
  PairCache cache(dir_, kVersion, {});
  const FleetResult result = MergeFleet(FirstMaps(fleet_, 3), 0, options_, {}, &cache);
  // Still alive, but closed: another job gets the folder at once (no wait), with its pairs.
  PairCache other(dir_, kVersion, {});
  EXPECT_TRUE(other.FindPair(PairOptionsDigest(
                                 [&] {
                                   PairOptions o = options_.pair;
                                   o.hypotheses.min_overlap_cells = options_.min_overlap_cells;
                                   return o;
                                 }(),
                                 kVersion),
                             MapDigest(result.maps[0]), MapDigest(result.maps[1])));
  EXPECT_THROW(cache.FindPair({}, {}, {}), Error);
}

TEST(MapDigest, ChangesWithCellsResolutionAndOrigin) {
  OccupancyGrid grid(GridGeometry(0.05, {40, 30}, Pose2(1.0, 2.0, 0.0)), CellState::kFree);
  const ContentDigest digest = MapDigest(grid);
  EXPECT_EQ(MapDigest(grid), digest);
  OccupancyGrid cell = grid;
  cell.mutable_cells()(3, 7) = static_cast<std::uint8_t>(CellState::kOccupied);
  EXPECT_NE(MapDigest(cell), digest);
  EXPECT_NE(
      MapDigest(OccupancyGrid(GridGeometry(0.1, {40, 30}, Pose2(1.0, 2.0, 0.0)), CellState::kFree)),
      digest);
  EXPECT_NE(MapDigest(OccupancyGrid(GridGeometry(0.05, {40, 30}, Pose2(1.0, 2.05, 0.0)),
                                    CellState::kFree)),
            digest);
  // The same cells transposed into another shape.
  EXPECT_NE(MapDigest(OccupancyGrid(GridGeometry(0.05, {30, 40}, Pose2(1.0, 2.0, 0.0)),
                                    CellState::kFree)),
            digest);
}

TEST(PairOutcomePayload, RoundTripsBitForBitAndRefusesOtherBytes) {
  PairOutcome outcome;
  outcome.hypotheses.push_back({Pose2(1.25, -3.5, M_PI), 0.97, 12345, 0.91, 17.5});
  outcome.hypotheses.push_back({Pose2(0.1, 0.2, -0.3), 0.5, 99, 0.25, -2.0});
  outcome.overlap_cells = 12345;
  outcome.wall_agreement = 0.91;
  outcome.margin_nats = std::numeric_limits<double>::infinity();
  outcome.ambiguous = true;
  const std::string payload = PairOutcomePayload(outcome);
  const std::optional<PairOutcome> parsed = ParsePairOutcome(payload);
  ASSERT_TRUE(parsed);
  ASSERT_EQ(parsed->hypotheses.size(), 2u);
  ExpectSamePose(parsed->hypotheses[0].T_a_b, outcome.hypotheses[0].T_a_b, "first");
  EXPECT_EQ(parsed->hypotheses[1].overlap_cells, 99);
  EXPECT_EQ(parsed->margin_nats, outcome.margin_nats);
  EXPECT_TRUE(parsed->ambiguous);
  EXPECT_EQ(PairOutcomePayload(*parsed), payload);
  EXPECT_FALSE(ParsePairOutcome(payload.substr(0, payload.size() - 1)));
  EXPECT_FALSE(ParsePairOutcome(payload + "x"));
  EXPECT_FALSE(ParsePairOutcome(""));
  std::string huge_count = payload;
  huge_count[4] = '\xff';
  EXPECT_FALSE(ParsePairOutcome(huge_count));
}

// An entry sealed with a valid checksum (a stray writer, a bug of another build of this
// version) still holds values the search gives, or it is refused: no NaN or infinite pose, no yaw
// outside (-pi, pi] (Pose2 would wrap it, and the pair would differ from the entry), no omega or
// wall agreement outside [0, 1], no negative cell count. The search's own NaN evidence (not
// measured) and infinite margin (no runner-up) are kept.
TEST(PairOutcomePayload, RefusesValuesNoSearchGives) {
  PairOutcome outcome;
  outcome.hypotheses.push_back({Pose2(1.25, -3.5, 0.5), 0.97, 12345, 0.91, 17.5});
  outcome.hypotheses.push_back(
      {Pose2(0.1, 0.2, -0.3), 0.5, 99, 0.25, std::numeric_limits<double>::quiet_NaN()});
  outcome.overlap_cells = 12345;
  outcome.wall_agreement = 0.91;
  outcome.margin_nats = std::numeric_limits<double>::infinity();
  const std::string payload = PairOutcomePayload(outcome);
  ASSERT_TRUE(ParsePairOutcome(payload));
  EXPECT_EQ(PairOutcomePayload(*ParsePairOutcome(payload)), payload);
  // The payload's doubles after the tag and the count: hypothesis k's x, y, yaw, omega, overlap
  // (an int64), walls, evidence at 8 + 56 k + 8 i; then the pair's overlap and walls.
  const auto with = [&](std::size_t at, auto value) {
    std::string bytes = payload;
    std::memcpy(&bytes[at], &value, sizeof value);
    return bytes;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const std::size_t pair_fields = 8 + 56 * 2;
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"NaN x", with(8, nan)},
      {"infinite y", with(8 + 8, -inf)},
      {"yaw beyond pi", with(8 + 16, 4.0)},
      {"yaw -pi (written as +pi)", with(8 + 16, -M_PI)},
      {"omega above 1", with(8 + 24, 1.5)},
      {"NaN omega", with(8 + 56 + 24, nan)},
      {"negative overlap", with(8 + 32, std::int64_t{-1})},
      {"negative wall agreement", with(8 + 56 + 40, -0.25)},
      {"negative pair overlap", with(pair_fields, std::int64_t{-5})},
      {"pair walls above 1", with(pair_fields + 8, 2.0)},
  };
  for (const auto& [what, bytes] : refused) {
    EXPECT_FALSE(ParsePairOutcome(bytes)) << what;
  }
  EXPECT_TRUE(ParsePairOutcome(with(8 + 16, M_PI))) << "yaw pi";
}

// Two preparations of one map hold the same values, bit for bit.
void ExpectSamePreparation(const PreparedMap& expected, const PreparedMap& actual) {
  const std::vector<double>& e = expected.features().hough_spectrum;
  const std::vector<double>& a = actual.features().hough_spectrum;
  ASSERT_EQ(a.size(), e.size());
  EXPECT_FALSE(e.empty());
  EXPECT_EQ(std::memcmp(a.data(), e.data(), e.size() * sizeof(double)), 0);
  const auto expected_targets = expected.Targets();
  const auto actual_targets = actual.Targets();
  ASSERT_EQ(actual_targets.size(), expected_targets.size());
  for (const auto& [scale, target] : expected_targets) {
    ASSERT_EQ(actual_targets.count(scale), 1u) << "scale " << scale;
    const AlignmentTarget& other = *actual_targets.at(scale);
    const WallDistanceField& f = target->field;
    const WallDistanceField& g = other.field;
    EXPECT_EQ(g.truncation_cells(), f.truncation_cells());
    EXPECT_TRUE((g.offset() == f.offset()).all()) << "scale " << scale;
    ASSERT_EQ(g.distances().size(), f.distances().size()) << "scale " << scale;
    for (int r = 0; r < f.distances().rows; ++r) {
      ASSERT_EQ(std::memcmp(g.distances().ptr<float>(r), f.distances().ptr<float>(r),
                            f.distances().cols * sizeof(float)),
                0)
          << "scale " << scale << " row " << r;
    }
    EXPECT_EQ(cv::countNonZero(g.flat() != f.flat()), 0) << "scale " << scale;
    EXPECT_EQ(other.wall_points, target->wall_points) << "scale " << scale;
  }
}

// A prepared map's kept parts give the same preparation back, with the field's cells indexed
// (the default truncation: a few distinct distances) and as floats (a truncation of 30 cells:
// more distinct distances than the index holds); other bytes are refused.
TEST_F(PairCacheTest, PreparationPayloadRoundTripsBitForBitAndRefusesOtherBytes) {
  for (const double truncation_cells : {PairOptions{}.refine_truncation_cells, 30.0}) {
    PairOptions options;
    options.refine_truncation_cells = truncation_cells;
    const PreparedMap prepared(fleet_.maps[1], options);
    for (const int scale : {1, 2, 4}) prepared.Target(scale);
    const std::string payload = PreparationPayload(prepared);
    std::optional<KeptPreparation> kept = ParsePreparation(payload);
    ASSERT_TRUE(kept) << truncation_cells;
    EXPECT_EQ(kept->targets.size(), 3u);
    const PreparedMap again(fleet_.maps[1], options, std::move(*kept));
    EXPECT_EQ(again.targets_made(), 0);
    ExpectSamePreparation(prepared, again);
    EXPECT_EQ(PreparationPayload(again), payload);
    // Cut anywhere, one byte more, another payload: refused.
    for (const std::size_t size : {std::size_t{0}, std::size_t{3}, payload.size() / 3,
                                   payload.size() / 2, payload.size() - 1}) {
      EXPECT_FALSE(ParsePreparation(payload.substr(0, size))) << size;
    }
    EXPECT_FALSE(ParsePreparation(payload + "x"));
    EXPECT_FALSE(ParsePreparation(PairOutcomePayload(PairOutcome{})));
    EXPECT_FALSE(ParsePairOutcome(payload));
  }
  // A kept spectrum is taken as it is (not made again), unless its length is not this map's
  // with these options.
  {
    const PreparedMap original(fleet_.maps[1], PairOptions{});
    KeptPreparation kept;
    kept.hough_spectrum = original.features().hough_spectrum;
    kept.hough_spectrum[0] += 1.0;
    const std::vector<double> taken = kept.hough_spectrum;
    EXPECT_EQ(PreparedMap(fleet_.maps[1], PairOptions{}, kept).features().hough_spectrum, taken);
    kept.hough_spectrum.pop_back();
    EXPECT_EQ(PreparedMap(fleet_.maps[1], PairOptions{}, kept).features().hough_spectrum,
              original.features().hough_spectrum);
  }
  // Indexed cells: a cell whose index is beyond the field's table of distances is refused.
  const PreparedMap prepared(fleet_.maps[1], PairOptions{});
  prepared.Target(1);
  std::string payload = PreparationPayload(prepared);
  // The first cell's byte: after the tag, the spectrum's size and values, the target count, the
  // scale, the offset's x and y, rows, cols, the encoding, the table's size and values.
  std::size_t at = 4;
  std::uint32_t n = 0;
  std::memcpy(&n, payload.data() + at, 4);
  at += 4 + n * sizeof(double) + 4 + 4 + 16;
  ASSERT_EQ(payload[at], 0);  // indexed
  std::memcpy(&n, payload.data() + at + 1, 4);
  at += 1 + 4 + n * sizeof(float);
  ASSERT_TRUE(ParsePreparation(payload));
  payload[at] = static_cast<char>(n);  // one past the table, flat bit clear
  EXPECT_FALSE(ParsePreparation(payload));
}

}  // namespace
}  // namespace fleetmerge
