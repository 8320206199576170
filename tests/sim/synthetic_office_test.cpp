#include "sim/synthetic_office.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <string>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

constexpr std::uint8_t kFreeValue = static_cast<std::uint8_t>(CellState::kFree);
constexpr std::uint8_t kUnknownValue = static_cast<std::uint8_t>(CellState::kUnknown);

int CountDifferent(const OccupancyGrid& a, const OccupancyGrid& b) {
  return cv::countNonZero(a.cells() != b.cells());
}

// A cell of the main corridor: the row with the most free cells (a corridor row is free from
// outer wall to outer wall; every row of rooms crosses at least one wall between rooms).
cv::Point CorridorCell(const OccupancyGrid& office) {
  int best_row = 0, best_count = -1;
  for (int j = 0; j < office.height(); ++j) {
    const int count = cv::countNonZero(office.cells().row(j) == kFreeValue);
    if (count > best_count) best_count = count, best_row = j;
  }
  return cv::Point(office.width() / 2, best_row);
}

// Fraction of the free cells 4-connected to `seed` (4-connected: no squeezing between the
// corners of two walls).
double FractionReachable(const OccupancyGrid& office, cv::Point seed) {
  cv::Mat1b free_mask = office.cells() == kFreeValue;  // 255 where free
  EXPECT_EQ(free_mask(seed), 255);
  cv::floodFill(free_mask, seed, cv::Scalar(128), nullptr, cv::Scalar(0), cv::Scalar(0), 4);
  return cv::countNonZero(free_mask == 128) / static_cast<double>(office.Count(CellState::kFree));
}

TEST(GenerateOfficeFloor, SameSeedGivesIdenticalCellsOtherSeedsDiffer) {
  const OfficeOptions options;
  const OccupancyGrid a = GenerateOfficeFloor(options, 42);
  EXPECT_EQ(CountDifferent(a, GenerateOfficeFloor(options, 42)), 0);
  for (const std::uint32_t other : {0u, 1u, 43u, 4000000000u}) {
    EXPECT_GT(CountDifferent(a, GenerateOfficeFloor(options, other)), 1000) << "seed " << other;
  }
}

TEST(GenerateOfficeFloor, SizeAndFrameFollowTheOptions) {
  OfficeOptions options;
  const OccupancyGrid office = GenerateOfficeFloor(options, 1);
  EXPECT_EQ(office.width(), 600);
  EXPECT_EQ(office.height(), 400);
  EXPECT_DOUBLE_EQ(office.geometry().resolution_m(), 0.05);
  EXPECT_EQ(office.geometry().T_map_grid().translation_m(), Eigen::Vector2d::Zero());
  EXPECT_EQ(office.geometry().T_map_grid().yaw_rad(), 0.0);
  options.width_m = 17.0;
  options.height_m = 12.3;
  options.resolution_m = 0.1;
  const OccupancyGrid small = GenerateOfficeFloor(options, 1);
  EXPECT_EQ(small.width(), 170);
  EXPECT_EQ(small.height(), 123);
}

TEST(GenerateOfficeFloor, EveryRoomIsReachableFromTheCorridor) {
  OfficeOptions no_second_corridor;
  no_second_corridor.vertical_corridor = false;
  OfficeOptions cluttered;
  cluttered.clutter_per_room = 6;
  for (const OfficeOptions& options : {OfficeOptions(), no_second_corridor, cluttered}) {
    for (std::uint32_t seed = 0; seed < 20; ++seed) {
      const OccupancyGrid office = GenerateOfficeFloor(options, seed);
      EXPECT_GE(FractionReachable(office, CorridorCell(office)), 0.95) << "seed " << seed;
    }
  }
}

TEST(GenerateOfficeFloor, OccupiedFractionOfKnownCellsIsPlausible) {
  for (std::uint32_t seed = 0; seed < 20; ++seed) {
    const OccupancyGrid office = GenerateOfficeFloor(OfficeOptions(), seed);
    const double occupied = office.Count(CellState::kOccupied);
    const double fraction = occupied / (occupied + office.Count(CellState::kFree));
    EXPECT_GT(fraction, 0.03) << "seed " << seed;
    EXPECT_LT(fraction, 0.30) << "seed " << seed;
  }
}

TEST(GenerateOfficeFloor, BuildingIsSealedAndOutsideIsUnknown) {
  for (std::uint32_t seed = 0; seed < 20; ++seed) {
    const OccupancyGrid office = GenerateOfficeFloor(OfficeOptions(), seed);
    EXPECT_GT(office.Count(CellState::kUnknown), 0) << "the cut corner is outside";
    const cv::Mat1b& c = office.cells();
    for (int j = 0; j < c.rows; ++j) {
      for (int i = 0; i < c.cols; ++i) {
        if (c(j, i) != kFreeValue) continue;
        ASSERT_TRUE(i > 0 && j > 0 && i + 1 < c.cols && j + 1 < c.rows) << "free on the border";
        ASSERT_TRUE(c(j, i - 1) != kUnknownValue && c(j, i + 1) != kUnknownValue &&
                    c(j - 1, i) != kUnknownValue && c(j + 1, i) != kUnknownValue)
            << "free cell (" << i << ", " << j << ") touches the outside, seed " << seed;
      }
    }
  }
  OfficeOptions whole;
  whole.cut_corner = false;
  EXPECT_EQ(GenerateOfficeFloor(whole, 3).Count(CellState::kUnknown), 0);
}

TEST(GenerateOfficeFloor, FloorPlanIsNotSymmetric) {
  OfficeOptions whole;  // without the cut corner, asymmetry must come from the rooms alone
  whole.cut_corner = false;
  for (std::uint32_t seed = 0; seed < 10; ++seed) {
    const cv::Mat1b cells = GenerateOfficeFloor(whole, seed).cells();
    for (const int flip : {0, 1, -1}) {  // mirror in x, in y, and the half turn
      cv::Mat1b flipped;
      cv::flip(cells, flipped, flip);
      EXPECT_GT(cv::countNonZero(cells != flipped), 1000) << "seed " << seed << " flip " << flip;
    }
  }
}

TEST(GenerateOfficeFloor, ClutterAddsOccupiedCells) {
  OfficeOptions bare;
  bare.clutter_per_room = 0;
  EXPECT_LT(GenerateOfficeFloor(bare, 5).Count(CellState::kOccupied),
            GenerateOfficeFloor(OfficeOptions(), 5).Count(CellState::kOccupied));
}

TEST(GenerateOfficeFloor, RejectsBadOptions) {
  const auto with = [](auto change) {
    OfficeOptions options;
    change(options);
    return options;
  };
  EXPECT_THROW(GenerateOfficeFloor(with([](OfficeOptions& o) { o.resolution_m = 0.0; }), 1), Error);
  EXPECT_THROW(GenerateOfficeFloor(with([](OfficeOptions& o) { o.width_m = NAN; }), 1), Error);
  EXPECT_THROW(GenerateOfficeFloor(with([](OfficeOptions& o) { o.clutter_per_room = -1; }), 1),
               Error);
  EXPECT_THROW(GenerateOfficeFloor(with([](OfficeOptions& o) { o.min_room_width_m = 7.0; }), 1),
               Error);
  EXPECT_THROW(GenerateOfficeFloor(with([](OfficeOptions& o) { o.door_width_m = 2.5; }), 1), Error);
  EXPECT_THROW(GenerateOfficeFloor(with([](OfficeOptions& o) { o.height_m = 5.0; }), 1), Error);
  EXPECT_THROW(GenerateOfficeFloor(with([](OfficeOptions& o) { o.width_m = 5.0; }), 1), Error);
  try {
    GenerateOfficeFloor(with([](OfficeOptions& o) { o.corridor_width_m = -2.0; }), 1);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("corridor_width_m"), std::string::npos) << e.what();
  }
  // The smallest accepted building still generates.
  const OccupancyGrid small = GenerateOfficeFloor(with([](OfficeOptions& o) {
                                                    o.width_m = 5.4;
                                                    o.height_m = 6.5;
                                                  }),
                                                  1);
  EXPECT_GT(small.Count(CellState::kFree), 0);
}

}  // namespace
}  // namespace fleetmerge
