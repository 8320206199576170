// Octree speed for a tree of about one million leaves: floor estimate + floor-plan projection
// (target: under 1 s), and the merged octree: one input moved by (x, y, yaw, z) resampled into a
// new tree with OctoMap's update rule, then written as .bt (atomically). Run:
//   ./build/tests/benchmarks/octree_benchmark --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one command line)
// The tree is a synthetic office (octree/synthetic_octree.hpp) of 27 x 19 m at 5 cm, walls and
// free space 2.5 m high, floor, ceiling and low clutter; its size is printed on stderr.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>

#include "io/octree_io.hpp"
#include "octree/floor_height.hpp"
#include "octree/octree_merge.hpp"
#include "octree/octree_projection.hpp"
#include "octree/synthetic_octree.hpp"
#include "sim/synthetic_office.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

const octomap::OcTree& MillionLeafTree() {
  static const std::unique_ptr<octomap::OcTree> tree = [] {
    OfficeOptions office;
    office.width_m = 27.0;
    office.height_m = 19.0;
    office.clutter_per_room = 4;
    auto t = ExtrudeFloorPlan(GenerateOfficeFloor(office, 7));
    std::fprintf(stderr, "tree: %zu leaves, %zu nodes, resolution %.2f m\n", t->getNumLeafNodes(),
                 t->size(), t->getResolution());
    return t;
  }();
  return *tree;
}

void BM_FloorHeight(benchmark::State& state) {
  const octomap::OcTree& tree = MillionLeafTree();
  for (auto _ : state) benchmark::DoNotOptimize(EstimateFloorHeight(tree));
}
BENCHMARK(BM_FloorHeight)->Unit(benchmark::kMillisecond);

// What a job pays per octree after loading: floor estimate + projection.
void BM_Projection(benchmark::State& state) {
  const octomap::OcTree& tree = MillionLeafTree();
  for (auto _ : state) benchmark::DoNotOptimize(ProjectOctree(tree, OctreeOptions{}));
}
BENCHMARK(BM_Projection)->Unit(benchmark::kMillisecond);

void BM_LoadBt(benchmark::State& state) {
  const auto path = testing::MakeTempDir("octree_benchmark_load") / "tree.bt";
  SaveOctree(MillionLeafTree(), path);
  state.counters["file_MB"] = double(std::filesystem::file_size(path)) / 1e6;
  for (auto _ : state) benchmark::DoNotOptimize(LoadOctree(path));
}
BENCHMARK(BM_LoadBt)->Unit(benchmark::kMillisecond);

// The merged octree of a component holding this tree, moved by a pose with a 0.5 rad yaw:
// resampling + OctoMap's update + pruning, then the atomic .bt write.
void BM_MergedOctree(benchmark::State& state) {
  const octomap::OcTree& tree = MillionLeafTree();
  const auto path = testing::MakeTempDir("octree_benchmark_merge") / "merged_0.bt";
  const OctreePose T{Pose2(3.2, -1.7, 0.5), 0.37};
  for (auto _ : state) {
    const auto merged = MergeOctrees({{&tree, T}}, tree.getResolution());
    state.counters["merged_leaves"] = double(merged->getNumLeafNodes());
    SaveOctree(*merged, path);
  }
}
BENCHMARK(BM_MergedOctree)->Unit(benchmark::kMillisecond);

void BM_WriteBt(benchmark::State& state) {
  const auto path = testing::MakeTempDir("octree_benchmark_write") / "tree.bt";
  for (auto _ : state) SaveOctree(MillionLeafTree(), path);
}
BENCHMARK(BM_WriteBt)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fleetmerge

BENCHMARK_MAIN();
