// The whole `fleetmerge` command line: every subcommand, --help and --version
// (cli/all_commands.hpp).
#include "cli/all_commands.hpp"

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "cli/bench_command.hpp"
#include "cli/cli_options.hpp"
#include "cli/command_line.hpp"
#include "cli/demo_command.hpp"
#include "cli/eval_command.hpp"
#include "cli/example_command.hpp"
#include "cli/extract_command.hpp"
#include "cli/merge_command.hpp"
#include "cli/pair_command.hpp"
#include "cli/process_memory.hpp"
#include "cli/process_threads.hpp"
#include "cli/simulate_command.hpp"

namespace fleetmerge {

int RunAllCommands(int argc, char** argv) {
  CLI::App app;
  SetUpTopLevel(app);
  // `fleetmerge --version` and `fleetmerge version` print the same line.
  CLI::App* version_app = app.add_subcommand("version", "Print the version");

  PairCommand pair;
  CLI::App* pair_app = AddPairCommand(app, pair);

  // With job files, an option that a job key also sets applies to every job and one of --out's
  // map list is refused: each new option belongs in one of cli/merge_command.cpp's lists
  // (kJobKeyOptions, kMapListOptions), or it is dropped without a word.
  MergeCommand merge;
  CLI::App* merge_app =
      app.add_subcommand("merge", "Merge the maps of a fleet: job files, or maps with --out DIR");
  merge_app->add_option("inputs", merge.inputs, "job files (YAML), or maps (YAML, bags) with --out")
      ->required();
  merge_app
      ->add_option("--topic", merge.topics,
                   "with --out: read only these nav_msgs/OccupancyGrid topics from bags "
                   "(repeatable; default every map topic)")
      ->allow_extra_args(false);
  merge_app->add_option("--out", merge.out_dir, "treat the inputs as maps of one job, output here");
  merge_app->add_option("--reference", merge.reference, "with --out: the reference map's name");
  merge_app
      ->add_option("--fixed", merge.fixed_maps,
                   "with --out: NAME or NAME=X,Y,YAW: a fixed base map that never moves, at "
                   "this pose of its frame in the merged frame (default identity; "
                   "repeatable)")
      ->allow_extra_args(false);
  merge_app
      ->add_option("--initial-pose", merge.initial_poses,
                   "with --out: NAME=X,Y,YAW[,SIGMA_M,SIGMA_RAD]: a map's known start pose "
                   "in the merged frame (default sigmas 0.5 m, 0.1745 rad; repeatable)")
      ->allow_extra_args(false);
  merge_app
      ->add_option("--tf-parent", merge.tf_parent_frame,
                   "with --out: parent frame of the transforms written (transforms.launch*)")
      ->capture_default_str();
  merge_app
      ->add_option("--tf-child", merge.tf_child_frame,
                   "with --out: child frame of each map's transform; {name} is the map's name")
      ->capture_default_str();
  merge_app->add_option("--threads", merge.options.threads, "threads (0: all cores)")
      ->check(CLI::NonNegativeNumber);
  merge_app
      ->add_option("--omega-threshold", merge.options.omega_threshold,
                   "best omega a pair needs to become an edge")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  merge_app
      ->add_option("--octree-band-min", merge.options.octree.band_min_m,
                   "octrees: bottom of the floor plan's height band, metres above the floor")
      ->check(CLI::Range(-10.0, 10.0))
      ->capture_default_str();
  merge_app
      ->add_option("--octree-band-max", merge.options.octree.band_max_m,
                   "octrees: top of the floor plan's height band, metres above the floor")
      ->check(CLI::Range(-10.0, 10.0))
      ->capture_default_str();
  merge_app->add_flag("--quiet", merge.quiet, "no progress output");
  merge_app->add_flag("--force", merge.force,
                      "replace an output folder that holds the results of another job");
  merge_app
      ->add_option("--lock-wait", merge.lock_wait_s,
                   "seconds to wait for another job using the same output folder or cache "
                   "folder (0: fail at once)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  merge_app->add_option("--cache", merge.cache_dir,
                        "keep pairs' hypotheses and maps' preparations in this folder and reuse "
                        "them in re-runs (every job; a job file's 'cache' otherwise)");
  merge_app
      ->add_option("--cache-max-mb", merge.cache_max_mb,
                   "size bound of the cache folder in MiB (default " +
                       std::to_string(kDefaultCacheMaxMb) +
                       "; least recently used entries are evicted beyond)")
      ->check(CLI::Range(std::int64_t(1), kLargestCacheMaxMb));
  merge_app
      ->add_option(
          "--max-map-cells", merge.options.max_map_cells,
          "refuse map images (before decoding) and merged maps (before allocating) with more cells")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  AddMethodOptions(*merge_app, merge.options.pair);

  ExtractCommand extract;
  CLI::App* extract_app = app.add_subcommand(
      "extract", "Write each map topic's last map of ROS 1/ROS 2 bags as map_server YAML + PGM");
  extract_app->add_option("bags", extract.bags, "ROS 1 .bag files, ROS 2 bag folders, .db3, .mcap")
      ->required();
  extract_app->add_option("--out", extract.out_dir, "output folder")->required();
  extract_app
      ->add_option("--topic", extract.topics,
                   "only these nav_msgs/OccupancyGrid topics (repeatable)")
      ->allow_extra_args(false);

  ExampleCommand example;
  CLI::App* example_app = app.add_subcommand(
      "example", "Write two overlapping robot maps of a synthetic office with the true answer");
  example_app->add_option("dir", example.out_dir, "output folder")->required();
  example_app->add_option("--seed", example.seed, "random seed")->capture_default_str();
  example_app->add_flag("--octree", example.octree,
                        "two OctoMap octrees (.bt) of one storey, with truth.yaml and job.yaml");

  DemoCommand demo;
  CLI::App* demo_app = AddDemoCommand(app, demo);

  SimulateCommand simulate;
  CLI::App* simulate_app = AddSimulateCommand(app, simulate);

  EvalCommand eval;
  CLI::App* eval_app = app.add_subcommand(
      "eval", "Score a merge's report.json against a case's truth.yaml (poses, false merges)");
  eval_app->add_option("report", eval.report_json, "report.json written by `fleetmerge merge`")
      ->required();
  eval_app->add_option("truth", eval.truth_yaml, "truth.yaml of the case")->required();
  eval_app->add_flag("--json", eval.json, "print JSON instead of a table");
  eval_app
      ->add_option("--min-overlap-cells", eval.options.min_overlap_cells,
                   "pairs observing at least this many common cells truly overlap")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();

  CLI::App* bench_app =
      app.add_subcommand("bench", "Experiments on case folders with ground truth (truth.yaml)");
  bench_app->require_subcommand(1);
  CutFleetCommand cut;
  CLI::App* cut_app = bench_app->add_subcommand(
      "cut-fleet", "Cut a building map into K robot maps in random frames, with truth.yaml");
  cut_app->add_option("map", cut.map_yaml, "the building's map (map_server YAML)")->required();
  cut_app->add_option("dir", cut.out_dir, "output case folder")->required();
  cut_app->add_option("--robots", cut.robots, "number of robot maps")
      ->check(CLI::Range(1, 64))
      ->capture_default_str();
  cut_app->add_option("--seed", cut.seed, "random seed")->capture_default_str();
  SamplingBenchCommand sampling;
  CLI::App* sampling_app = bench_app->add_subcommand(
      "sampling", "The paper's sampling experiment (IV-B): random vs every k-th point");
  sampling_app->add_option("case", sampling.case_dir, "case folder with truth.yaml")->required();
  sampling_app->add_option("--trials", sampling.trials, "trials per setting")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  sampling_app->add_option("--seed", sampling.seed, "random seed")->capture_default_str();
  sampling_app->add_option("--out", sampling.out_dir, "output folder (default CASE/sampling)");
  sampling_app
      ->add_option("--min-overlap-cells", sampling.min_overlap_cells,
                   "pairs observing at least this many common cells truly overlap")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  sampling_app->add_flag("--quiet", sampling.quiet, "no progress output");
  sampling_app->add_flag("--ours", sampling.ours,
                         "our pipeline (2-D correlation + refinement) instead of the paper's "
                         "(X/Y spectra, no refinement)");

  if (const std::optional<int> exit_code = ParseCommandLine(app, argc, argv)) return *exit_code;
  if (version_app->parsed()) {
    std::cout << VersionLine() << "\n";
    return 0;
  }
  return RunReportingErrors([&] {
    if (demo_app->parsed()) return RunDemoCommand(demo, std::cout, std::cerr);
    if (merge_app->parsed()) {
      for (const CLI::Option* option : merge_app->get_options()) {
        if (option->count() > 0) merge.given.push_back(option->get_name());
      }
      return RunMergeCommand(merge, std::cout, std::cerr);
    }
    if (pair_app->parsed()) {
      ShareTheHeapBetweenThreads();
      return RunPairCommand(pair, std::cout);
    }
    if (extract_app->parsed()) return RunExtractCommand(extract, std::cout);
    if (example_app->parsed()) return RunExampleCommand(example, std::cout);
    if (simulate_app->parsed()) return RunSimulateCommand(simulate, std::cout);
    if (eval_app->parsed()) return RunEvalCommand(eval, std::cout);
    if (cut_app->parsed()) return RunCutFleetCommand(cut, std::cout);
    if (sampling_app->parsed()) return RunSamplingBenchCommand(sampling, std::cout, std::cerr);
    return 0;
  });
}

}  // namespace fleetmerge

extern "C" int fleetmerge_run_all_commands(int argc, char** argv) {
  // The executable set this for its own copy of OpenCV core (cli/CMakeLists.txt); the module
  // computes with the shared library's.
  fleetmerge::RunOpenCvOnTheCallingThread();
  return fleetmerge::RunAllCommands(argc, argv);
}
