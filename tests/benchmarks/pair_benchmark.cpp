// Speed of one pair of 530 x 530 cell maps (the paper's size, Section IV-B) with all points and
// with 5 / 20 / 50 % random sampling of the Hough transform and the translation points. Run:
//   ./build/tests/benchmarks/pair_benchmark --benchmark_repetitions=7
//       --benchmark_report_aggregates_only=true   (one command line)
// The maps: tests/benchmarks/bench_pair.hpp.
#include <benchmark/benchmark.h>

#include "core/acceptance_index.hpp"
#include "core/hypothesis_generator.hpp"
#include "io/map_io.hpp"
#include "pipeline/composite.hpp"
#include "pipeline/pair_merge.hpp"
#include "tests/benchmarks/bench_pair.hpp"

namespace fleetmerge {
namespace {

const BenchPair& Pair() {
  static const BenchPair pair = MakeBenchPair();
  return pair;
}

HypothesisOptions WithSampling(double fraction) {
  HypothesisOptions o;
  if (fraction < 1.0) {
    o.hough_sampling = {SamplingMode::kRandomFraction, fraction, 1, 1};
    o.spectra_sampling = {SamplingMode::kRandomFraction, fraction, 1, 2};
  }
  return o;
}

// Algorithm 1 as in the paper (hypotheses ranked by omega), our default translation search.
void BM_Hypotheses(benchmark::State& state) {
  const HypothesisOptions options = WithSampling(state.range(0) / 100.0);
  for (auto _ : state) benchmark::DoNotOptimize(GenerateHypotheses(Pair().a, Pair().b, options));
  state.SetLabel(std::to_string(state.range(0)) + " % of points");
}
BENCHMARK(BM_Hypotheses)->Arg(100)->Arg(50)->Arg(20)->Arg(5)->Unit(benchmark::kMillisecond);

// The paper's X/Y-spectra translation instead of 2-D correlation.
void BM_HypothesesXySpectra(benchmark::State& state) {
  HypothesisOptions options = WithSampling(state.range(0) / 100.0);
  options.translation.method = TranslationMethod::kXySpectra;
  for (auto _ : state) benchmark::DoNotOptimize(GenerateHypotheses(Pair().a, Pair().b, options));
}
BENCHMARK(BM_HypothesesXySpectra)->Arg(100)->Arg(5)->Unit(benchmark::kMillisecond);

// What `fleetmerge pair` runs: hypotheses plus local refinement and re-ranking.
void BM_PairWithRefinement(benchmark::State& state) {
  PairOptions options;
  options.hypotheses = WithSampling(state.range(0) / 100.0);
  for (auto _ : state) benchmark::DoNotOptimize(MergePair(Pair().a, Pair().b, options));
}
BENCHMARK(BM_PairWithRefinement)->Arg(100)->Arg(20)->Unit(benchmark::kMillisecond);

// The same pair on N threads, as `fleetmerge pair` runs it on an N-core machine (one thread is
// BM_PairWithRefinement/100; the process benchmark's pair_530 adds start-up, loading and output).
void BM_PairOnThreads(benchmark::State& state) {
  const PairOptions options;
  const int threads = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(MergePair(Pair().a, Pair().b, options, threads));
}
BENCHMARK(BM_PairOnThreads)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Omega (Eq. 1) of the pair under its true pose at full resolution: the count every hypothesis
// and every refined candidate pays.
void BM_Omega(benchmark::State& state) {
  const OccupancyGrid& a = Pair().a;
  const OccupancyGrid& b = Pair().b;
  const Pose2 T_a_b(10.0, 7.5, 37.0 * M_PI / 180.0);
  const Pose2 T_ga_gb = CellPoseFromMapPose(a.geometry(), b.geometry(), T_a_b);
  const RowSpans spans = KnownRowSpans(b);
  for (auto _ : state) benchmark::DoNotOptimize(CountAgreement(a, b, T_ga_gb, 1, &spans));
}
BENCHMARK(BM_Omega)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace fleetmerge

BENCHMARK_MAIN();
