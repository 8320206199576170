#include "pipeline/fleet_graph.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace fleetmerge {
namespace {

PoseGraphEdge EdgeOf(const PairOutcome& pair) {
  const PairHypothesis& h = pair.hypotheses[pair.edge_hypothesis];
  return {pair.a, pair.b, h.T_a_b, h.omega};
}

std::vector<PoseGraphEdge> EdgesOf(const std::vector<PairOutcome>& pairs) {
  std::vector<PoseGraphEdge> edges;
  for (const auto& p : pairs) {
    if (p.accepted) edges.push_back(EdgeOf(p));
  }
  return edges;
}

std::vector<int> Components(int map_count, const std::vector<PairOutcome>& pairs) {
  std::vector<int> parent(map_count);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& p : pairs) {
    if (p.accepted) parent[std::max(find(p.a), find(p.b))] = std::min(find(p.a), find(p.b));
  }
  // Number components by their first map, in map order.
  std::vector<int> id(map_count, -1), component(map_count);
  int next = 0;
  for (int m = 0; m < map_count; ++m) {
    const int root = find(m);
    if (id[root] < 0) id[root] = next++;
    component[m] = id[root];
  }
  return component;
}

std::vector<std::optional<Pose2>> Solve(int map_count, const std::vector<PairOutcome>& pairs,
                                        int reference, const PoseGraphOptions& options) {
  const auto edges = EdgesOf(pairs);
  return OptimizePoseGraph(SpanningTreePoses(map_count, edges, reference), edges, reference,
                           options);
}

// Disagreement of an edge with the poses, in units of the tolerances (> 1: inconsistent).
double Violation(const PoseGraphEdge& edge, const std::vector<std::optional<Pose2>>& poses,
                 const PoseGraphOptions& options) {
  if (!poses[edge.a] || !poses[edge.b]) return 0.0;
  const EdgeError e = EdgeDisagreement(edge, *poses[edge.a], *poses[edge.b]);
  return std::max(e.yaw_rad / options.max_edge_yaw_error_rad,
                  e.translation_m / options.max_edge_translation_error_m);
}

// Takes out the worst inconsistent edge of the component of `reference`; returns false when
// every edge agrees with the poses.
bool FixWorstEdge(int map_count, std::vector<PairOutcome>& pairs, int reference,
                  const PoseGraphOptions& options) {
  const auto poses = Solve(map_count, pairs, reference, options);
  int worst = -1;
  double worst_violation = 1.0;
  for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
    if (!pairs[k].accepted) continue;
    const double v = Violation(EdgeOf(pairs[k]), poses, options);
    if (v > worst_violation) worst = k, worst_violation = v;
  }
  if (worst < 0) return false;
  PairOutcome& pair = pairs[worst];
  const int rejected_hypothesis = pair.edge_hypothesis;
  pair.accepted = false;
  const auto without = Solve(map_count, pairs, reference, options);
  for (int h = 0; h < static_cast<int>(pair.hypotheses.size()); ++h) {
    if (h == rejected_hypothesis) continue;
    const PoseGraphEdge candidate{pair.a, pair.b, pair.hypotheses[h].T_a_b, 1.0};
    if (without[pair.a] && without[pair.b] && Violation(candidate, without, options) <= 1.0) {
      pair.accepted = true;
      pair.edge_hypothesis = h;
      pair.note = "hypothesis " + std::to_string(rejected_hypothesis + 1) +
                  " disagreed with its cycles; replaced by hypothesis " + std::to_string(h + 1);
      return true;
    }
  }
  std::ostringstream note;
  note << "rejected: hypothesis " << rejected_hypothesis + 1
       << " disagrees with its cycles and no other hypothesis agrees";
  pair.note = note.str();
  return true;
}

}  // namespace

FleetGraph SolveFleetGraph(int map_count, std::vector<PairOutcome>& pairs, int reference,
                           const PoseGraphOptions& options) {
  FleetGraph graph;
  // Each fix removes or replaces one edge, so this ends; the bound is for safety.
  for (std::size_t round = 0; round <= 2 * pairs.size(); ++round) {
    graph.component_of = Components(map_count, pairs);
    bool changed = false;
    for (int c = 0, n = 1 + *std::max_element(graph.component_of.begin(), graph.component_of.end());
         c < n && !changed; ++c) {
      const int ref = graph.component_of[reference] == c
                          ? reference
                          : int(std::find(graph.component_of.begin(), graph.component_of.end(), c) -
                                graph.component_of.begin());
      changed = FixWorstEdge(map_count, pairs, ref, options);
    }
    if (!changed) break;
  }
  graph.component_of = Components(map_count, pairs);
  const int components =
      1 + *std::max_element(graph.component_of.begin(), graph.component_of.end());
  graph.component_reference.assign(components, -1);
  graph.T_component_map.assign(map_count, Pose2());
  for (int c = 0; c < components; ++c) {
    int ref = -1;
    for (int m = 0; m < map_count && ref < 0; ++m) ref = graph.component_of[m] == c ? m : -1;
    if (graph.component_of[reference] == c) ref = reference;
    graph.component_reference[c] = ref;
    const auto poses = Solve(map_count, pairs, ref, options);
    for (int m = 0; m < map_count; ++m) {
      if (graph.component_of[m] == c && poses[m]) graph.T_component_map[m] = *poses[m];
    }
  }
  return graph;
}

}  // namespace fleetmerge
