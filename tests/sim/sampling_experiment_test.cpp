// The sampling experiment's bookkeeping: the paper's 40 settings; every setting solves the same
// problems (same pairs per trial); keeping every point by any mode gives the same answer; and the
// truth of each re-framed problem is right: our pipeline recovers it to within a cell, which a
// wrong truth could not match. Case: 4 robots cut from the Intel lab map (shared maps).
#include "sim/sampling_experiment.hpp"

#include <gtest/gtest.h>

#include <random>

#include "io/map_io.hpp"
#include "sim/cut_fleet_case.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

TEST(SamplingExperimentTest, PaperSettingsCoverFivePercentStepsAndKUpToTwenty) {
  const std::vector<SamplingSetting> settings = PaperSamplingSettings();
  ASSERT_EQ(settings.size(), 40u);
  EXPECT_EQ(settings[0].mode, SamplingMode::kRandomFraction);
  EXPECT_DOUBLE_EQ(settings[0].KeptFraction(), 0.05);
  EXPECT_DOUBLE_EQ(settings[19].KeptFraction(), 1.0);
  EXPECT_EQ(settings[20].Label(), "every:1");
  EXPECT_EQ(settings[39].Label(), "every:20");
  EXPECT_DOUBLE_EQ(settings[39].KeptFraction(), 0.05);
  EXPECT_EQ(settings[6].Label(), "random:0.35");
}

TEST(SamplingExperimentTest, SameProblemsForEverySettingAndTheTruthIsRecovered) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const OccupancyGrid building = LoadMap(*testing::SharedMapsDir() / "intel_lab.yaml").grid;
  const std::filesystem::path dir = testing::MakeTempDir("sampling_experiment");
  const GroundTruth truth = WriteCutFleetCase(building, "intel", "intel_lab.yaml", 4, 1, dir);
  std::vector<OccupancyGrid> grids;
  for (const TruthMap& map : truth.maps) grids.push_back(LoadMap(map.file).grid);
  std::vector<const OccupancyGrid*> pointers;
  for (const auto& g : grids) pointers.push_back(&g);

  const std::vector<SamplingSetting> settings = {{SamplingMode::kAll, 1.0, 1},
                                                 {SamplingMode::kRandomFraction, 1.0, 1},
                                                 {SamplingMode::kEveryKth, 1.0, 1},
                                                 {SamplingMode::kEveryKth, 1.0, 4}};
  SamplingExperimentOptions options;
  options.trials = 4;
  options.pair = PairOptions{};  // ours: 2-D correlation + refinement
  const std::vector<SamplingTrial> rows = RunSamplingExperiment(truth, pointers, settings, options);
  ASSERT_EQ(rows.size(), settings.size() * 4);
  int recovered = 0;
  for (int t = 0; t < 4; ++t) {
    const SamplingTrial& all = rows[t];
    EXPECT_NE(all.a, all.b);
    for (std::size_t s = 1; s < settings.size(); ++s) {
      const SamplingTrial& other = rows[s * 4 + t];
      EXPECT_EQ(other.trial, t);
      EXPECT_EQ(other.a, all.a);
      EXPECT_EQ(other.b, all.b);
      EXPECT_GT(other.time_ms, 0.0);
      if (s < 3) {  // every point kept: the same answer
        EXPECT_EQ(other.best_omega, all.best_omega);
        EXPECT_EQ(other.displacement_cells, all.displacement_cells);
      }
    }
    recovered += all.displacement_cells < 1.0 && all.yaw_error_deg < 0.25;
  }
  EXPECT_GE(recovered, 2);  // measured: 3 of 4 (a small diagonal overlap may fail)

  const std::vector<SamplingSummary> summary = SummarizeSampling(settings, rows);
  ASSERT_EQ(summary.size(), settings.size());
  EXPECT_DOUBLE_EQ(summary[0].success_rate, recovered / 4.0);
  EXPECT_LE(summary[0].min_omega, summary[0].mean_omega);
  EXPECT_LE(summary[0].mean_omega, summary[0].max_omega);
}

}  // namespace
}  // namespace fleetmerge
