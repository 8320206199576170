// Speed of one pair of 530 x 530 cell maps (the paper's size, Section IV-B) with all points and
// with 5 / 20 / 50 % random sampling of the Hough transform and the translation points. Run:
//   ./build/tests/benchmarks/pair_benchmark --benchmark_repetitions=7
//       --benchmark_report_aggregates_only=true   (one command line)
// The maps are cut from the Intel lab map in ../shared (or a synthetic office without it); b is
// rotated by 37 degrees and shifted by (10, 7.5) m.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "core/hypothesis_generator.hpp"
#include "io/map_io.hpp"
#include "pipeline/composite.hpp"
#include "pipeline/pair_merge.hpp"
#include "sim/synthetic_office.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

constexpr int kSide = 530;

struct BenchPair {
  OccupancyGrid a, b;
};

const BenchPair& Pair() {
  static const BenchPair pair = [] {
    OccupancyGrid building;
    if (const auto dir = testing::SharedMapsDir()) {
      building = LoadMap(*dir / "intel_lab.yaml").grid;
    } else {
      std::fprintf(stderr, "shared maps absent: benchmarking a synthetic office instead\n");
      OfficeOptions office;
      office.width_m = office.height_m = 40.0;
      building = GenerateOfficeFloor(office, 1);
    }
    const double r = building.geometry().resolution_m();
    const cv::Rect box = cv::boundingRect(building.cells() != 0);
    const Eigen::Vector2d corner =
        building.geometry().T_map_grid() * Eigen::Vector2d(box.x * r, box.y * r);
    const GridGeometry window(r, {kSide, kSide});
    const Pose2 T_building_a(corner, 0.0);
    const Pose2 T_building_b = T_building_a * Pose2(10.0, 7.5, 37.0 * M_PI / 180.0);
    BenchPair p;
    p.a = SampleOnto({&building, T_building_a.inverse()}, window);
    p.b = SampleOnto({&building, T_building_b.inverse()}, window);
    return p;
  }();
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

}  // namespace
}  // namespace fleetmerge

BENCHMARK_MAIN();
