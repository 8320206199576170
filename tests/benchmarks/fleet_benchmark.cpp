// End to end fleet merging of 8 maps of about 600 x 600 cells: load (PGM + YAML), all 28 pairs,
// pose graph, compositing and writing, on all cores. Run:
//   ./build/tests/benchmarks/fleet_benchmark --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one command line)
// The maps are cut from willow-full-0.05 (1165 x 945 cells) in ../shared as 8 robots (4 x 2 tiles
// grown by 30 %, each re-framed at random), or from a synthetic office without it; they are
// written once to a temporary folder so that loading is timed too.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <random>
#include <sstream>

#include "cli/merge_command.hpp"
#include "cli/process_memory.hpp"
#include "cli/process_threads.hpp"
#include "io/map_io.hpp"
#include "io/png_image.hpp"
#include "job/job.hpp"
#include "pipeline/composite.hpp"
#include "pipeline/pair_cache.hpp"
#include "pipeline/preview.hpp"
#include "sim/ground_truth_pair.hpp"
#include "sim/synthetic_office.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

const Job& EightMapJob() {
  static const Job job = [] {
    OccupancyGrid building;
    if (const auto dir = testing::SharedMapsDir()) {
      building = LoadMap(*dir / "willow-full-0.05.yaml").grid;
    } else {
      OfficeOptions office;
      office.width_m = 58.0;
      office.height_m = 47.0;
      building = GenerateOfficeFloor(office, 3);
    }
    std::mt19937 rng(2);
    const GroundTruthFleet fleet = CutFleet(building, 8, rng);
    Job j;
    j.name = "bench";
    const auto dir = testing::MakeTempDir("fleet_benchmark");
    j.output_dir = dir / "out";
    for (std::size_t m = 0; m < fleet.maps.size(); ++m) {
      const auto path = dir / ("robot_" + std::to_string(m) + ".yaml");
      SaveMap(fleet.maps[m], path);
      j.maps.push_back(
          {path.stem().string(), path, path, /*topic=*/"", false, Pose2(), std::nullopt});
      std::fprintf(stderr, "robot_%zu: %d x %d cells\n", m, fleet.maps[m].width(),
                   fleet.maps[m].height());
    }
    j.reference = j.maps.front().name;
    return j;
  }();
  return job;
}

void BM_MergeEightMaps(benchmark::State& state) {
  Job job = EightMapJob();
  job.options.threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    std::ostringstream out, err;
    if (RunJobs({job}, /*quiet=*/true, out, err) != 0) state.SkipWithError(err.str().c_str());
  }
  state.SetLabel(std::to_string(state.range(0)) + " thread(s)");
}
BENCHMARK(BM_MergeEightMaps)->Arg(2)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// The eight maps as the job loads them, for the benchmarks of single stages.
const std::vector<OccupancyGrid>& EightMaps() {
  static const std::vector<OccupancyGrid> maps = [] {
    std::vector<OccupancyGrid> loaded;
    for (const JobMap& m : EightMapJob().maps) loaded.push_back(LoadMap(m.path).grid);
    return loaded;
  }();
  return maps;
}

// The re-run cache's key of one map (pipeline/pair_cache.hpp: its geometry and every cell through
// io/content_hash.hpp), which a job with --cache computes for each of its maps; bytes/s in the
// output. The map: the eight-map job's first.
void BM_MapDigest(benchmark::State& state) {
  const OccupancyGrid& map = EightMaps().front();
  for (auto _ : state) benchmark::DoNotOptimize(MapDigest(map));
  state.SetBytesProcessed(state.iterations() * map.width() * map.height());
}
BENCHMARK(BM_MapDigest)->Unit(benchmark::kMicrosecond);

// Compositing and the colour preview of the eight maps on one thread, each turned by a yaw of
// its own (0.7 rad apart; the first at identity, as a reference map is): the sampling of every
// input at every merged cell that `merge`'s composite stage does. /1: the preview coloured while
// compositing (PreviewColourer, as `merge` and `pair` do); /0: ColourPreview afterwards, which
// samples the inputs again (a job whose merged cells are not the compared ones).
void BM_CompositeAndPreview(benchmark::State& state) {
  const std::vector<OccupancyGrid>& maps = EightMaps();
  std::vector<CompositeInput> inputs;
  for (std::size_t k = 0; k < maps.size(); ++k) {
    inputs.push_back({&maps[k], Pose2(3.0 * k, -2.0 * k, 0.7 * k)});
  }
  const double resolution_m = maps.front().geometry().resolution_m();
  for (auto _ : state) {
    if (state.range(0) == 1) {
      PreviewColourer preview;
      benchmark::DoNotOptimize(
          Composite(inputs, resolution_m, FusionMode::kLogOdds, 1, 0, &preview));
      benchmark::DoNotOptimize(preview.image());
    } else {
      const OccupancyGrid merged = Composite(inputs, resolution_m, FusionMode::kLogOdds, 1, 0);
      benchmark::DoNotOptimize(ColourPreview(inputs, merged, 1));
    }
  }
}
BENCHMARK(BM_CompositeAndPreview)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// PNG encoding (io/png_image.hpp) of a site-sized preview on 1 and 2 threads (the argument): the
// eight maps' colour preview tiled to at least 4000 x 4000 pixels, RGB, as the preview of a site
// job (scripts/large_site_benchmark.sh) is; the largest file `merge` encodes. Bytes/s of pixels.
void BM_EncodePreviewPng(benchmark::State& state) {
  static const cv::Mat3b site_preview = [] {
    const std::vector<OccupancyGrid>& maps = EightMaps();
    std::vector<CompositeInput> inputs;
    for (std::size_t k = 0; k < maps.size(); ++k) {
      inputs.push_back({&maps[k], Pose2(3.0 * k, -2.0 * k, 0.7 * k)});
    }
    PreviewColourer preview;
    Composite(inputs, maps.front().geometry().resolution_m(), FusionMode::kLogOdds, 1, 0, &preview);
    const cv::Mat3b& tile = preview.image();
    cv::Mat3b tiled;
    cv::repeat(tile, (4000 + tile.rows - 1) / tile.rows, (4000 + tile.cols - 1) / tile.cols, tiled);
    std::fprintf(stderr, "preview: %d x %d pixels\n", tiled.cols, tiled.rows);
    return tiled;
  }();
  for (auto _ : state) {
    benchmark::DoNotOptimize(EncodePng(site_preview, static_cast<int>(state.range(0))));
  }
  state.SetBytesProcessed(state.iterations() * site_preview.total() * site_preview.elemSize());
  state.SetLabel(std::to_string(state.range(0)) + " thread(s)");
}
BENCHMARK(BM_EncodePreviewPng)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace fleetmerge

// As `fleetmerge merge` runs: the executable's allocator and thread settings
// (cli/process_memory.hpp, cli/process_threads.hpp).
int main(int argc, char** argv) {
  fleetmerge::KeepFreedMemoryForReuse();
  fleetmerge::RunOpenCvOnTheCallingThread();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
