// `fleetmerge simulate`'s library call (SimulateFleet) with default options: 4 robots in the
// default 30 x 20 m synthetic office, and 6 robots in the Intel lab from ../shared (skipped
// without it), on 1 thread and on all cores. Run:
//   ./build/tests/benchmarks/simulation_benchmark --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one command line)
#include <benchmark/benchmark.h>

#include "io/map_io.hpp"
#include "sim/simulation.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

void Simulate(benchmark::State& state, const SimulationBuilding& building, int robots) {
  SimulationOptions options;
  options.robots = robots;
  options.threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const SimulatedCase c = SimulateFleet(building, options);
    benchmark::DoNotOptimize(c.maps.data());
  }
}

void BM_Office4Robots(benchmark::State& state) {
  static const SimulationBuilding office = OfficeBuilding(1);
  Simulate(state, office, 4);
}
BENCHMARK(BM_Office4Robots)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_IntelLab6Robots(benchmark::State& state) {
  const auto dir = testing::SharedMapsDir();
  if (!dir) {
    state.SkipWithError("shared maps not found");
    return;
  }
  static const SimulationBuilding intel{LoadMap(*dir / "intel_lab.yaml").grid, "intel", "intel"};
  Simulate(state, intel, 6);
}
BENCHMARK(BM_IntelLab6Robots)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace fleetmerge

BENCHMARK_MAIN();
