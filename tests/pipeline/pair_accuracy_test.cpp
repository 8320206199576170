// Ground truth on real maps: two overlapping parts cut from one map, the second re-framed by a
// seeded random rigid motion and resampled (sim/ground_truth_pair.hpp). The best hypothesis
// must be within 1 degree and 3 cells (mean displacement of b's walls) in >= 95 % of the trials
// per map; the fine rate (0.25 degree, 1 cell) is asserted at >= 80 %. CI runs the first 30
// trials of each map (its time budget); FLEETMERGE_FULL_ACCURACY=1 runs the 100 that docs/accuracy.md
// quotes (the first 30 are the same trials).
//
// FLEETMERGE_ACCURACY_METHOD=spectra or =spectra-unrefined runs the same trials with the paper's
// X/Y-spectra translation (with or without our refinement) to compare the methods; the printed
// rates are the measurement (the assertions hold only for the default).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "core/resample.hpp"
#include "io/map_io.hpp"
#include "pipeline/pair_merge.hpp"
#include "sim/ground_truth_pair.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

// Trials per map: 30 by default, 100 with FLEETMERGE_FULL_ACCURACY=1.
int TrialsPerMap() {
  const char* full = std::getenv("FLEETMERGE_FULL_ACCURACY");
  return full != nullptr && std::string(full) == "1" ? 100 : 30;
}

// Trials 0..5 cover the special angles; the rest are uniform in [-pi, pi).
double TrialYaw(int trial, std::mt19937& rng) {
  const double special[] = {0.0, M_PI / 2, M_PI, -M_PI / 2, M_PI - 1e-4, -M_PI + 1e-4};
  if (trial < 6) return special[trial];
  return std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
}

struct Tally {
  int coarse = 0, fine = 0, trials = 0;
  std::vector<double> yaw_errors_deg, displacement_cells;
};

PairOptions MethodUnderTest() {
  PairOptions options;
  const char* method = std::getenv("FLEETMERGE_ACCURACY_METHOD");
  const std::string name = method != nullptr ? method : "";
  if (name.rfind("spectra", 0) == 0) {
    options.hypotheses.translation.method = TranslationMethod::kXySpectra;
  }
  if (name == "spectra-unrefined" || name == "correlation-unrefined") options.refine = false;
  return options;
}

Tally RunTrials(const OccupancyGrid& building, std::uint32_t seed, int trials) {
  const PairOptions options = MethodUnderTest();
  std::mt19937 rng(seed);
  Tally tally;
  for (int k = 0; k < trials; ++k) {
    const double yaw = TrialYaw(k, rng);
    const GroundTruthPair pair = CutPair(building, yaw, rng);
    const PairResult result = MergePair(pair.a, pair.b, options);
    ++tally.trials;
    if (result.hypotheses.empty()) continue;
    const PoseError e = ComparePoses(pair.b, result.hypotheses[0].T_a_b, pair.T_a_b);
    tally.yaw_errors_deg.push_back(e.yaw_deg);
    tally.displacement_cells.push_back(e.mean_displacement_cells);
    tally.coarse += e.yaw_deg <= 1.0 && e.mean_displacement_cells <= 3.0;
    tally.fine += e.yaw_deg <= 0.25 && e.mean_displacement_cells <= 1.0;
  }
  return tally;
}

double Median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

class PairAccuracy : public ::testing::TestWithParam<const char*> {};

TEST_P(PairAccuracy, BestHypothesisWithinOneDegreeAndThreeCells) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const LoadedMap map = LoadMap(*testing::SharedMapsDir() / GetParam());
  // FLEETMERGE_TEST_SCALE (sanitizer build): fewer trials, never fewer than the 6 special angles.
  const Tally t = RunTrials(map.grid, 42, testing::ScaledCount(TrialsPerMap(), 6));
  std::printf(
      "[ accuracy ] %-24s coarse (1 deg, 3 cells) %d/%d, fine (0.25 deg, 1 cell) %d/%d, "
      "median yaw error %.3f deg, median displacement %.3f cells\n",
      GetParam(), t.coarse, t.trials, t.fine, t.trials, Median(t.yaw_errors_deg),
      Median(t.displacement_cells));
  EXPECT_GE(t.coarse * 100, 95 * t.trials) << "95 % within 1 degree and 3 cells";
  EXPECT_GE(t.fine * 100, 80 * t.trials) << "fine-tolerance target: 80 % of true pairs";
}

INSTANTIATE_TEST_SUITE_P(RealMaps, PairAccuracy,
                         ::testing::Values("intel_lab.yaml", "willow-full-0.05.yaml",
                                           "aces3_austin.yaml", "mit_csail.yaml",
                                           "gdc_floor1_full.yaml", "stata_basement.yaml"),
                         [](const auto& info) {
                           std::string name = info.param;
                           name = name.substr(0, name.find('.'));
                           std::replace_if(
                               name.begin(), name.end(), [](char c) { return !std::isalnum(c); },
                               '_');
                           return name;
                         });

TEST(PairAccuracy, DifferentResolutionsAreComparedAtTheFinerOne) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const LoadedMap map = LoadMap(*testing::SharedMapsDir() / "intel_lab.yaml");
  std::mt19937 rng(7);
  for (int k = 0; k < 10; ++k) {
    const GroundTruthPair pair = CutPair(map.grid, TrialYaw(k + 6, rng), rng);
    const OccupancyGrid b_coarse = ResampleToResolution(pair.b, 0.10);
    const PairResult result = MergePair(pair.a, b_coarse, PairOptions{});
    ASSERT_TRUE(result.resampled);
    EXPECT_DOUBLE_EQ(result.resolution_m, 0.05);
    ASSERT_FALSE(result.hypotheses.empty());
    const PoseError e = ComparePoses(pair.b, result.hypotheses[0].T_a_b, pair.T_a_b);
    // b lost half its detail, so the coarse tolerance is measured in b's new 0.10 m cells.
    EXPECT_LE(e.yaw_deg, 1.0) << "trial " << k;
    EXPECT_LE(e.mean_displacement_cells, 3.0 * 2.0) << "trial " << k;
  }
}

// Section III-D sampling of the translation search's points must not cost the pose. Every k-th
// point of a row-major list can drop whole walls (aliasing); when b's open space was taken from
// the sampled walls, such a wall's pixels turned open and the true pose was penalised: with every
// 8th point the bench sampling experiment found it in 0 of 100 trials (all points: 96).
TEST(PairAccuracy, SampledTranslationPointsStillFindTheTruePose) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const LoadedMap map = LoadMap(*testing::SharedMapsDir() / "intel_lab.yaml");
  for (const char* spec : {"every:8", "random:0.125"}) {
    PairOptions options;
    if (std::string(spec) == "every:8") {
      options.hypotheses.spectra_sampling = {SamplingMode::kEveryKth, 1.0, 8, 0};
    } else {
      options.hypotheses.spectra_sampling = {SamplingMode::kRandomFraction, 0.125, 1, 3};
    }
    std::mt19937 rng(21);
    int coarse = 0;
    const int trials = testing::ScaledCount(10, 4);
    for (int k = 0; k < trials; ++k) {
      const GroundTruthPair pair = CutPair(map.grid, TrialYaw(k + 6, rng), rng);
      const PairResult result = MergePair(pair.a, pair.b, options);
      if (result.hypotheses.empty()) continue;
      const PoseError e = ComparePoses(pair.b, result.hypotheses[0].T_a_b, pair.T_a_b);
      coarse += e.yaw_deg <= 1.0 && e.mean_displacement_cells <= 3.0;
    }
    std::printf("[ accuracy ] intel_lab, translation points %s: coarse %d/%d\n", spec, coarse,
                trials);
    EXPECT_GE(coarse * 10, 8 * trials) << spec;
  }
}

}  // namespace
}  // namespace fleetmerge
