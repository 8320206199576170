// Maps of different buildings must score a clearly lower best omega than true pairs, so that a
// threshold can reject them. The test measures both on real maps and states the margin found.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <random>

#include "io/map_io.hpp"
#include "pipeline/pair_merge.hpp"
#include "sim/ground_truth_pair.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

const char* const kBuildings[] = {"intel_lab.yaml", "willow-full-0.05.yaml", "aces3_austin.yaml",
                                  "mit_csail.yaml", "gdc_floor1_full.yaml"};

double BestOmega(const OccupancyGrid& a, const OccupancyGrid& b) {
  const PairResult r = MergePair(a, b, PairOptions{});
  return r.hypotheses.empty() ? 0.0 : r.hypotheses[0].omega;
}

TEST(OmegaMargin, DifferentBuildingsScoreClearlyBelowTruePairs) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  std::vector<GroundTruthPair> pairs;
  std::mt19937 rng(3);
  // The sanitizer build (FLEETMERGE_TEST_SCALE) takes the first buildings only: the same pairs,
  // a subset, so its margin is never smaller than the full test's.
  const int buildings = testing::ScaledCount(5, 2);
  for (int n = 0; n < buildings; ++n) {
    const LoadedMap map = LoadMap(*testing::SharedMapsDir() / kBuildings[n]);
    for (int k = 0; k < 4; ++k) {
      pairs.push_back(CutPair(map.grid, std::uniform_real_distribution<double>(-3, 3)(rng), rng));
    }
  }
  double min_true = 1.0, max_false = 0.0;
  for (const auto& p : pairs) min_true = std::min(min_true, BestOmega(p.a, p.b));
  // Part a of one building against part b of every other building.
  const int per_building = 4;
  for (std::size_t i = 0; i < pairs.size(); i += per_building) {
    for (std::size_t j = 0; j < pairs.size(); j += per_building) {
      if (i == j) continue;
      max_false = std::max(max_false, BestOmega(pairs[i].a, pairs[j + 1].b));
    }
  }
  std::printf(
      "[ omega ] true pairs: min best omega %.3f; different buildings: max best omega "
      "%.3f; margin %.3f\n",
      min_true, max_false, min_true - max_false);
  EXPECT_GT(min_true - max_false, 0.05);
}

}  // namespace
}  // namespace fleetmerge
