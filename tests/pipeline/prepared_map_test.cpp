// Per-map work shared by all pairs (pipeline/prepared_map.hpp) must not change any pair's
// answer: ComputeAllPairs, which prepares each map once and shares it between threads, against
// RankedCellHypotheses computed from scratch for each pair, on robot maps cut from a real
// building (the synthetic office without ../shared) and on the same maps at mixed scales.
#include "pipeline/prepared_map.hpp"

#include <gtest/gtest.h>

#include <random>

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
    const std::vector<CellHypothesis> own = RankedCellHypotheses(a, b, options);
    ASSERT_EQ(pair.hypotheses.size(), own.size()) << pair.a << "-" << pair.b;
    for (std::size_t k = 0; k < own.size(); ++k) {
      // The fleet may promote a tied hypothesis with better walls to the front; every other
      // one keeps its place, and all are exactly the pair's own numbers.
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
