// The paper's sampling experiment (Section IV-B, Fig. 6 and 7), on any case with ground truth:
// per trial two maps of one building that truly overlap are picked at random, the first is
// rotated and translated at random (Reframe), and the paper's pipeline (Hough rotation, X/Y
// spectra translation, omega ranking, no refinement) runs with each sampling setting applied to
// both the Hough transform and the X/Y spectra: random fractions 5 %..100 % and every k-th point
// for k = 1..20. Recorded per trial: time, best omega (what the paper plots) and the pose error of
// the best hypothesis against the truth (which the paper could not measure). As in the paper,
// every setting solves the same problems (seeded).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/point_sampling.hpp"
#include "io/truth_file.hpp"
#include "pipeline/pair_merge.hpp"

namespace fleetmerge {

struct SamplingSetting {
  SamplingMode mode = SamplingMode::kAll;
  double fraction = 1.0;  // kRandomFraction
  int step = 1;           // kEveryKth
  double KeptFraction() const { return mode == SamplingMode::kEveryKth ? 1.0 / step : fraction; }
  std::string Label() const;  // "random:0.35", "every:7"
};

// Random 5 %, 10 %, ..., 100 %, then every k-th point for k = 1..20.
std::vector<SamplingSetting> PaperSamplingSettings();

struct SamplingExperimentOptions {
  int trials = 100;
  std::uint32_t seed = 1;
  long long min_overlap_cells = 2000;  // pairs that truly overlap (truth.yaml `cells`)
  double max_offset_m = 10.0;          // of the first map's random re-framing, per axis
  // The pipeline; its Hough and spectra sampling are replaced by each setting's.
  PairOptions pair = PaperPairOptions();
  static PairOptions PaperPairOptions();  // X/Y spectra translation, no refinement
};

struct SamplingTrial {
  int setting = 0;  // index into the settings
  int trial = 0;
  std::string a, b;  // map names
  double time_ms = 0.0;
  double best_omega = 0.0;                                 // 0 when no hypothesis
  double yaw_error_deg = 180.0, displacement_cells = 1e9;  // of the best hypothesis
  bool coarse = false;                                     // within 1 degree and 3 cells
};

using SamplingProgressFn = std::function<void(int done, int total)>;

// `grids[i]` is truth.maps[i] loaded. Throws fleetmerge::Error when no pair of maps truly
// overlaps. Rows ordered by setting, then trial.
std::vector<SamplingTrial> RunSamplingExperiment(const GroundTruth& truth,
                                                 const std::vector<const OccupancyGrid*>& grids,
                                                 const std::vector<SamplingSetting>& settings,
                                                 const SamplingExperimentOptions& options,
                                                 const SamplingProgressFn& progress = {});

// Per setting: mean and median time, omega mean / min / max, coarse success share, median
// displacement.
struct SamplingSummary {
  SamplingSetting setting;
  double mean_time_ms = 0.0, median_time_ms = 0.0;
  double mean_omega = 0.0, min_omega = 0.0, max_omega = 0.0;
  double success_rate = 0.0;
  double median_displacement_cells = 0.0;
};
std::vector<SamplingSummary> SummarizeSampling(const std::vector<SamplingSetting>& settings,
                                               const std::vector<SamplingTrial>& trials);

}  // namespace fleetmerge
