// The wall distance field (refine/wall_distance_field.hpp) against a brute-force oracle: the
// truncated distance to the nearest wall cell computed for every cell of a padded copy of the
// whole grid, interpolated by Ceres' own bicubic interpolator. The field stores only a crop and
// skips the interpolation where it is flat; both must give the oracle's value and gradient
// everywhere, inside the grid, around the walls' box and far outside it.
#include "refine/wall_distance_field.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace fleetmerge {
namespace {

constexpr double kTruncationCells = 6.0;
constexpr int kPad = 40;  // oracle cells beyond each side of the grid (all at the truncation)

// A grid with a few walls: an L of two segments and a lone pillar.
OccupancyGrid Walls() {
  OccupancyGrid grid(GridGeometry(0.05, {90, 70}), CellState::kFree);
  for (int x = 20; x < 60; ++x) grid.set({x, 30}, CellState::kOccupied);
  for (int y = 30; y < 55; ++y) grid.set({60, y}, CellState::kOccupied);
  grid.set({75, 10}, CellState::kOccupied);
  return grid;
}

// Distances for cells -kPad .. size + kPad - 1 of `grid`, by brute force over all wall cells.
cv::Mat1f OracleDistances(const OccupancyGrid& grid) {
  const std::vector<Eigen::Array2i> walls = grid.CellsIn(CellState::kOccupied);
  cv::Mat1f d(grid.height() + 2 * kPad, grid.width() + 2 * kPad);
  for (int r = 0; r < d.rows; ++r) {
    for (int c = 0; c < d.cols; ++c) {
      float best = static_cast<float>(kTruncationCells);
      for (const auto& w : walls) {
        const float dist = std::hypot(float(c - kPad - w.x()), float(r - kPad - w.y()));
        if (dist < kTruncationCells) best = std::min(best, dist);
      }
      d(r, c) = best;
    }
  }
  return d;
}

TEST(WallDistanceField, MatchesBruteForceInterpolationEverywhereWithTheFlatShortcut) {
  const OccupancyGrid grid = Walls();
  const WallDistanceField field(grid, kTruncationCells);
  const cv::Mat1f oracle = OracleDistances(grid);
  const ceres::Grid2D<float, 1> oracle_grid(oracle.ptr<float>(), 0, oracle.rows, 0, oracle.cols);
  const ceres::BiCubicInterpolator<ceres::Grid2D<float, 1>> interpolate(oracle_grid);

  std::mt19937 rng(5);
  // Points inside the grid and up to 30 cells beyond it (inside the oracle's padding, which is
  // flat there as the field's border is).
  std::uniform_real_distribution<double> x(-30.0, grid.width() + 30.0);
  std::uniform_real_distribution<double> y(-30.0, grid.height() + 30.0);
  int flat = 0, near_walls = 0;
  for (int k = 0; k < 20000; ++k) {
    const double px = x(rng), py = y(rng);
    double d = 0, d_dx = 0, d_dy = 0;
    const bool is_flat = field.Evaluate(px, py, &d, &d_dx, &d_dy);
    double want = 0, want_dr = 0, want_dc = 0;
    // Cell (i, j) has its centre at (i + .5, j + .5).
    interpolate.Evaluate(py - 0.5 + kPad, px - 0.5 + kPad, &want, &want_dr, &want_dc);
    ASSERT_NEAR(d, want, 1e-12) << "at (" << px << ", " << py << ")";
    ASSERT_NEAR(d_dx, want_dc, 1e-12) << "at (" << px << ", " << py << ")";
    ASSERT_NEAR(d_dy, want_dr, 1e-12) << "at (" << px << ", " << py << ")";
    if (is_flat) {
      ++flat;
      EXPECT_EQ(d, static_cast<float>(kTruncationCells));
      EXPECT_EQ(d_dx, 0.0);
      EXPECT_EQ(d_dy, 0.0);
    } else if (want < kTruncationCells - 1e-6) {
      ++near_walls;
    }
  }
  // Both paths were taken: most of the area is far from the walls.
  EXPECT_GT(flat, 10000);
  EXPECT_GT(near_walls, 1000);
}

TEST(WallDistanceField, FarAwayAndNanPointsAreFlat) {
  const WallDistanceField field(Walls(), kTruncationCells);
  double d = 0, d_dx = 1, d_dy = 1;
  EXPECT_TRUE(field.Evaluate(1e9, -1e9, &d, &d_dx, &d_dy));
  EXPECT_EQ(d, static_cast<float>(kTruncationCells));
  EXPECT_EQ(d_dx, 0.0);
  EXPECT_EQ(d_dy, 0.0);
  // NaN (a diverged pose) is flat too, rather than a float-to-int conversion in Ceres.
  d_dx = d_dy = 1;
  EXPECT_TRUE(field.Evaluate(std::nan(""), 10.0, &d, &d_dx, &d_dy));
  EXPECT_EQ(d, static_cast<float>(kTruncationCells));
  EXPECT_EQ(d_dx, 0.0);
}

}  // namespace
}  // namespace fleetmerge
