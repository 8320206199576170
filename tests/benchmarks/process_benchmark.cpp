// Whole `fleetmerge` processes, start-up included: `fleetmerge --help` (dynamic loading and
// static initialisation: what every command pays) and `fleetmerge pair` on the 530 x 530 pair of
// tests/benchmarks/bench_pair.hpp written as map files. Run:
//   ./build/tests/benchmarks/process_benchmark --benchmark_repetitions=20
//       --benchmark_report_aggregates_only=true --benchmark_enable_random_interleaving=true
// With FLEETMERGE_BASELINE_EXE=/path/to/older/fleetmerge the same benchmarks also run that
// executable, interleaved, for a before/after comparison in one run.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "io/map_io.hpp"
#include "tests/benchmarks/bench_pair.hpp"
#include "tests/benchmarks/child_process.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

// The pair as map_server files, written once.
const std::vector<std::string>& PairFiles() {
  static const std::vector<std::string> files = [] {
    const BenchPair pair = MakeBenchPair();
    const auto dir = testing::MakeTempDir("process_benchmark");
    SaveMap(pair.a, dir / "a.yaml");
    SaveMap(pair.b, dir / "b.yaml");
    return std::vector<std::string>{(dir / "a.yaml").string(), (dir / "b.yaml").string()};
  }();
  return files;
}

void BM_Process(benchmark::State& state, std::vector<std::string> argv) {
  if (argv.size() > 1 && argv[1] == "pair")
    argv.insert(argv.end(), PairFiles().begin(), PairFiles().end());
  for (auto _ : state) {
    if (!RunChild(argv).ok) state.SkipWithError(("failed: " + argv[0]).c_str());
  }
}

void RegisterFor(const std::string& label, const std::string& exe) {
  benchmark::RegisterBenchmark(("help/" + label).c_str(), BM_Process,
                               std::vector<std::string>{exe, "--help"})
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  benchmark::RegisterBenchmark(("pair_530/" + label).c_str(), BM_Process,
                               std::vector<std::string>{exe, "pair"})
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
}

}  // namespace
}  // namespace fleetmerge

int main(int argc, char** argv) {
  return fleetmerge::RunExecutableBenchmarks(argc, argv, fleetmerge::RegisterFor);
}
