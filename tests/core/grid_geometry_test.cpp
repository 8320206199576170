#include "core/grid_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

TEST(GridGeometry, CellCentreAndCellOfRoundTripWithRotatedOrigin) {
  const GridGeometry g(0.05, {40, 30}, Pose2(-1.0, 2.0, M_PI));  // stata_basement has yaw 3.14
  for (int j = 0; j < 30; j += 7) {
    for (int i = 0; i < 40; i += 5) {
      const Eigen::Array2i cell(i, j);
      EXPECT_TRUE((g.CellOf(g.CellCenter(cell)) == cell).all()) << i << "," << j;
    }
  }
  // With yaw pi the cell (0, 0) centre lies down-left of the origin.
  const Eigen::Vector2d c = g.CellCenter({0, 0});
  EXPECT_NEAR(c.x(), -1.025, 1e-12);
  EXPECT_NEAR(c.y(), 1.975, 1e-12);
}

TEST(GridGeometry, ContainsChecksBothAxes) {
  const GridGeometry g(0.1, {3, 2});
  EXPECT_TRUE(g.Contains({0, 0}));
  EXPECT_TRUE(g.Contains({2, 1}));
  EXPECT_FALSE(g.Contains({3, 1}));
  EXPECT_FALSE(g.Contains({2, 2}));
  EXPECT_FALSE(g.Contains({-1, 0}));
}

TEST(GridGeometry, RejectsNonPositiveResolutionWithMessage) {
  try {
    GridGeometry(0.0, {1, 1});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("resolution must be a finite number > 0"),
              std::string::npos);
  }
  EXPECT_THROW(GridGeometry(-0.05, {1, 1}), Error);
  EXPECT_THROW(GridGeometry(NAN, {1, 1}), Error);
  EXPECT_THROW(GridGeometry(0.05, {-1, 1}), Error);
}

}  // namespace
}  // namespace fleetmerge
