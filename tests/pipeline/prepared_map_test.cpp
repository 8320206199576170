// Per-map work shared by all pairs (pipeline/prepared_map.hpp) must not change any pair's
// answer: ComputeAllPairs, which prepares each map once and shares it between threads, against
// RankedCellHypotheses computed from scratch for each pair, on robot maps cut from a real
// building (the synthetic office without ../shared) and on the same maps at mixed scales.
#include "pipeline/prepared_map.hpp"

#include <gtest/gtest.h>

#include <optional>
#include <random>

#include "core/wall_agreement.hpp"
#include "io/map_io.hpp"
#include "pipeline/all_pairs.hpp"
#include "pipeline/pair_merge.hpp"
#include "sim/ground_truth_pair.hpp"
#include "sim/synthetic_office.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

OccupancyGrid Building() {
  if (const auto dir = testing::SharedMapsDir()) return LoadMap(*dir / "intel_lab.yaml").grid;
  std::printf("[ skipped ] ../shared/data/maps is missing: the synthetic office instead\n");
  return GenerateOfficeFloor(OfficeOptions{}, 5);
}

TEST(PreparedMapTest, SharedWorkGivesEveryPairItsOwnAnswer) {
  std::mt19937 rng(41);
  const GroundTruthFleet fleet = CutFleet(Building(), 4, rng);
  const PairOptions options;
  const std::vector<PairOutcome> shared = ComputeAllPairs(fleet.maps, options, /*threads=*/2);
  ASSERT_EQ(shared.size(), 6u);
  for (const PairOutcome& pair : shared) {
    const OccupancyGrid& a = fleet.maps[pair.a];
    const OccupancyGrid& b = fleet.maps[pair.b];
    const std::vector<CellHypothesis> own = RankedCellHypotheses(a, b, options).hypotheses;
    ASSERT_EQ(pair.hypotheses.size(), own.size()) << pair.a << "-" << pair.b;
    for (std::size_t k = 0; k < own.size(); ++k) {
      // The same hypotheses, exactly the pair's own numbers.
      const auto same = [&](const PairHypothesis& h) {
        const Pose2 T = MapPoseFromCellPose(a.geometry(), b.geometry(), own[k].T_ga_gb);
        return h.omega == own[k].omega && h.T_a_b.x_m() == T.x_m() && h.T_a_b.y_m() == T.y_m() &&
               h.T_a_b.yaw_rad() == T.yaw_rad();
      };
      EXPECT_TRUE(std::any_of(pair.hypotheses.begin(), pair.hypotheses.end(), same))
          << pair.a << "-" << pair.b << " hypothesis " << k;
    }
  }
}

// One pair's work shared by threads (the rotation searches, the refinements, the two maps'
// preparation) gives exactly the one-thread hypotheses, with refinement and without, and on the
// paper's X/Y spectra.
TEST(PreparedMapTest, OnePairOnSeveralThreadsGivesTheOneThreadHypotheses) {
  std::mt19937 rng(43);
  const GroundTruthFleet fleet = CutFleet(Building(), 3, rng);
  PairOptions plain;
  plain.refine = false;
  PairOptions spectra;
  spectra.hypotheses.translation.method = TranslationMethod::kXySpectra;
  int compared = 0;
  for (const PairOptions& options : {PairOptions{}, plain, spectra}) {
    for (const auto& [a, b] : {std::pair{0, 1}, std::pair{1, 2}}) {
      const PairResult one = MergePair(fleet.maps[a], fleet.maps[b], options, 1);
      ASSERT_FALSE(one.hypotheses.empty());
      for (const int threads : {2, 3, 0}) {
        const PairResult many = MergePair(fleet.maps[a], fleet.maps[b], options, threads);
        ASSERT_EQ(many.hypotheses.size(), one.hypotheses.size()) << threads;
        for (std::size_t k = 0; k < one.hypotheses.size(); ++k) {
          const PairHypothesis &h = many.hypotheses[k], &want = one.hypotheses[k];
          EXPECT_EQ(h.omega, want.omega) << threads << " threads, hypothesis " << k;
          EXPECT_EQ(h.T_a_b.x_m(), want.T_a_b.x_m()) << threads << " threads, hypothesis " << k;
          EXPECT_EQ(h.T_a_b.y_m(), want.T_a_b.y_m()) << threads << " threads, hypothesis " << k;
          EXPECT_EQ(h.T_a_b.yaw_rad(), want.T_a_b.yaw_rad()) << threads << " threads, " << k;
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 30);
}

// The walls a fleet's judging needs (core/wall_agreement.hpp) are handed on by the pair search,
// which made them with each map's features: they must be what MapWalls makes from the cells.
TEST(PreparedMapTest, WallsHandedOnAreTheMapsOwnWalls) {
  std::mt19937 rng(44);
  const GroundTruthFleet fleet = CutFleet(Building(), 4, rng);
  std::vector<std::optional<MapWalls>> walls;
  ComputeAllPairs(fleet.maps, PairOptions{}, /*threads=*/2, {}, nullptr, nullptr, &walls);
  ASSERT_EQ(walls.size(), fleet.maps.size());
  for (std::size_t m = 0; m < walls.size(); ++m) {
    ASSERT_TRUE(walls[m]) << "map " << m;
    const MapWalls own(fleet.maps[m]);
    EXPECT_EQ(&walls[m]->grid, &fleet.maps[m]);
    ASSERT_FALSE(own.centres.empty());
    EXPECT_EQ(walls[m]->centres, own.centres) << "map " << m;
    ASSERT_EQ(walls[m]->near_walls.size(), own.near_walls.size());
    EXPECT_EQ(cv::countNonZero(walls[m]->near_walls != own.near_walls), 0) << "map " << m;
    EXPECT_GT(cv::countNonZero(own.near_walls), 0);
    EXPECT_EQ(walls[m]->known_spans.row_begin, own.known_spans.row_begin) << "map " << m;
    EXPECT_EQ(walls[m]->known_spans.runs, own.known_spans.runs) << "map " << m;
  }
}

TEST(PreparedMapTest, TargetsAreBuiltOncePerScaleAndShared) {
  std::mt19937 rng(42);
  const GroundTruthFleet fleet = CutFleet(Building(), 2, rng);
  const PreparedMap prepared(fleet.maps[0], PairOptions{});
  const AlignmentTarget& fine = prepared.Target(1);
  const AlignmentTarget& coarse = prepared.Target(3);
  EXPECT_EQ(&prepared.Target(1), &fine);
  EXPECT_EQ(&prepared.Target(3), &coarse);
  EXPECT_EQ(fine.wall_points.size(), AlignmentTarget(fleet.maps[0]).wall_points.size());
  EXPECT_LT(coarse.wall_points.size(), fine.wall_points.size());
}

}  // namespace
}  // namespace fleetmerge
