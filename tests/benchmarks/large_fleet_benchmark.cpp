// Whole `fleetmerge merge` processes on simulated fleets in the ACES building (aces3_austin in
// ../shared, 820-1420 cell maps): the 8-robot case (seed 3, 100 m paths) and the large
// fleets of 32 and 100 robots (seed 7, default paths), on 2 threads. Each case is simulated
// once into a temporary folder by `fleetmerge simulate`; every repetition is one merge process,
// timed end to end (start-up, loading, all pairs, pose graph, compositing, writing), with the
// child's peak resident memory as the counter peak_rss_mb. Run:
//   ./build/tests/benchmarks/large_fleet_benchmark --benchmark_repetitions=3
//       --benchmark_report_aggregates_only=true   (one command line; 100 robots: ~5 minutes)
// --benchmark_filter=Aces/8 runs one case. With FLEETMERGE_BASELINE_EXE=/path/to/fleetmerge the
// same merges also run that executable (on the same simulated maps) for before/after.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "tests/benchmarks/child_process.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

struct FleetCase {
  int robots;
  int seed;
  double path_length_m;  // 0: simulate's default
};

// The case's job file, simulated on first use; empty when ../shared is absent.
std::string JobFile(const FleetCase& c) {
  static std::map<int, std::string> jobs;
  auto it = jobs.find(c.robots);
  if (it != jobs.end()) return it->second;
  std::string job;
  if (const auto maps = testing::SharedMapsDir()) {
    const auto dir =
        testing::MakeTempDir("large_fleet_benchmark") / ("aces" + std::to_string(c.robots));
    std::vector<std::string> argv = {FLEETMERGE_EXE,
                                     "simulate",
                                     dir.string(),
                                     "--building",
                                     (*maps / "aces3_austin.yaml").string(),
                                     "--robots",
                                     std::to_string(c.robots),
                                     "--seed",
                                     std::to_string(c.seed)};
    if (c.path_length_m > 0) {
      argv.push_back("--path-length");
      argv.push_back(std::to_string(c.path_length_m));
    }
    std::fprintf(stderr, "simulating %d robots in aces3_austin ...\n", c.robots);
    if (RunChild(argv).ok) job = (dir / "job.yaml").string();
  }
  jobs[c.robots] = job;
  return job;
}

void BM_Merge(benchmark::State& state, std::string exe, FleetCase c) {
  const std::string job = JobFile(c);
  if (job.empty()) {
    state.SkipWithError("../shared/data/maps is absent (or simulate failed): nothing to merge");
    return;
  }
  double peak_mb = 0.0;
  for (auto _ : state) {
    const ChildRun run = RunChild({exe, "merge", job, "--threads", "2", "--quiet"});
    if (!run.ok) state.SkipWithError(("merge failed: " + exe).c_str());
    peak_mb = std::max(peak_mb, run.peak_rss_mb);
  }
  state.counters["peak_rss_mb"] = peak_mb;
}

void RegisterFor(const std::string& label, const std::string& exe) {
  for (const FleetCase& c :
       {FleetCase{8, 3, 100.0}, FleetCase{32, 7, 0.0}, FleetCase{100, 7, 0.0}}) {
    benchmark::RegisterBenchmark(("Aces/" + std::to_string(c.robots) + "/" + label).c_str(),
                                 BM_Merge, exe, c)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime()
        ->Iterations(1);
  }
}

}  // namespace
}  // namespace fleetmerge

int main(int argc, char** argv) {
  return fleetmerge::RunExecutableBenchmarks(argc, argv, fleetmerge::RegisterFor);
}
