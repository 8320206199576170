// Wall agreement (core/wall_agreement.hpp) against a brute-force oracle that reads its
// definition literally: of b's occupied cells whose centres land on a cell a knows, the share
// within one cell (8-neighbourhood) of an occupied cell of a. All three forms (grids, b's wall
// centres, per-map MapWalls) must give the oracle's value, on a synthetic office cut into a
// re-framed pair, at the true pose and at wrong ones.
#include "core/wall_agreement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/hypothesis_generator.hpp"  // CellPoseFromMapPose
#include "core/point_sampling.hpp"
#include "sim/ground_truth_pair.hpp"
#include "sim/synthetic_office.hpp"

namespace fleetmerge {
namespace {

double OracleWallAgreement(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb) {
  long on_known = 0, on_wall = 0;
  for (const Eigen::Array2i& cell : b.CellsIn(CellState::kOccupied)) {
    const Eigen::Vector2d p = T_ga_gb * Eigen::Vector2d(cell.x() + 0.5, cell.y() + 0.5);
    const Eigen::Array2i in_a(static_cast<int>(std::floor(p.x())),
                              static_cast<int>(std::floor(p.y())));
    if (a.StateOrUnknown(in_a) == CellState::kUnknown) continue;
    ++on_known;
    bool near = false;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        near |= a.StateOrUnknown(in_a + Eigen::Array2i(dx, dy)) == CellState::kOccupied;
      }
    }
    on_wall += near;
  }
  return on_known < kMinWallsJudged ? 0.0 : double(on_wall) / double(on_known);
}

TEST(WallAgreement, AllFormsMatchTheDefinitionAtTrueAndWrongPoses) {
  OfficeOptions office;
  office.width_m = 30.0;
  office.height_m = 20.0;
  const OccupancyGrid building = GenerateOfficeFloor(office, 4);
  std::mt19937 rng(11);
  const GroundTruthPair pair = CutPair(building, 0.7, rng);
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

}  // namespace
}  // namespace fleetmerge
