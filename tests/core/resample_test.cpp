#include "core/resample.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

constexpr CellState U = CellState::kUnknown;
constexpr CellState F = CellState::kFree;
constexpr CellState O = CellState::kOccupied;

// Builds a grid from rows written top row first (as they read on the page), so row 0 of
// `rows_top_first` becomes grid row height - 1.
OccupancyGrid GridFromRows(const std::vector<std::vector<CellState>>& rows_top_first,
                           double resolution_m, const Pose2& T_map_grid = {}) {
  const int height = static_cast<int>(rows_top_first.size());
  const int width = static_cast<int>(rows_top_first.front().size());
  OccupancyGrid grid(GridGeometry(resolution_m, {width, height}, T_map_grid));
  for (int r = 0; r < height; ++r) {
    for (int i = 0; i < width; ++i) grid.set({i, height - 1 - r}, rows_top_first[r][i]);
  }
  return grid;
}

void ExpectCells(const OccupancyGrid& grid, const std::vector<std::vector<CellState>>& expected) {
  const OccupancyGrid want = GridFromRows(expected, grid.geometry().resolution_m());
  ASSERT_EQ(grid.width(), want.width());
  ASSERT_EQ(grid.height(), want.height());
  for (int j = 0; j < grid.height(); ++j) {
    for (int i = 0; i < grid.width(); ++i) {
      EXPECT_EQ(grid.at({i, j}), want.at({i, j})) << "cell (" << i << ", " << j << ")";
    }
  }
}

TEST(ResampleToResolution, CoarsensTwoByTwoBlocksOccupiedThenFreeThenUnknown) {
  const OccupancyGrid grid = GridFromRows({{U, U, F, U, O, F},  //
                                           {U, U, U, U, F, F},
                                           {F, F, O, U, U, U},
                                           {F, O, U, U, U, F}},
                                          0.05);
  const OccupancyGrid coarse = ResampleToResolution(grid, 0.10);
  ExpectCells(coarse, {{U, F, O},  //
                       {O, O, F}});
  EXPECT_DOUBLE_EQ(coarse.geometry().resolution_m(), 0.10);
}

TEST(ResampleToResolution, OddSizeCoarsensToCeilingWithPartialEdgeCells) {
  const OccupancyGrid grid = GridFromRows({{F, F, O},  //
                                           {F, F, F},
                                           {U, U, F}},
                                          0.1);
  const OccupancyGrid coarse = ResampleToResolution(grid, 0.2);
  // 3 cells of 0.1 m -> ceil(0.3 / 0.2) = 2 cells; the right/top ones cover one source column/row
  // and half a cell of nothing.
  ExpectCells(coarse, {{F, O},  //
                       {F, F}});
}

TEST(ResampleToResolution, RefinesEachCellIntoTwoByTwoCopies) {
  const OccupancyGrid grid = GridFromRows({{O, F},  //
                                           {U, F}},
                                          0.1);
  const OccupancyGrid fine = ResampleToResolution(grid, 0.05);
  ExpectCells(fine, {{O, O, F, F},  //
                     {O, O, F, F},
                     {U, U, F, F},
                     {U, U, F, F}});
}

TEST(ResampleToResolution, SameResolutionIsAnIndependentCopy) {
  const OccupancyGrid grid = GridFromRows({{O, F, U}, {F, F, O}}, 0.05, Pose2(1.0, -2.0, 0.3));
  OccupancyGrid copy = ResampleToResolution(grid, 0.05);
  ASSERT_EQ(copy.width(), 3);
  ASSERT_EQ(copy.height(), 2);
  EXPECT_EQ(cv::countNonZero(copy.cells() != grid.cells()), 0);
  copy.set({0, 0}, CellState::kOccupied);
  EXPECT_EQ(grid.at({0, 0}), CellState::kFree);  // not sharing the cell buffer
}

TEST(ResampleToResolution, WallOneCellThickSurvivesThreeTimesCoarsening) {
  // A 30 x 30 free room with a one-cell wall in column 17 and another in row 4 (neither on a
  // multiple of 3, so each coarse cell sees the wall in just one of its 3 source columns/rows).
  OccupancyGrid grid(GridGeometry(0.05, {30, 30}), CellState::kFree);
  for (int k = 0; k < 30; ++k) {
    grid.set({17, k}, CellState::kOccupied);
    grid.set({k, 4}, CellState::kOccupied);
  }
  const OccupancyGrid coarse = ResampleToResolution(grid, 0.15);
  ASSERT_EQ(coarse.width(), 10);
  ASSERT_EQ(coarse.height(), 10);
  for (int k = 0; k < 10; ++k) {
    EXPECT_EQ(coarse.at({17 / 3, k}), CellState::kOccupied) << "vertical wall row " << k;
    EXPECT_EQ(coarse.at({k, 4 / 3}), CellState::kOccupied) << "horizontal wall column " << k;
  }
  EXPECT_EQ(coarse.Count(CellState::kOccupied), 19);  // two lines of 10, crossing once
  EXPECT_EQ(coarse.Count(CellState::kFree), 81);
}

TEST(ResampleToResolution, KeepsOriginPoseAndCoversTheOldExtent) {
  const Pose2 T_map_grid(-12.5, 3.25, M_PI);  // rotated origins occur in real map files
  const OccupancyGrid grid(GridGeometry(0.05, {401, 250}, T_map_grid), CellState::kFree);
  for (const double resolution_m : {0.05, 0.1, 0.15, 0.025, 0.07}) {
    const OccupancyGrid out = ResampleToResolution(grid, resolution_m);
    const GridGeometry& g = out.geometry();
    EXPECT_EQ(g.width(), static_cast<int>(std::ceil(401 * 0.05 / resolution_m - 1e-9)));
    EXPECT_EQ(g.height(), static_cast<int>(std::ceil(250 * 0.05 / resolution_m - 1e-9)));
    EXPECT_GE(g.width() * resolution_m, 401 * 0.05 - 1e-9);
    EXPECT_LT((g.width() - 1) * resolution_m, 401 * 0.05);
    EXPECT_NEAR(g.T_map_grid().x_m(), T_map_grid.x_m(), 1e-12);
    EXPECT_NEAR(g.T_map_grid().y_m(), T_map_grid.y_m(), 1e-12);
    EXPECT_NEAR(g.T_map_grid().yaw_rad(), T_map_grid.yaw_rad(), 1e-12);
    // The same world point lands in a known cell of the same state in both grids.
    const Eigen::Vector2d p_map = grid.geometry().CellCenter({200, 100});
    EXPECT_EQ(out.StateOrUnknown(g.CellOf(p_map)), CellState::kFree);
  }
  // Exact multiples do not gain a spurious empty cell from rounding (0.5 / 0.1 > 5 in doubles).
  const OccupancyGrid ten(GridGeometry(0.05, {10, 10}), CellState::kFree);
  EXPECT_EQ(ResampleToResolution(ten, 0.1).width(), 5);
  EXPECT_EQ(ResampleToResolution(ten, 0.1).Count(CellState::kUnknown), 0);
}

TEST(ResampleToResolution, RefineThenCoarsenRestoresTheGrid) {
  OccupancyGrid grid(GridGeometry(0.1, {13, 7}));
  std::uint32_t state = 12345u;  // small LCG: a fixed pseudo-random pattern of all three states
  for (int j = 0; j < 7; ++j) {
    for (int i = 0; i < 13; ++i) {
      state = state * 1664525u + 1013904223u;
      grid.set({i, j}, static_cast<CellState>((state >> 16) % 3));
    }
  }
  const OccupancyGrid back = ResampleToResolution(ResampleToResolution(grid, 0.025), 0.1);
  ASSERT_EQ(back.width(), 13);
  ASSERT_EQ(back.height(), 7);
  EXPECT_EQ(cv::countNonZero(back.cells() != grid.cells()), 0);
}

TEST(ResampleToResolution, RejectsNonPositiveResolution) {
  const OccupancyGrid grid(GridGeometry(0.05, {4, 4}));
  EXPECT_THROW(ResampleToResolution(grid, 0.0), Error);
  EXPECT_THROW(ResampleToResolution(grid, -0.1), Error);
  EXPECT_THROW(ResampleToResolution(grid, NAN), Error);
  EXPECT_THROW(ResampleToResolution(grid, INFINITY), Error);
}

}  // namespace
}  // namespace fleetmerge
