// Pose evidence and ranking (core/pose_evidence.hpp) against an oracle that reads the definition
// literally, cell by cell, on a synthetic office cut into a re-framed pair; and a building of
// identical rooms, where two poses one room apart explain the maps equally: a coin toss.
#include "core/pose_evidence.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "core/acceptance_index.hpp"
#include "core/wall_agreement.hpp"
#include "tests/support/office_pair.hpp"

namespace fleetmerge {
namespace {

// The log-likelihood ratio of the header, from counts made cell by cell.
double OracleEvidence(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb,
                      double* walls) {
  const auto share = [](const OccupancyGrid& g, bool near_wall) {
    double known = 0, hits = 0;
    for (int j = 0; j < g.height(); ++j) {
      for (int i = 0; i < g.width(); ++i) {
        if (g.at({i, j}) == CellState::kUnknown) continue;
        ++known;
        bool hit = g.at({i, j}) == CellState::kOccupied;
        for (int dy = -1; dy <= 1 && near_wall; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            hit |= g.StateOrUnknown({i + dx, j + dy}) == CellState::kOccupied;
          }
        }
        hits += hit;
      }
    }
    return hits / known;
  };
  const auto log_ratio = [](double hits, double trials, double q, double p) {
    p = std::clamp(p, 0.01, q - 0.01);
    return hits * std::log(q / p) + (trials - hits) * std::log((1 - q) / (1 - p));
  };
  // Walls of `from` landing on known cells of `onto`, and of those the ones near its walls.
  const auto walls_on = [&](const OccupancyGrid& onto, const OccupancyGrid& from, const Pose2& T) {
    double judged = 0, near = 0;
    for (const Eigen::Array2i& cell : from.CellsIn(CellState::kOccupied)) {
      const Eigen::Vector2d p = T * Eigen::Vector2d(cell.x() + 0.5, cell.y() + 0.5);
      const Eigen::Array2i c(static_cast<int>(std::floor(p.x())),
                             static_cast<int>(std::floor(p.y())));
      if (onto.StateOrUnknown(c) == CellState::kUnknown) continue;
      ++judged;
      bool hit = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          hit |= onto.StateOrUnknown(c + Eigen::Array2i(dx, dy)) == CellState::kOccupied;
        }
      }
      near += hit;
    }
    return std::make_pair(near, judged);
  };
  const auto [near_ab, judged_ab] = walls_on(a, b, T_ga_gb);
  const auto [near_ba, judged_ba] = walls_on(b, a, T_ga_gb.inverse());
  // Chance for walls: the same pose 4 cells off along each axis of the receiving map.
  const auto chance = [&](const OccupancyGrid& onto, const OccupancyGrid& from, const Pose2& T) {
    double near = 0, judged = 0;
    for (const Eigen::Vector2d& shift : {Eigen::Vector2d(4, 0), Eigen::Vector2d(-4, 0),
                                         Eigen::Vector2d(0, 4), Eigen::Vector2d(0, -4)}) {
      const auto [n, j] = walls_on(onto, from, Pose2(shift, 0.0) * T);
      near += n;
      judged += j;
    }
    return judged < kMinWallsJudged ? share(onto, true) : near / judged;
  };
  *walls = std::min(judged_ab < kMinWallsJudged ? 0.0 : near_ab / judged_ab,
                    judged_ba < kMinWallsJudged ? 0.0 : near_ba / judged_ba);
  const Agreement g = CountAgreement(a, b, T_ga_gb);  // Eq. (1), tested in acceptance_index_test
  const double o_a = share(a, false), o_b = share(b, false);
  const double cells =
      log_ratio(g.agree, g.agree + g.disagree, 0.99, o_a * o_b + (1 - o_a) * (1 - o_b));
  return (cells + log_ratio(near_ab, judged_ab, 0.98, chance(a, b, T_ga_gb)) +
          log_ratio(near_ba, judged_ba, 0.98, chance(b, a, T_ga_gb.inverse()))) /
         9.0;
}

CellHypothesis Hypothesis(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T) {
  const Agreement g = CountAgreement(a, b, T);
  return {T, g.omega(), g.agree + g.disagree};
}

TEST(PoseEvidence, MatchesTheDefinitionAndPrefersTheTruePose) {
  std::mt19937 rng(12);
  const GroundTruthPair pair = testing::CutOfficePair(rng);
  const HypothesisOptions options;
  const MapFeatures a(pair.a, options), b(pair.b, options);
  const Pose2 T_true = CellPoseFromMapPose(pair.a.geometry(), pair.b.geometry(), pair.T_a_b);
  std::normal_distribution<double> shift_cells(0.0, 10.0), turn_rad(0.0, 0.2);
  double true_nats = 0.0;
  for (int k = 0; k < 20; ++k) {
    const Pose2 T =
        k == 0 ? T_true : T_true * Pose2(shift_cells(rng), shift_cells(rng), turn_rad(rng));
    CellHypothesis h = Hypothesis(pair.a, pair.b, T);
    double want_walls = 0.0;
    const double want = OracleEvidence(pair.a, pair.b, T, &want_walls);
    const double got = MeasureEvidence(a, b, h);
    EXPECT_NEAR(got, want, 1e-6 * std::max(1.0, std::abs(want))) << k;
    EXPECT_EQ(h.wall_agreement, want_walls) << k;
    if (k == 0) {
      true_nats = got;
      EXPECT_GT(got, 100.0);  // thousands of agreeing cells and walls
    } else {
      EXPECT_LT(got, true_nats) << k;
    }
  }
}

// A corridor of identical rooms, each 40 cells wide with a door; map a sees rooms 0-3, map b
// rooms 1-3 in a frame of its own. Shifting b by one room lands it on rooms 0-2: every cell agrees
// as well as at the truth, with as much overlap.
OccupancyGrid Rooms(int first_room, int rooms) {
  constexpr int kRoom = 40;
  OccupancyGrid g(GridGeometry(0.05, {rooms * kRoom + 1, 41}));
  for (int j = 0; j <= 40; ++j) {
    for (int i = 0; i <= rooms * kRoom; ++i) {
      const int x = (i + first_room * kRoom) % kRoom;
      const bool wall = j == 0 || j == 40 || (x == 0 && !(j >= 15 && j < 25) && j < 30);
      g.set({i, j}, wall ? CellState::kOccupied : CellState::kFree);
    }
  }
  return g;
}

TEST(PoseEvidence, OneRoomApartInIdenticalRoomsIsACoinToss) {
  const OccupancyGrid a = Rooms(0, 4), b = Rooms(1, 2);
  const HypothesisOptions options;
  const MapFeatures fa(a, options), fb(b, options);
  const Pose2 T_true(40.0, 0.0, 0.0), T_next(80.0, 0.0, 0.0);
  const RankedHypotheses tie = RankByEvidence(
      fa, fb, {Hypothesis(a, b, T_true), Hypothesis(a, b, T_next)}, /*min_overlap_cells=*/100);
  ASSERT_EQ(tie.hypotheses.size(), 2u);
  EXPECT_NEAR(tie.hypotheses[0].omega, 1.0, 1e-12);
  EXPECT_NEAR(tie.hypotheses[1].omega, 1.0, 1e-12);
  EXPECT_TRUE(tie.ambiguous) << "margin " << tie.margin_nats;
  // Nearly nothing between them: only the chance poses 4 cells off differ, at a's ends.
  EXPECT_LT(std::abs(tie.margin_nats), 1.0);

  // Half a room off is a different story: walls land in free space.
  const RankedHypotheses clear = RankByEvidence(
      fa, fb, {Hypothesis(a, b, Pose2(60.0, 0.0, 0.0)), Hypothesis(a, b, T_true)}, 100);
  EXPECT_EQ(clear.hypotheses[0].T_ga_gb.x_m(), 40.0) << "the evidence ranks the truth first";
  EXPECT_FALSE(clear.ambiguous);
  EXPECT_GT(clear.margin_nats, kAmbiguousMarginNats);

  // One hypothesis: no runner-up, no coin toss.
  const RankedHypotheses alone = RankByEvidence(fa, fb, {Hypothesis(a, b, T_true)}, 100);
  EXPECT_FALSE(alone.ambiguous);
  EXPECT_TRUE(std::isinf(alone.margin_nats));
}

}  // namespace
}  // namespace fleetmerge
