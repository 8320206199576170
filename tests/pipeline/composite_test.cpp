#include "pipeline/composite.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "pipeline/preview.hpp"
#include "sim/synthetic_office.hpp"

namespace fleetmerge {
namespace {

constexpr FusionMode kAllModes[] = {FusionMode::kLogOdds, FusionMode::kMax, FusionMode::kVote};

// Uniform in [lo, hi) from mt19937's standard-fixed sequence (portable across libraries).
double Uniform(std::mt19937& rng, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(rng()) / 4294967296.0);
}

// A fixed pseudo-random pattern of all three states, known cells everywhere except a border of
// `unknown_border` cells.
OccupancyGrid PatternGrid(const GridGeometry& geometry, std::uint32_t seed, int unknown_border) {
  OccupancyGrid grid(geometry);
  std::mt19937 rng(seed);
  for (int j = unknown_border; j < grid.height() - unknown_border; ++j) {
    for (int i = unknown_border; i < grid.width() - unknown_border; ++i) {
      grid.set({i, j}, rng() % 4 == 0 ? CellState::kOccupied : CellState::kFree);
      if (rng() % 7 == 0) grid.set({i, j}, CellState::kUnknown);
    }
  }
  return grid;
}

// Every merged cell holds the state of the input cell under its centre, and every known input
// cell appears in the merged grid.
void ExpectSameWorld(const OccupancyGrid& merged, const OccupancyGrid& original,
                     const Pose2& T_merged_map = {}) {
  const Pose2 T_map_merged = T_merged_map.inverse();
  for (int j = 0; j < merged.height(); ++j) {
    for (int i = 0; i < merged.width(); ++i) {
      const Eigen::Vector2d p_map = T_map_merged * merged.geometry().CellCenter({i, j});
      ASSERT_EQ(merged.at({i, j}), original.StateOrUnknown(original.geometry().CellOf(p_map)))
          << "merged cell (" << i << ", " << j << ")";
    }
  }
  EXPECT_EQ(merged.Count(CellState::kOccupied), original.Count(CellState::kOccupied));
  EXPECT_EQ(merged.Count(CellState::kFree), original.Count(CellState::kFree));
}

TEST(Composite, OneMapAtIdentityCompositesToItself) {
  const OccupancyGrid grid = PatternGrid(GridGeometry(0.05, {20, 15}, Pose2(-1.0, 2.0, 0.0)), 7, 2);
  for (const FusionMode mode : kAllModes) {
    const OccupancyGrid merged = Composite({{&grid, Pose2()}}, 0.05, mode);
    EXPECT_EQ(merged.width(), 16 + 2);  // known bounding box plus a one-cell margin each side
    EXPECT_EQ(merged.height(), 11 + 2);
    EXPECT_DOUBLE_EQ(merged.geometry().T_map_grid().yaw_rad(), 0.0);
    // Same world positions: the merged origin is the first known cell's corner, less the margin.
    EXPECT_NEAR(merged.geometry().T_map_grid().x_m(), -1.0 + 0.05, 1e-12);
    EXPECT_NEAR(merged.geometry().T_map_grid().y_m(), 2.0 + 0.05, 1e-12);
    ExpectSameWorld(merged, grid);
  }
}

TEST(Composite, MapWithHalfTurnGridOriginKeepsEveryCell) {
  // Real map files (stata_basement) carry a grid origin with yaw pi.
  const OccupancyGrid grid = PatternGrid(GridGeometry(0.05, {25, 10}, Pose2(3.0, 1.0, M_PI)), 8, 0);
  const Pose2 T_merged_map(-4.0, 0.5, 0.0);
  ExpectSameWorld(Composite({{&grid, T_merged_map}}, 0.05), grid, T_merged_map);
}

TEST(Composite, ReferenceKeepsItsCellsWhenAnotherMapReachesLower) {
  // The reference's grid corner is off the other map's lattice by a fraction of a cell, and its
  // grid frame is turned by 0 or pi (real map files carry both); the other map is rotated and
  // reaches below and left of it, so the merged grid's corner is not the reference's.
  for (const double grid_yaw_rad : {0.0, M_PI}) {
    const OccupancyGrid reference =
        PatternGrid(GridGeometry(0.05, {40, 30}, Pose2(0.013, -0.027, grid_yaw_rad)), 21, 3);
    const OccupancyGrid other = PatternGrid(GridGeometry(0.05, {30, 30}), 22, 0);
    const Pose2 T_merged_other(-1.3, -0.9, 0.4);
    for (const FusionMode mode : kAllModes) {
      const OccupancyGrid merged =
          Composite({{&reference, Pose2()}, {&other, T_merged_other}}, 0.05, mode, 1, 0);
      const OccupancyGrid other_on_merged = SampleOnto({&other, T_merged_other}, merged.geometry());
      int only_reference = 0;
      for (int j = 0; j < reference.height(); ++j) {
        for (int i = 0; i < reference.width(); ++i) {
          if (reference.at({i, j}) == CellState::kUnknown) continue;  // outside the merged grid
          const Eigen::Vector2d p = reference.geometry().CellCenter({i, j});
          const Eigen::Array2i cell = merged.geometry().CellOf(p);
          ASSERT_TRUE(merged.geometry().Contains(cell));
          ASSERT_LT((merged.geometry().CellCenter(cell) - p).norm(), 1e-9) << i << ", " << j;
          if (other_on_merged.at(cell) != CellState::kUnknown) continue;
          ++only_reference;
          ASSERT_EQ(merged.at(cell), reference.at({i, j})) << i << ", " << j;
        }
      }
      EXPECT_GT(only_reference, 300);
      // Not vacuous: alone, the reference's lowest known cell (3, 3) would be the merged grid's
      // cell (1, 1) (the margin); the other map pushes the corner further down or left.
      const Eigen::Vector2d lowest_known_in_merged_grid =
          merged.geometry().T_map_grid().inverse() * reference.geometry().CellCenter({3, 3});
      EXPECT_GT(lowest_known_in_merged_grid.maxCoeff(), 2.5 * 0.05);
    }
  }
  const OccupancyGrid grid = PatternGrid(GridGeometry(0.05, {5, 5}), 1, 0);
  EXPECT_THROW(Composite({{&grid, Pose2()}}, 0.05, FusionMode::kLogOdds, 1, 1), Error);
}

TEST(Composite, TwoHalvesPlacedByRotationAndTranslationRebuildTheOriginal) {
  const OccupancyGrid original = PatternGrid(GridGeometry(0.1, {20, 12}), 3, 0);
  ASSERT_NE(original.at({0, 0}), CellState::kUnknown);  // so the known box is the whole grid
  ASSERT_NE(original.at({19, 11}), CellState::kUnknown);
  // Left half: columns 0..9, stored as-is in the merged frame.
  const OccupancyGrid left(GridGeometry(0.1, {10, 12}),
                           original.cells()(cv::Rect(0, 0, 10, 12)).clone());
  // Right half: columns 10..19, stored turned by 90 degrees in a map whose grid origin is offset.
  // Its grid frame sits at (2 m, 0) in the merged frame, rotated +90 degrees, so grid cell (a, b)
  // covers original column 19 - b, row a.
  const Pose2 T_merged_rightgrid(2.0, 0.0, M_PI / 2.0);
  const Pose2 T_map_grid(0.3, -0.2, 0.0);
  OccupancyGrid right(GridGeometry(0.1, {12, 10}, T_map_grid));
  for (int b = 0; b < 10; ++b) {
    for (int a = 0; a < 12; ++a) {
      const Eigen::Array2i cell = original.geometry().CellOf(
          T_merged_rightgrid * right.geometry().CellCenterInGrid({a, b}));
      ASSERT_TRUE((cell == Eigen::Array2i(19 - b, a)).all());
      right.set({a, b}, original.at(cell));
    }
  }
  const Pose2 T_merged_rightmap = T_merged_rightgrid * T_map_grid.inverse();
  for (const FusionMode mode : kAllModes) {
    const OccupancyGrid merged =
        Composite({{&left, Pose2()}, {&right, T_merged_rightmap}}, 0.1, mode);
    EXPECT_EQ(merged.width(), 22);
    EXPECT_EQ(merged.height(), 14);
    ExpectSameWorld(merged, original);
  }
}

TEST(Composite, FuseFollowsTheDocumentedRules) {
  struct Case {
    int occupied, free;
    CellState log_odds, max, vote;
  };
  const CellState O = CellState::kOccupied, F = CellState::kFree, U = CellState::kUnknown;
  const Case cases[] = {{0, 0, U, U, U}, {1, 0, O, O, O}, {0, 1, F, F, F}, {1, 1, O, O, O},
                        {1, 2, O, O, F}, {1, 3, F, O, F}, {2, 1, O, O, O}, {2, 4, O, O, F},
                        {2, 5, F, O, F}, {0, 5, F, F, F}};
  for (const Case& c : cases) {
    SCOPED_TRACE(testing::Message() << c.occupied << " occupied, " << c.free << " free");
    EXPECT_EQ(Fuse(c.occupied, c.free, FusionMode::kLogOdds), c.log_odds);
    EXPECT_EQ(Fuse(c.occupied, c.free, FusionMode::kMax), c.max);
    EXPECT_EQ(Fuse(c.occupied, c.free, FusionMode::kVote), c.vote);
  }
  EXPECT_NEAR(kLogOddsOccupied, std::log(0.7 / 0.3), 1e-15);
  EXPECT_NEAR(kLogOddsFree, std::log(0.4 / 0.6), 1e-15);
}

TEST(Composite, ConflictingCellFollowsTheFusionMode) {
  // Four 3 x 3 free maps at one place; the centre is occupied in the first only.
  std::vector<OccupancyGrid> grids;
  for (int k = 0; k < 4; ++k) grids.emplace_back(GridGeometry(0.1, {3, 3}), CellState::kFree);
  grids[0].set({1, 1}, CellState::kOccupied);
  const auto centre_state = [&](int map_count, FusionMode mode) {
    std::vector<CompositeInput> inputs;
    for (int k = 0; k < map_count; ++k) inputs.push_back({&grids[k], Pose2()});
    const OccupancyGrid merged = Composite(inputs, 0.1, mode);
    return merged.at(merged.geometry().CellOf(Eigen::Vector2d(0.15, 0.15)));
  };
  EXPECT_EQ(centre_state(2, FusionMode::kLogOdds), CellState::kOccupied);  // 1 vs 1
  EXPECT_EQ(centre_state(2, FusionMode::kMax), CellState::kOccupied);
  EXPECT_EQ(centre_state(2, FusionMode::kVote), CellState::kOccupied);     // tie -> occupied
  EXPECT_EQ(centre_state(3, FusionMode::kLogOdds), CellState::kOccupied);  // 0.847 > 2 x 0.405
  EXPECT_EQ(centre_state(3, FusionMode::kVote), CellState::kFree);
  EXPECT_EQ(centre_state(4, FusionMode::kLogOdds), CellState::kFree);  // 0.847 < 3 x 0.405
  EXPECT_EQ(centre_state(4, FusionMode::kMax), CellState::kOccupied);
  EXPECT_EQ(centre_state(4, FusionMode::kVote), CellState::kFree);
}

TEST(Composite, FixedMapsAloneDecideTheCellsTheyKnow) {
  // Two fixed maps (the reference, and one turned and shifted over part of it) and two maps that
  // move, all rotated against each other, with unknown cells scattered in every map.
  const OccupancyGrid base =
      PatternGrid(GridGeometry(0.05, {60, 50}, Pose2(0.013, -0.027, 0.0)), 31, 4);
  const OccupancyGrid annex = PatternGrid(GridGeometry(0.05, {30, 30}), 32, 0);
  const OccupancyGrid robot_a = PatternGrid(GridGeometry(0.05, {45, 40}), 33, 0);
  const OccupancyGrid robot_b = PatternGrid(GridGeometry(0.05, {40, 40}), 34, 0);
  const std::vector<CompositeInput> inputs = {{&base, Pose2(), true},
                                              {&robot_a, Pose2(-0.8, -0.6, 0.3)},
                                              {&annex, Pose2(2.1, 0.7, -0.5), true},
                                              {&robot_b, Pose2(1.2, 1.5, 2.0)}};
  for (const FusionMode mode : kAllModes) {
    SCOPED_TRACE(static_cast<int>(mode));
    const OccupancyGrid merged = Composite(inputs, 0.05, mode, 2, 0);
    std::vector<OccupancyGrid> sampled;
    for (const CompositeInput& input : inputs)
      sampled.push_back(SampleOnto(input, merged.geometry()));
    int fixed_cells = 0, fused_otherwise = 0, both_fixed = 0, moving_only = 0;
    for (int j = 0; j < merged.height(); ++j) {
      for (int i = 0; i < merged.width(); ++i) {
        int counts[2][2] = {};  // [fixed][occupied]
        for (std::size_t k = 0; k < inputs.size(); ++k) {
          const CellState state = sampled[k].at({i, j});
          if (state == CellState::kUnknown) continue;
          ++counts[inputs[k].fixed][state == CellState::kOccupied];
        }
        const int fixed_known = counts[1][0] + counts[1][1];
        const CellState expected = fixed_known > 0 ? Fuse(counts[1][1], counts[1][0], mode)
                                                   : Fuse(counts[0][1], counts[0][0], mode);
        ASSERT_EQ(merged.at({i, j}), expected) << "merged cell " << i << ", " << j;
        fixed_cells += fixed_known > 0;
        both_fixed += fixed_known == 2;
        moving_only += fixed_known == 0 && counts[0][0] + counts[0][1] > 0;
        fused_otherwise += fixed_known > 0 && Fuse(counts[0][1] + counts[1][1],
                                                   counts[0][0] + counts[1][0], mode) != expected;
      }
    }
    // Not vacuous: cells every kind of case decides, and cells that fusing every map would change.
    EXPECT_GT(fixed_cells, 1500);
    EXPECT_GT(both_fixed, 100);
    EXPECT_GT(moving_only, 500);
    EXPECT_GT(fused_otherwise, 50);
  }
}

TEST(Composite, CellsSeenByNoMapAreUnknown) {
  const OccupancyGrid a(GridGeometry(0.1, {4, 4}), CellState::kFree);
  const OccupancyGrid b(GridGeometry(0.1, {4, 4}), CellState::kFree);
  // b is 1 m to the right and turned by a quarter turn about its own corner.
  const OccupancyGrid merged = Composite({{&a, Pose2()}, {&b, Pose2(1.4, 0.0, M_PI / 2.0)}}, 0.1);
  EXPECT_EQ(merged.width(), 16);
  EXPECT_EQ(merged.height(), 6);
  EXPECT_EQ(merged.Count(CellState::kFree), 32);
  EXPECT_EQ(merged.Count(CellState::kUnknown), 16 * 6 - 32);
  for (int j = 0; j < merged.height(); ++j) {
    for (int i = 5; i <= 10; ++i) EXPECT_EQ(merged.at({i, j}), CellState::kUnknown);  // the gap
  }
}

TEST(Composite, NoKnownCellsGiveAnEmptyGridAndBadInputsThrow) {
  const OccupancyGrid unknown(GridGeometry(0.1, {5, 5}));
  EXPECT_EQ(Composite({}, 0.1).width(), 0);
  EXPECT_EQ(Composite({{&unknown, Pose2()}}, 0.1).geometry().size().sum(), 0);
  EXPECT_THROW(Composite({{&unknown, Pose2()}}, 0.0), Error);
  EXPECT_THROW(Composite({{&unknown, Pose2()}}, NAN), Error);
  EXPECT_THROW(Composite({{nullptr, Pose2()}}, 0.1), Error);
  EXPECT_THROW(SampleOnto({nullptr, Pose2()}, GridGeometry(0.1, {2, 2})), Error);
}

TEST(SampleOnto, MatchesTheDirectCellOfLookupAtRandomPoses) {
  std::mt19937 rng(2024);
  for (int trial = 0; trial < 50; ++trial) {
    const Pose2 T_map_grid(Uniform(rng, -2, 2), Uniform(rng, -2, 2), Uniform(rng, -M_PI, M_PI));
    const OccupancyGrid input =
        PatternGrid(GridGeometry(0.05, {37, 23}, T_map_grid), static_cast<std::uint32_t>(trial), 0);
    const CompositeInput placed{
        &input, Pose2(Uniform(rng, -1, 1), Uniform(rng, -1, 1), Uniform(rng, -M_PI, M_PI))};
    // A target grid that is not axis-aligned, at another resolution.
    const GridGeometry target(
        Uniform(rng, 0.02, 0.08), {60, 50},
        Pose2(Uniform(rng, -3, -1), Uniform(rng, -3, -1), Uniform(rng, -1, 1)));
    const OccupancyGrid fast = SampleOnto(placed, target);
    int mismatches = 0;
    for (int j = 0; j < target.height(); ++j) {
      for (int i = 0; i < target.width(); ++i) {
        const Eigen::Vector2d p_map = placed.T_merged_map.inverse() * target.CellCenter({i, j});
        mismatches += fast.at({i, j}) != input.StateOrUnknown(input.geometry().CellOf(p_map));
      }
    }
    EXPECT_EQ(mismatches, 0) << "trial " << trial;
  }
}

// `count` synthetic offices (seeds 0, 1, ...) of width_m x height_m, each at a random pose:
// translation within +-max_shift_m per axis, any yaw.
struct PlacedOffices {
  PlacedOffices(int count, double width_m, double height_m, double max_shift_m,
                std::uint32_t seed) {
    OfficeOptions options;
    options.width_m = width_m;
    options.height_m = height_m;
    std::mt19937 rng(seed);
    for (int k = 0; k < count; ++k) {
      maps.push_back(GenerateOfficeFloor(options, static_cast<std::uint32_t>(k)));
    }
    for (const OccupancyGrid& map : maps) {
      inputs.push_back(
          {&map, Pose2(Uniform(rng, -max_shift_m, max_shift_m),
                       Uniform(rng, -max_shift_m, max_shift_m), Uniform(rng, -M_PI, M_PI))});
    }
  }
  PlacedOffices(const PlacedOffices&) = delete;  // inputs point into maps
  std::vector<OccupancyGrid> maps;
  std::vector<CompositeInput> inputs;
};

TEST(Composite, EightOfficeMapsOf600By600CompositeQuickly) {
  const PlacedOffices offices(8, 30.0, 30.0, 10.0, 99);  // 600 x 600 cells at 0.05 m
  const std::vector<CompositeInput>& inputs = offices.inputs;
  double best_ms = 1e9;
  OccupancyGrid merged;
  for (int run = 0; run < 3; ++run) {
    const auto start = std::chrono::steady_clock::now();
    merged = Composite(inputs, 0.05);
    const std::chrono::duration<double, std::milli> elapsed =
        std::chrono::steady_clock::now() - start;
    best_ms = std::min(best_ms, elapsed.count());
  }
  std::cout << "[ timing   ] 8 maps of 600 x 600 -> " << merged.width() << " x " << merged.height()
            << " merged cells in " << best_ms << " ms (best of 3)\n";
  RecordProperty("composite_ms", std::to_string(best_ms));
  EXPECT_GT(merged.Count(CellState::kOccupied), 0);
  EXPECT_LT(best_ms, 1000.0);  // loose: the machine is shared; the target is well under 100 ms
}

TEST(Composite, MergedGridAndPreviewAreTheSameForAnyThreadCount) {
  const PlacedOffices offices(5, 20.0, 15.0, 5.0, 7);
  const std::vector<CompositeInput>& inputs = offices.inputs;
  const OccupancyGrid one = Composite(inputs, 0.05, FusionMode::kLogOdds, 1);
  ASSERT_GT(one.height(), 64 * 3);  // several bands of rows
  const cv::Mat3b preview_one = ColourPreview(inputs, one, 1);
  for (const int threads : {2, 3, 0}) {
    const OccupancyGrid many = Composite(inputs, 0.05, FusionMode::kLogOdds, threads);
    ASSERT_EQ(many.cells().size(), one.cells().size());
    EXPECT_EQ(cv::countNonZero(many.cells() != one.cells()), 0) << threads << " threads";
    const cv::Mat3b preview = ColourPreview(inputs, one, threads);
    cv::Mat difference;
    cv::absdiff(preview, preview_one, difference);
    EXPECT_EQ(cv::countNonZero(difference.reshape(1)), 0) << threads << " threads";
  }
}

// The preview coloured while compositing is ColourPreview's afterwards, pixel for pixel: rotated
// maps, a reference map, several bands, any thread count.
TEST(ColourPreview, ColouredWhileCompositingIsTheSameImage) {
  const PlacedOffices offices(5, 20.0, 15.0, 5.0, 7);
  const std::vector<CompositeInput>& inputs = offices.inputs;
  for (const int reference : {-1, 2}) {
    const OccupancyGrid merged = Composite(inputs, 0.05, FusionMode::kLogOdds, 1, reference);
    ASSERT_GT(merged.height(), 64 * 3);  // several bands of rows
    const cv::Mat3b after = ColourPreview(inputs, merged, 1);
    for (const int threads : {1, 2, 3}) {
      PreviewColourer preview;
      const OccupancyGrid with_preview =
          Composite(inputs, 0.05, FusionMode::kLogOdds, threads, reference, &preview);
      EXPECT_EQ(cv::countNonZero(with_preview.cells() != merged.cells()), 0);
      ASSERT_EQ(preview.image().size(), after.size());
      cv::Mat difference;
      cv::absdiff(preview.image(), after, difference);
      EXPECT_EQ(cv::countNonZero(difference.reshape(1)), 0)
          << "reference " << reference << ", " << threads << " threads";
    }
  }
  PreviewColourer none;  // no known cell: an empty merged grid, an empty image
  const OccupancyGrid unknown(GridGeometry(0.05, {40, 30}));
  EXPECT_EQ(Composite({{&unknown, Pose2()}}, 0.05, FusionMode::kLogOdds, 1, -1, &none).width(), 0);
  EXPECT_TRUE(none.image().empty());
}

TEST(ColourPreview, ColoursEachMapAndPutsTheHighestRowOnTop) {
  // a: 4 x 3 free cells at the origin with its top-left cell occupied; b: the same size 1 m to the
  // right with its bottom-right cell occupied. Merged: 16 x 5 cells with the margin.
  OccupancyGrid a(GridGeometry(0.1, {4, 3}), CellState::kFree);
  OccupancyGrid b(GridGeometry(0.1, {4, 3}), CellState::kFree);
  a.set({0, 2}, CellState::kOccupied);
  b.set({3, 0}, CellState::kOccupied);
  const std::vector<CompositeInput> inputs = {{&a, Pose2()}, {&b, Pose2(1.0, 0.0, 0.0)}};
  const OccupancyGrid merged = Composite(inputs, 0.1);
  ASSERT_EQ(merged.width(), 16);
  ASSERT_EQ(merged.height(), 5);
  const cv::Mat3b image = ColourPreview(inputs, merged);
  ASSERT_EQ(image.rows, 5);
  ASSERT_EQ(image.cols, 16);
  // a's occupied cell is merged (1, 3): image row 5 - 1 - 3 = 1. b's is merged (14, 1): row 3.
  EXPECT_EQ(image(1, 1), PaletteColour(0));
  EXPECT_EQ(image(3, 14), PaletteColour(1));
  EXPECT_NE(PaletteColour(0), PaletteColour(1));
  EXPECT_EQ(image(3, 1)[0], image(3, 2)[0]);  // bottom-left of a is free like its neighbour
  EXPECT_EQ(image(0, 0), kPreviewUnknown);    // margin
  EXPECT_EQ(image(2, 7), kPreviewUnknown);    // the gap between the maps
  const cv::Vec3b free_a = image(2, 2), free_b = image(2, 12);
  EXPECT_NE(free_a, free_b);     // free cells tinted per map
  for (int c = 0; c < 3; ++c) {  // light: at least 0.8 x 245 = 196 in every channel
    EXPECT_GE(free_a[c], 196);
    EXPECT_GE(free_b[c], 196);
  }
}

TEST(ColourPreview, OverlapBlendsAndPaletteColoursAreDistinct) {
  OccupancyGrid a(GridGeometry(0.1, {3, 3}), CellState::kFree);
  a.set({1, 1}, CellState::kOccupied);
  const std::vector<CompositeInput> inputs = {{&a, Pose2()}, {&a, Pose2()}, {&a, Pose2()}};
  const OccupancyGrid merged = Composite(inputs, 0.1);
  const cv::Mat3b image = ColourPreview(inputs, merged);
  const cv::Vec3b mean =
      (cv::Vec3d(PaletteColour(0)) + cv::Vec3d(PaletteColour(1)) + cv::Vec3d(PaletteColour(2))) /
      3.0;
  EXPECT_EQ(image(merged.height() - 1 - 2, 2), mean);  // occupied cell (1, 1) + margin (1, 1)
  for (int k = 0; k < 10; ++k) {
    EXPECT_NE(PaletteColour(k), kPreviewUnknown);
    EXPECT_NE(PaletteColour(k), kPreviewFree);
    for (int l = 0; l < k; ++l) EXPECT_NE(PaletteColour(k), PaletteColour(l)) << k << " " << l;
  }
  EXPECT_EQ(PaletteColour(10), PaletteColour(0));  // cycles
}

}  // namespace
}  // namespace fleetmerge
