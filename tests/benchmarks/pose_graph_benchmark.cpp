// The fleet's pose graph solved with each linear solver (refine/pose_graph.hpp, PoseGraphSolver)
// on seeded synthetic fleets: N maps spread over a building, an edge between two maps where they
// are among the given share of closest pairs (maps overlap their neighbours), each measured with
// a pair's noise (0.05 m, 0.3 deg). The 33- and 100-robot ACES jobs of
// scripts/cache_rerun_benchmark.sh have 64 % and 63 % of their pairs as edges. Run (both solvers
// interleaved; docs/speed.md):
//   ./build/tests/benchmarks/pose_graph_benchmark --benchmark_repetitions=5
//       --benchmark_enable_random_interleaving=true --benchmark_report_aggregates_only=true
// Arguments: maps, edges as a percentage of all pairs, solver (0 automatic, 1 sparse Cholesky,
// 2 dense Schur).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "refine/pose_graph.hpp"

namespace fleetmerge {
namespace {

struct SyntheticGraph {
  std::vector<std::optional<Pose2>> initial;  // the spanning tree's poses
  std::vector<PoseGraphEdge> edges;
};

SyntheticGraph MakeGraph(int maps, int edge_percent) {
  std::mt19937 rng(7);
  // Maps' frames spread over a 100 x 60 m building, at any yaw.
  std::uniform_real_distribution<double> x(0.0, 100.0), y(0.0, 60.0), yaw(-M_PI, M_PI);
  std::vector<Pose2> truth;
  for (int m = 0; m < maps; ++m) truth.emplace_back(x(rng), y(rng), yaw(rng));
  std::vector<std::pair<double, std::pair<int, int>>> by_distance;
  for (int a = 0; a < maps; ++a) {
    for (int b = a + 1; b < maps; ++b) {
      by_distance.push_back({(truth[a].translation_m() - truth[b].translation_m()).norm(), {a, b}});
    }
  }
  std::sort(by_distance.begin(), by_distance.end());
  const std::size_t count = std::max<std::size_t>(static_cast<std::size_t>(maps - 1),
                                                  by_distance.size() * edge_percent / 100);
  std::normal_distribution<double> t(0.0, 0.05), r(0.0, 0.3 * M_PI / 180.0);
  std::uniform_real_distribution<double> omega(0.6, 1.0);
  SyntheticGraph graph;
  for (std::size_t k = 0; k < std::min(count, by_distance.size()); ++k) {
    const auto [a, b] = by_distance[k].second;
    const Pose2 T_a_b = truth[a].inverse() * truth[b] * Pose2(t(rng), t(rng), r(rng));
    graph.edges.push_back({a, b, T_a_b, omega(rng)});
  }
  // The nearest pairs may leave a map out: chain every map to the next so that all are solved.
  for (int m = 0; m + 1 < maps; ++m) {
    graph.edges.push_back({m, m + 1, truth[m].inverse() * truth[m + 1], 0.5});
  }
  graph.initial = SpanningTreePoses(maps, graph.edges, 0);
  return graph;
}

void BM_PoseGraph(benchmark::State& state) {
  const SyntheticGraph graph =
      MakeGraph(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  PoseGraphOptions options;
  options.solver = static_cast<PoseGraphSolver>(state.range(2));
  for (auto _ : state) {
    benchmark::DoNotOptimize(OptimizePoseGraph(graph.initial, graph.edges, 0, options));
  }
  state.counters["edges"] = static_cast<double>(graph.edges.size());
}
BENCHMARK(BM_PoseGraph)
    ->ArgsProduct({{8, 33, 100, 200, 400}, {2, 5, 10, 25, 60}, {1, 2}})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fleetmerge

BENCHMARK_MAIN();
