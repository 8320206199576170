// Wall agreement (core/wall_agreement.hpp) against a brute-force oracle that reads its
// definition literally: of b's occupied cells whose centres land on a cell a knows, the share
// within one cell (8-neighbourhood) of an occupied cell of a. All three forms (grids, b's wall
// centres, per-map MapWalls) must give the oracle's value, on a synthetic office cut into a
// re-framed pair, at the true pose and at wrong ones.
#include "core/wall_agreement.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "core/hypothesis_generator.hpp"  // CellPoseFromMapPose
#include "core/point_sampling.hpp"
#include "tests/support/office_pair.hpp"
#include "tests/support/random_grid.hpp"

namespace fleetmerge {
namespace {

WallCount OracleWallCount(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb) {
  WallCount count;
  for (const Eigen::Array2i& cell : b.CellsIn(CellState::kOccupied)) {
    const Eigen::Vector2d p = T_ga_gb * Eigen::Vector2d(cell.x() + 0.5, cell.y() + 0.5);
    const Eigen::Array2i in_a(static_cast<int>(std::floor(p.x())),
                              static_cast<int>(std::floor(p.y())));
    if (a.StateOrUnknown(in_a) == CellState::kUnknown) continue;
    ++count.on_known;
    bool near = false;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        near |= a.StateOrUnknown(in_a + Eigen::Array2i(dx, dy)) == CellState::kOccupied;
      }
    }
    count.near_wall += near;
  }
  return count;
}

double OracleWallAgreement(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb) {
  return OracleWallCount(a, b, T_ga_gb).share();
}

TEST(WallAgreement, AllFormsMatchTheDefinitionAtTrueAndWrongPoses) {
  std::mt19937 rng(11);
  const GroundTruthPair pair = testing::CutOfficePair(rng);
  const Pose2 T_true = CellPoseFromMapPose(pair.a.geometry(), pair.b.geometry(), pair.T_a_b);
  const MapWalls walls_a(pair.a), walls_b(pair.b);
  ASSERT_EQ(walls_b.centres.size(), OccupiedCellCenters(pair.b).size());

  std::normal_distribution<double> shift_cells(0.0, 15.0), turn_rad(0.0, 0.3);
  int judged = 0, high = 0, low = 0;
  for (int k = 0; k < 40; ++k) {
    // The truth, then ever wronger poses around it.
    const Pose2 T = k == 0 ? T_true
                           : T_true * Pose2(shift_cells(rng) * k / 40.0,
                                            shift_cells(rng) * k / 40.0, turn_rad(rng) * k / 40.0);
    const double want_ab = OracleWallAgreement(pair.a, pair.b, T);
    const double want_ba = OracleWallAgreement(pair.b, pair.a, T.inverse());
    EXPECT_EQ(WallAgreement(pair.a, pair.b, T), want_ab) << k;
    EXPECT_EQ(WallAgreement(pair.a, walls_a.near_walls, walls_b.centres, T), want_ab) << k;
    EXPECT_EQ(SymmetricWallAgreement(pair.a, pair.b, T), std::min(want_ab, want_ba)) << k;
    EXPECT_EQ(SymmetricWallAgreement(walls_a, walls_b, T), std::min(want_ab, want_ba)) << k;
    judged += want_ab > 0.0;
    high += want_ab > 0.95;
    low += want_ab > 0.0 && want_ab < 0.7;
  }
  EXPECT_GT(OracleWallAgreement(pair.a, pair.b, T_true), 0.95);  // the true pose
  // The poses spanned agreeing and disagreeing walls.
  EXPECT_GT(judged, 20);
  EXPECT_GT(low, 5);
  EXPECT_GE(high, 1);
}

// CountWallsAndShifted's five counts in one pass against the oracle at each pose: the chance
// shifts the evidence uses (4 cells along a's axes) and uneven ones, around true and wrong poses.
TEST(WallAgreement, ShiftedCountsMatchTheDefinitionAtEachShiftedPose) {
  std::mt19937 rng(12);
  const GroundTruthPair pair = testing::CutOfficePair(rng);
  const Pose2 T_true = CellPoseFromMapPose(pair.a.geometry(), pair.b.geometry(), pair.T_a_b);
  const MapWalls walls_a(pair.a);
  const std::vector<Eigen::Vector2f> b_centres = OccupiedCellCenters(pair.b);
  const std::array<std::array<Eigen::Vector2d, 4>, 2> shift_sets = {{
      {Eigen::Vector2d(4.0, 0.0), Eigen::Vector2d(-4.0, 0.0), Eigen::Vector2d(0.0, 4.0),
       Eigen::Vector2d(0.0, -4.0)},
      {Eigen::Vector2d(2.5, -1.25), Eigen::Vector2d(-7.0, 3.0), Eigen::Vector2d(0.3, 0.0),
       Eigen::Vector2d(-0.5, -9.75)},
  }};
  std::normal_distribution<double> shift_cells(0.0, 10.0), turn_rad(0.0, 0.2);
  long judged = 0;
  for (int k = 0; k < 10; ++k) {
    const Pose2 T =
        k == 0 ? T_true : T_true * Pose2(shift_cells(rng), shift_cells(rng), turn_rad(rng));
    for (const auto& shifts : shift_sets) {
      const std::array<WallCount, 5> got =
          CountWallsAndShifted(pair.a, walls_a.near_walls, b_centres, T, shifts);
      for (int s = 0; s < 5; ++s) {
        const Pose2 T_s = s == 0 ? T : Pose2(shifts[s - 1], 0.0) * T;
        const WallCount want = OracleWallCount(pair.a, pair.b, T_s);
        EXPECT_EQ(got[s].on_known, want.on_known) << k << " " << s;
        EXPECT_EQ(got[s].near_wall, want.near_wall) << k << " " << s;
        judged += want.on_known;
      }
    }
  }
  EXPECT_GT(judged, 1000);  // the poses put walls on a's known cells
}

// b's wall centres landing exactly on a's cell borders, on its last column and row, and a quarter
// of a cell outside its left and bottom borders (floor -1, int cast 0): the counts of every form
// are the definition's.
TEST(WallAgreement, CellBordersAndTheGridsEdgesCountAsTheDefinition) {
  std::mt19937 rng(13);
  const OccupancyGrid a = testing::RandomGrid(41, 29, rng);
  const OccupancyGrid b = testing::RandomGrid(33, 37, rng);
  const MapWalls walls_a(a);
  const std::vector<Eigen::Vector2f> b_centres = OccupiedCellCenters(b);
  std::vector<Pose2> poses;
  for (const double x : {-0.5, 7.5, -33.5 + 41.0}) {
    for (const double y : {-0.5, 4.5, -37.5 + 29.0}) poses.emplace_back(x, y, 0.0);
  }
  poses.emplace_back(-0.75, -0.75, 0.0);
  poses.emplace_back(-0.75 + 33.0, 2.0, M_PI);
  poses.emplace_back(3.0, -0.75 + 33.0, -M_PI / 2);
  long on_known = 0;
  for (const Pose2& T : poses) {
    const WallCount want = OracleWallCount(a, b, T);
    const WallCount got = CountWalls(a, walls_a.near_walls, b_centres, T);
    EXPECT_EQ(got.on_known, want.on_known) << T.x_m() << " " << T.y_m() << " " << T.yaw_rad();
    EXPECT_EQ(got.near_wall, want.near_wall) << T.x_m() << " " << T.y_m() << " " << T.yaw_rad();
    EXPECT_EQ(WallAgreement(a, b, T), want.share());
    on_known += want.on_known;
  }
  EXPECT_GT(on_known, 500);
}

}  // namespace
}  // namespace fleetmerge
