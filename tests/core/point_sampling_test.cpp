#include "core/point_sampling.hpp"

#include <gtest/gtest.h>

#include <random>

#include "core/error.hpp"
#include "tests/support/random_grid.hpp"

namespace fleetmerge {
namespace {

std::vector<Eigen::Vector2f> Line(int n) {
  std::vector<Eigen::Vector2f> p;
  for (int k = 0; k < n; ++k) p.emplace_back(float(k), 0.f);
  return p;
}

TEST(SamplePoints, EveryKthKeepsFirstAndStride) {
  SamplingOptions o;
  o.mode = SamplingMode::kEveryKth;
  o.step = 3;
  const auto s = SamplePoints(Line(10), o);
  ASSERT_EQ(s.size(), 4u);
  EXPECT_EQ(s[0].x(), 0.f);
  EXPECT_EQ(s[3].x(), 9.f);
}

TEST(SamplePoints, RandomFractionIsSeededExactSizeAndOrdered) {
  SamplingOptions o;
  o.mode = SamplingMode::kRandomFraction;
  o.fraction = 0.2;
  o.seed = 4;
  const auto s1 = SamplePoints(Line(1000), o);
  const auto s2 = SamplePoints(Line(1000), o);
  ASSERT_EQ(s1.size(), 200u);
  for (std::size_t k = 0; k < s1.size(); ++k) EXPECT_EQ(s1[k], s2[k]);
  for (std::size_t k = 1; k < s1.size(); ++k) EXPECT_LT(s1[k - 1].x(), s1[k].x());
  o.seed = 5;
  EXPECT_NE(SamplePoints(Line(1000), o)[0].x() + SamplePoints(Line(1000), o)[1].x(),
            s1[0].x() + s1[1].x());
}

TEST(SamplePoints, RejectsBadParameters) {
  SamplingOptions o;
  o.mode = SamplingMode::kRandomFraction;
  o.fraction = 0.0;
  EXPECT_THROW(SamplePoints(Line(5), o), Error);
  o.mode = SamplingMode::kEveryKth;
  o.step = 0;
  EXPECT_THROW(SamplePoints(Line(5), o), Error);
}

TEST(OccupiedCellCenters, UsesCellCentresFromTheBottomRow) {
  OccupancyGrid g(GridGeometry(0.05, {4, 3}), CellState::kFree);
  g.set({3, 0}, CellState::kOccupied);
  g.set({1, 2}, CellState::kOccupied);
  const auto p = OccupiedCellCenters(g);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0], Eigen::Vector2f(3.5f, 0.5f));
  EXPECT_EQ(p[1], Eigen::Vector2f(1.5f, 2.5f));
}

TEST(OccupiedAndFreeCellCenters, GivesTheListsInScanOrderLikeCellCenters) {
  std::mt19937 rng(3);
  const OccupancyGrid g = testing::RandomGrid(37, 29, rng);
  // The lists by hand, cell by cell in scan order.
  std::vector<Eigen::Vector2f> want[3];
  for (int j = 0; j < g.height(); ++j)
    for (int i = 0; i < g.width(); ++i)
      want[static_cast<int>(g.at({i, j}))].emplace_back(i + 0.5f, j + 0.5f);
  std::vector<Eigen::Vector2f> occupied = {Eigen::Vector2f(9, 9)}, free;  // replaced
  OccupiedAndFreeCellCenters(g, &occupied, &free);
  EXPECT_EQ(occupied, want[static_cast<int>(CellState::kOccupied)]);
  EXPECT_EQ(free, want[static_cast<int>(CellState::kFree)]);
  for (const CellState state : {CellState::kUnknown, CellState::kFree, CellState::kOccupied}) {
    EXPECT_EQ(CellCenters(g, state), want[static_cast<int>(state)]);
  }
  EXPECT_EQ(occupied.size() + free.size() + g.Count(CellState::kUnknown), 37u * 29u);
}

}  // namespace
}  // namespace fleetmerge
