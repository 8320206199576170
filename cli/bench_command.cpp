#include "cli/bench_command.hpp"

#include <iomanip>
#include <ostream>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/map_io.hpp"
#include "io/truth_file.hpp"
#include "sim/cut_fleet_case.hpp"
#include "sim/sampling_experiment.hpp"
#include "sim/sampling_plot.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;

int RunCutFleetCommand(const CutFleetCommand& command, std::ostream& out) {
  const LoadedMap building = LoadMap(command.map_yaml);
  // The case's files never overwrite the building map (kept in the case folder as robot1.pgm).
  const std::vector<fs::path> inputs = {command.map_yaml, building.metadata.image_path};
  const GroundTruth truth = WriteCutFleetCase(building.grid, command.map_yaml.stem().string(),
                                              command.map_yaml.generic_string(), command.robots,
                                              command.seed, command.out_dir, {}, inputs);
  out << "wrote " << truth.maps.size() << " maps, truth.yaml and job.yaml to "
      << command.out_dir.string() << " (" << truth.overlaps.size()
      << " overlapping pairs); merge with: fleetmerge merge "
      << (command.out_dir / "job.yaml").string() << "\n";
  return 0;
}

int RunSamplingBenchCommand(const SamplingBenchCommand& command, std::ostream& out,
                            std::ostream& err) {
  const fs::path truth_yaml = command.case_dir / "truth.yaml";
  const GroundTruth truth = LoadTruth(truth_yaml);
  std::vector<OccupancyGrid> grids;
  for (const TruthMap& map : truth.maps) grids.push_back(LoadMap(map.file).grid);
  std::vector<const OccupancyGrid*> pointers;
  for (const OccupancyGrid& g : grids) pointers.push_back(&g);

  SamplingExperimentOptions options;
  options.trials = command.trials;
  options.seed = command.seed;
  options.min_overlap_cells = command.min_overlap_cells;
  if (command.ours) options.pair = PairOptions{};
  const std::vector<SamplingSetting> settings = PaperSamplingSettings();
  const auto progress = [&](int done, int total) {
    if (!command.quiet && (done % (total / 10 > 0 ? total / 10 : 1) == 0 || done == total)) {
      err << "sampling: " << done << "/" << total << "\n" << std::flush;
    }
  };
  const std::vector<SamplingTrial> trials =
      RunSamplingExperiment(truth, pointers, settings, options, progress);
  const std::vector<SamplingSummary> summary = SummarizeSampling(settings, trials);

  const fs::path out_dir =
      command.out_dir.empty() ? command.case_dir / "sampling" : command.out_dir;
  fs::create_directories(out_dir);
  std::ostringstream csv;
  csv << std::setprecision(9)
      << "setting,kept_fraction,trial,map_a,map_b,time_ms,best_omega,yaw_error_deg,"
         "displacement_cells,coarse\n";
  for (const SamplingTrial& t : trials) {
    const SamplingSetting& s = settings[t.setting];
    csv << s.Label() << "," << s.KeptFraction() << "," << t.trial << "," << t.a << "," << t.b << ","
        << t.time_ms << "," << t.best_omega << "," << t.yaw_error_deg << "," << t.displacement_cells
        << "," << (t.coarse ? 1 : 0) << "\n";
  }
  WriteFileAtomically(out_dir / "sampling_trials.csv", csv.str());

  std::ostringstream table;
  table << std::setprecision(6)
        << "setting,kept_fraction,mean_time_ms,median_time_ms,mean_omega,min_omega,max_omega,"
           "success_rate,"
           "median_displacement_cells\n";
  for (const SamplingSummary& s : summary) {
    table << s.setting.Label() << "," << s.setting.KeptFraction() << "," << s.mean_time_ms << ","
          << s.median_time_ms << "," << s.mean_omega << "," << s.min_omega << "," << s.max_omega
          << "," << s.success_rate << "," << s.median_displacement_cells << "\n";
  }
  WriteFileAtomically(out_dir / "sampling_summary.csv", table.str());
  const std::string title = std::string(command.ours ? "Our pipeline" : "Paper's pipeline") +
                            ", sampling (IV-B): " + command.case_dir.string() + ", " +
                            std::to_string(command.trials) + " trials";
  SaveImage(DrawSamplingPlot(summary, title), out_dir / "sampling.png");

  out << std::left << std::setw(12) << "setting" << std::right << std::setw(8) << "kept"
      << std::setw(10) << "med.ms" << std::setw(8) << "omega" << std::setw(8) << "min"
      << std::setw(8) << "max" << std::setw(9) << "right%" << std::setw(12) << "med.displ"
      << "\n";
  for (const SamplingSummary& s : summary) {
    out << std::left << std::setw(12) << s.setting.Label() << std::right << std::fixed
        << std::setprecision(3) << std::setw(8) << s.setting.KeptFraction() << std::setprecision(2)
        << std::setw(10) << s.median_time_ms << std::setprecision(3) << std::setw(8) << s.mean_omega
        << std::setw(8) << s.min_omega << std::setw(8) << s.max_omega << std::setprecision(0)
        << std::setw(9) << 100.0 * s.success_rate << std::setprecision(2) << std::setw(12)
        << s.median_displacement_cells << "\n";
  }
  out.unsetf(std::ios::fixed);
  out << "wrote " << (out_dir / "sampling_trials.csv").string() << ", sampling_summary.csv, "
      << "sampling.png\n";
  return 0;
}

}  // namespace fleetmerge
