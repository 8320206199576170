#include "core/translation_search.hpp"

#include <gtest/gtest.h>

namespace fleetmerge {
namespace {

OccupancyGrid Grid(int width, int height) {
  return OccupancyGrid(GridGeometry(0.05, {width, height}));
}

// The coarse pixel of the translation search (192-pixel images by default), in cells.
int Pooling(const OccupancyGrid& a, const OccupancyGrid& b) {
  return CorrelationPooling(a, b, TranslationOptions{});
}

TEST(CorrelationPooling, MapsOfSimilarSizeUseTheLargerExtent) {
  // b's extent is its diagonal (it is searched at every rotation): 1000 cells -> 6 per pixel.
  EXPECT_EQ(Pooling(Grid(900, 620), Grid(800, 600)), 6);
  EXPECT_EQ(Pooling(Grid(1200, 400), Grid(800, 600)), 7);  // a's side, 1200
}

TEST(CorrelationPooling, ASiteCountsAtMostTwiceTheRobotsExtent) {
  // A 4000 x 4000 site against an 884 x 784 robot (diagonal 1181.6): 2363 cells -> 13 per pixel,
  // not the 21 the site alone would set; in the other order the robot's side (884) is the smaller
  // extent: 1768 -> 10.
  EXPECT_EQ(Pooling(Grid(4000, 4000), Grid(884, 784)), 13);
  EXPECT_EQ(Pooling(Grid(884, 784), Grid(4000, 4000)), 10);
}

TEST(CorrelationPooling, ATinyMapKeepsTheTransformsBounded) {
  // A quarter of the larger extent at least: 1000 -> 6 per pixel, so the site's image stays
  // ~670 pixels a side however small the robot's map.
  EXPECT_EQ(Pooling(Grid(4000, 4000), Grid(100, 100)), 6);
  EXPECT_EQ(Pooling(Grid(100, 100), Grid(4000, 4000)), 8);  // 5657 / 4 -> 1414
}

}  // namespace
}  // namespace fleetmerge
