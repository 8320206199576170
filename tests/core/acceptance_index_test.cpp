#include "core/acceptance_index.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

#include "tests/support/random_grid.hpp"

namespace fleetmerge {
namespace {

constexpr auto U = CellState::kUnknown;
constexpr auto F = CellState::kFree;
constexpr auto O = CellState::kOccupied;

OccupancyGrid Grid(const std::vector<std::vector<CellState>>& rows_from_bottom) {
  const int h = static_cast<int>(rows_from_bottom.size());
  const int w = static_cast<int>(rows_from_bottom[0].size());
  OccupancyGrid g(GridGeometry(0.05, {w, h}));
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) g.set({i, j}, rows_from_bottom[j][i]);
  }
  return g;
}

TEST(AcceptanceIndex, HandCountedAgreementAndDisagreement) {
  const OccupancyGrid a = Grid({{F, F, O}, {U, O, F}});
  const OccupancyGrid b = Grid({{F, O, O}, {F, O, U}});
  const Agreement r = CountAgreement(a, b, Pose2());
  // (0,0) F/F agree, (1,0) F/O dis, (2,0) O/O agree, (0,1) U skip, (1,1) O/O agree, (2,1) skip.
  EXPECT_EQ(r.agree, 3);
  EXPECT_EQ(r.disagree, 1);
  EXPECT_DOUBLE_EQ(r.omega(), 0.75);
}

TEST(AcceptanceIndex, IsOneForAMapWithItself) {
  std::mt19937 rng(5);
  const OccupancyGrid m = testing::RandomGrid(37, 23, rng);
  EXPECT_DOUBLE_EQ(CountAgreement(m, m, Pose2()).omega(), 1.0);
}

TEST(AcceptanceIndex, IsZeroWithoutAgreement) {
  const OccupancyGrid a = Grid({{F, F}});
  const OccupancyGrid b = Grid({{O, U}});
  EXPECT_EQ(CountAgreement(a, b, Pose2()).omega(), 0.0);
  EXPECT_EQ(CountAgreement(a, Grid({{U, U}}), Pose2()).omega(), 0.0);
}

TEST(AcceptanceIndex, MatchesMaterialisedRotatedCopy) {
  // Oracle: rotate b explicitly cell by cell into a's grid and count there.
  std::mt19937 rng(9);
  const OccupancyGrid a = testing::RandomGrid(30, 30, rng);
  const OccupancyGrid b = testing::RandomGrid(20, 15, rng);
  const Pose2 T_ga_gb(12.3, 4.1, 0.9);
  Agreement expected;
  for (int j = 0; j < 15; ++j) {
    for (int i = 0; i < 20; ++i) {
      const Eigen::Vector2d p = T_ga_gb * Eigen::Vector2d(i + 0.5, j + 0.5);
      const Eigen::Array2i cell = p.array().floor().cast<int>();
      const CellState sa = a.StateOrUnknown(cell), sb = b.at({i, j});
      if (sa == U || sb == U) continue;
      (sa == sb ? expected.agree : expected.disagree)++;
    }
  }
  const Agreement r = CountAgreement(a, b, T_ga_gb);
  EXPECT_EQ(r.agree, expected.agree);
  EXPECT_EQ(r.disagree, expected.disagree);
  EXPECT_GT(expected.agree + expected.disagree, 50);
}

}  // namespace
}  // namespace fleetmerge

namespace fleetmerge {
namespace {

TEST(AcceptanceIndex, RowSpansGiveTheSameCountsAtEveryStride) {
  std::mt19937 rng(21);
  const OccupancyGrid a = testing::RandomGrid(60, 60, rng);
  OccupancyGrid b(GridGeometry(0.05, {40, 30}));
  // b: a tilted known band with unknown margins, like a re-framed map.
  for (int j = 0; j < 30; ++j) {
    for (int i = 0; i < 40; ++i) {
      if (i >= j / 2 + 3 && i < j + 15) b.set({i, j}, static_cast<CellState>(1 + rng() % 2));
    }
  }
  const RowSpans spans = KnownRowSpans(b);
  ASSERT_EQ(spans.row_begin.size(), 31u);
  EXPECT_EQ(spans.runs[spans.row_begin[0]], std::make_pair(3, 15));
  const Pose2 T(20.0, 7.0, 0.4);
  for (const int stride : {1, 2, 3}) {
    const Agreement plain = CountAgreement(a, b, T, stride);
    const Agreement fast = CountAgreement(a, b, T, stride, &spans);
    EXPECT_EQ(plain.agree, fast.agree) << stride;
    EXPECT_EQ(plain.disagree, fast.disagree) << stride;
  }
}

}  // namespace
}  // namespace fleetmerge

namespace fleetmerge {
namespace {

// Brute force at any stride: every visited cell of b looked up in a by its own floor().
Agreement CountByHand(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb,
                      int stride) {
  Agreement expected;
  for (int j = 0; j < b.height(); j += stride) {
    for (int i = 0; i < b.width(); i += stride) {
      const Eigen::Vector2d p = T_ga_gb * Eigen::Vector2d(i + 0.5, j + 0.5);
      const Eigen::Array2i cell = p.array().floor().cast<int>();
      const CellState sa = a.StateOrUnknown(cell), sb = b.at({i, j});
      if (sa == CellState::kUnknown || sb == CellState::kUnknown) continue;
      (sa == sb ? expected.agree : expected.disagree)++;
    }
  }
  return expected;
}

TEST(AcceptanceIndex, MatchesBruteForceForRandomPosesIncludingPartialOverlaps) {
  // The count clips each row of b to the part that lands in a; poses that put b half outside a,
  // beyond each of its four edges, entirely outside, or on exact cell borders must all count
  // what the cell-by-cell oracle counts.
  std::mt19937 rng(33);
  const OccupancyGrid a = testing::RandomGrid(47, 38, rng);
  OccupancyGrid b(GridGeometry(0.05, {29, 41}));
  for (int j = 0; j < b.height(); ++j)
    for (int i = 0; i < b.width(); ++i)
      if (i > j / 3) b.set({i, j}, static_cast<CellState>(rng() % 3));
  const RowSpans spans = KnownRowSpans(b);
  std::uniform_real_distribution<double> shift(-60.0, 90.0), yaw(-M_PI, M_PI);
  std::vector<Pose2> poses = {Pose2(),
                              Pose2(0.5, -0.5, 0.0),
                              Pose2(10.0, 3.0, M_PI / 2),
                              Pose2(30.0, 20.0, M_PI),
                              Pose2(-5.0, 40.0, -M_PI / 2),
                              Pose2(500.0, 0.0, 0.3),
                              Pose2(-1e9, 1e9, 1.0)};
  for (int n = 0; n < 300; ++n) poses.emplace_back(shift(rng), shift(rng), yaw(rng));
  std::int64_t compared = 0;
  for (const Pose2& T : poses) {
    for (const int stride : {1, 2, 3}) {
      const Agreement expected = CountByHand(a, b, T, stride);
      for (const RowSpans* s : {static_cast<const RowSpans*>(nullptr), &spans}) {
        const Agreement got = CountAgreement(a, b, T, stride, s);
        ASSERT_EQ(got.agree, expected.agree) << T.x_m() << " " << T.y_m() << " " << stride;
        ASSERT_EQ(got.disagree, expected.disagree) << T.x_m() << " " << T.y_m() << " " << stride;
      }
      compared += expected.agree + expected.disagree;
    }
  }
  EXPECT_GT(compared, 10000);  // many poses overlap: the test compares real counts
}

// OverlapCentre against its definition read literally (std::floor of each visited centre, the
// cell's state through StateOrUnknown): random maps at random poses, and poses that put b's cell
// centres exactly on a's cell borders and just outside a (x in (-1, 0), where the floor is -1
// but the int cast 0), at strides 1 and 8 (the pose graph's anchors).
TEST(OverlapCentre, MatchesItsDefinitionAlsoOnCellBordersAndJustOutsideTheGrid) {
  std::mt19937 rng(9);
  const OccupancyGrid a = testing::RandomGrid(41, 29, rng);
  const OccupancyGrid b = testing::RandomGrid(33, 37, rng);
  const auto oracle = [&](const Pose2& T, int stride) -> std::optional<Eigen::Vector2d> {
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    int count = 0;
    for (int j = 0; j < b.height(); j += stride) {
      for (int i = 0; i < b.width(); i += stride) {
        if (b.StateOrUnknown({i, j}) == CellState::kUnknown) continue;
        const Eigen::Vector2d p = T * Eigen::Vector2d(i + 0.5, j + 0.5);
        const Eigen::Array2i in_a(static_cast<int>(std::floor(p.x())),
                                  static_cast<int>(std::floor(p.y())));
        if (a.StateOrUnknown(in_a) == CellState::kUnknown) continue;
        sum += Eigen::Vector2d(i + 0.5, j + 0.5);
        ++count;
      }
    }
    if (count == 0) return std::nullopt;
    return sum / count;
  };
  std::vector<Pose2> poses;
  std::uniform_real_distribution<double> t(-30.0, 40.0), yaw(-M_PI, M_PI);
  for (int k = 0; k < 30; ++k) poses.emplace_back(t(rng), t(rng), yaw(rng));
  // Centres i + 0.5 moved by a whole number plus a half: every one on a cell corner of a, the
  // first column or row on a's left or bottom border, and the last ones on its right or top one.
  for (const double x : {-0.5, 7.5, 8.5, -33.5 + 41.0}) {
    for (const double y : {-0.5, 4.5, -37.5 + 29.0}) poses.emplace_back(x, y, 0.0);
  }
  // A quarter of a cell short of a's left and bottom borders: b's first column and row land at
  // -0.25, whose floor is outside a.
  poses.emplace_back(-0.75, -0.75, 0.0);
  poses.emplace_back(-0.75 + 33.0, 2.0, M_PI);  // turned a half: the last column at -0.25
  int overlapping = 0;
  for (const Pose2& T : poses) {
    for (const int stride : {1, 8}) {
      const auto want = oracle(T, stride);
      const auto got = OverlapCentre(a, b, T, stride);
      ASSERT_EQ(got.has_value(), want.has_value()) << T.x_m() << " " << T.y_m();
      if (!want) continue;
      ++overlapping;
      EXPECT_EQ(got->x(), want->x()) << T.x_m() << " " << T.y_m() << " " << T.yaw_rad();
      EXPECT_EQ(got->y(), want->y()) << T.x_m() << " " << T.y_m() << " " << T.yaw_rad();
    }
  }
  EXPECT_GT(overlapping, 30);
}

}  // namespace
}  // namespace fleetmerge
