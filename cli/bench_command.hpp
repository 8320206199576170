// `fleetmerge bench`: experiments on case folders with ground truth (truth.yaml).
//   bench cut-fleet MAP.yaml DIR [--robots K] [--seed S]: a case cut from one building map
//       (sim/cut_fleet_case.hpp): robot maps, truth.yaml, job.yaml.
//   bench sampling CASE_DIR [--trials N] [--seed S] [--out DIR] [--ours]: the paper's sampling
//   experiment
//       (sim/sampling_experiment.hpp); writes DIR/sampling_trials.csv (one row per setting
//       and trial), DIR/sampling_summary.csv (one row per setting) and DIR/sampling.png, and
//       prints the summary.
#pragma once

#include <cstdint>
#include <filesystem>
#include <iosfwd>

namespace fleetmerge {

struct CutFleetCommand {
  std::filesystem::path map_yaml;
  std::filesystem::path out_dir;
  int robots = 4;
  std::uint32_t seed = 1;
};

struct SamplingBenchCommand {
  std::filesystem::path case_dir;
  std::filesystem::path out_dir;  // default: CASE_DIR/sampling
  int trials = 100;
  std::uint32_t seed = 1;
  long long min_overlap_cells = 2000;
  bool quiet = false;
  bool ours = false;  // our pipeline (2-D correlation + refinement) instead of the paper's
};

int RunCutFleetCommand(const CutFleetCommand& command, std::ostream& out);
int RunSamplingBenchCommand(const SamplingBenchCommand& command, std::ostream& out,
                            std::ostream& err);

}  // namespace fleetmerge
