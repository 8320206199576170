#include "pipeline/fleet_graph.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace fleetmerge {
namespace {

PoseGraphEdge EdgeOf(const PairOutcome& pair) {
  const PairHypothesis& h = pair.hypotheses[pair.edge_hypothesis];
  return {pair.a, pair.b, h.T_a_b, h.omega, 0.0, 0.0};
}

std::vector<PoseGraphEdge> EdgesOf(const std::vector<PairOutcome>& pairs,
                                   const EdgeAnchor& anchor) {
  std::vector<PoseGraphEdge> edges;
  for (const auto& p : pairs) {
    if (!p.accepted) continue;
    edges.push_back(EdgeOf(p));
    if (anchor) edges.back().anchor_b_m = anchor(p, p.edge_hypothesis);
  }
  return edges;
}

}  // namespace

std::vector<int> Components(int map_count, const std::vector<PairOutcome>& pairs, int skip_pair) {
  std::vector<int> parent(map_count);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
    const PairOutcome& p = pairs[k];
    if (k == skip_pair || !p.accepted) continue;
    parent[std::max(find(p.a), find(p.b))] = std::min(find(p.a), find(p.b));
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

namespace {

// The maps whose poses are known in the site frame (fixed maps and maps with a prior).
struct Known {
  const FixedPoses& fixed;
  const PosePriors& priors;
  const EdgeAnchor& anchor;
  bool any(int m) const { return IsFixed(fixed, m) || HasPrior(priors, m); }
};

// Components() with every map of `tied` in the component of the first one, renumbered by first
// map.
template <typename Tied>
std::vector<int> TiedComponents(int map_count, const std::vector<PairOutcome>& pairs,
                                const Tied& tied_map) {
  std::vector<int> component = Components(map_count, pairs);
  int tied = -1;
  std::vector<int> merged(map_count);
  std::iota(merged.begin(), merged.end(), 0);
  for (int m = 0; m < map_count; ++m) {
    if (!tied_map(m)) continue;
    if (tied < 0) tied = component[m];
    merged[component[m]] = tied;
  }
  std::vector<int> id(map_count, -1), out(map_count);
  int next = 0;
  for (int m = 0; m < map_count; ++m) {
    const int c = merged[component[m]];
    if (id[c] < 0) id[c] = next++;
    out[m] = id[c];
  }
  return out;
}

// Components with the fixed maps tied (their poses) and the maps with priors tied (node S).
std::vector<int> SiteComponents(int map_count, const std::vector<PairOutcome>& pairs,
                                const Known& known) {
  return TiedComponents(map_count, pairs, [&](int m) { return known.any(m); });
}

// The component of the maps with known poses, or -1.
int SiteComponent(const std::vector<int>& component_of, const Known& known) {
  for (int m = 0; m < static_cast<int>(component_of.size()); ++m) {
    if (known.any(m)) return component_of[m];
  }
  return -1;
}

// Poses of the maps. For the site component (that of the maps with known poses, when
// `in_site`): in the site frame, with node S (index map_count) and every fixed map held at their
// poses, and one edge S -> m per prior. Else in `reference`'s frame, which is held at identity.
std::vector<std::optional<Pose2>> Solve(int map_count, const std::vector<PairOutcome>& pairs,
                                        int reference, const PoseGraphOptions& options,
                                        const Known& known, bool in_site) {
  auto edges = EdgesOf(pairs, known.anchor);
  if (!in_site) {
    return OptimizePoseGraph(SpanningTreePoses(map_count, edges, reference), edges, reference,
                             options);
  }
  const int site = map_count;
  std::vector<std::optional<Pose2>> anchors(map_count + 1);
  std::vector<bool> constant(map_count + 1, false);
  anchors[site] = Pose2();
  constant[site] = true;
  // The spanning tree sees the prior edges at omega 0, below any pair's: it places a map by its
  // pairs where it has any, by its prior only where it has none. In the solve a prior is whitened
  // by its own sigmas (omega 1; the robust loss trims it at loss_scale of them) and its cost
  // scaled by kPriorCostScale.
  auto tree_edges = edges;
  for (int m = 0; m < map_count; ++m) {
    if (IsFixed(known.fixed, m)) {
      anchors[m] = *known.fixed[m];
      constant[m] = true;
    } else if (HasPrior(known.priors, m)) {
      const PosePrior& p = *known.priors[m];
      edges.push_back({site, m, p.T_site_map, 1.0, p.translation_sigma_m, p.yaw_sigma_rad});
      edges.back().cost_scale = kPriorCostScale;
      tree_edges.push_back(edges.back());
      tree_edges.back().omega = 0.0;
    }
  }
  auto poses = OptimizePoseGraph(SpanningTreePoses(map_count + 1, tree_edges, anchors), edges,
                                 constant, options);
  poses.resize(map_count);
  return poses;
}

// Disagreement of an edge with the poses, in units of the tolerances (> 1: inconsistent).
double Violation(const PoseGraphEdge& edge, const std::vector<std::optional<Pose2>>& poses,
                 const PoseGraphOptions& options) {
  if (!poses[edge.a] || !poses[edge.b]) return 0.0;
  const EdgeError e = EdgeDisagreement(edge, *poses[edge.a], *poses[edge.b]);
  return std::max(e.yaw_rad / options.max_edge_yaw_error_rad,
                  e.translation_m / options.max_edge_translation_error_m);
}

// Solve with the last solve's answer kept: a fix that rejects an edge without a replacement
// leaves the next round the very problem it solved without that edge (the same accepted edges,
// reference and frame), and the last round's problem is the final one. Solving is deterministic,
// so the kept poses are the ones solving again would give (docs/speed.md, the fleet graph).
class Solver {
 public:
  Solver(int map_count, const PoseGraphOptions& options, const Known& known)
      : map_count_(map_count), options_(options), known_(known) {}

  const std::vector<std::optional<Pose2>>& Solve(const std::vector<PairOutcome>& pairs,
                                                 int reference, bool in_site) {
    std::vector<int> edge_of_pair(pairs.size());  // the edge hypothesis, -1: not accepted
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      edge_of_pair[k] = pairs[k].accepted ? pairs[k].edge_hypothesis : -1;
    }
    if (solved_ && reference == reference_ && in_site == in_site_ &&
        edge_of_pair == edge_of_pair_) {
      return poses_;
    }
    poses_ = fleetmerge::Solve(map_count_, pairs, reference, options_, known_, in_site);
    solved_ = true;
    reference_ = reference;
    in_site_ = in_site;
    edge_of_pair_ = std::move(edge_of_pair);
    return poses_;
  }

 private:
  int map_count_;
  const PoseGraphOptions& options_;
  const Known& known_;
  bool solved_ = false;
  int reference_ = -1;
  bool in_site_ = false;
  std::vector<int> edge_of_pair_;
  std::vector<std::optional<Pose2>> poses_;
};

// Whether map x or map y is one of `pair`'s.
bool HasAMapOf(const PairOutcome& pair, int x, int y) {
  return pair.a == x || pair.a == y || pair.b == x || pair.b == y;
}

// pairs[worst], taken out (accepted false) with no other hypothesis that agrees, has walls of at
// least `weak_wall_agreement` on its edge's hypothesis. Its weakest neighbour (an accepted pair of
// one of its maps, with walls below `weak_wall_agreement`) is rejected instead, and pairs[worst]
// kept, when the poses solved without that neighbour agree with pairs[worst]. Returns whether it
// did. Why: the solve can side with a weak edge that is a few cells off (a corridor's aliasing,
// within the triangles' doubled tolerances), and then the strong edge beside it is the one whose
// residual is too large. Walls are the pairs' evidence of being right (the triangles' tie-break).
bool BlameAWeakNeighbour(Solver& solver, std::vector<PairOutcome>& pairs, int worst, int reference,
                         const PoseGraphOptions& options, bool in_site,
                         double weak_wall_agreement) {
  PairOutcome& pair = pairs[worst];
  const int hypothesis = pair.edge_hypothesis;
  const double walls = pair.hypotheses[hypothesis].wall_agreement;
  if (walls < weak_wall_agreement) return false;
  int weakest = -1;
  double weakest_walls = weak_wall_agreement;
  for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
    const PairOutcome& p = pairs[k];
    if (k == worst || !p.accepted || !HasAMapOf(p, pair.a, pair.b)) continue;
    const double w = p.hypotheses[p.edge_hypothesis].wall_agreement;
    if (w < weakest_walls) weakest = k, weakest_walls = w;
  }
  if (weakest < 0) return false;
  PairOutcome& weak = pairs[weakest];
  pair.accepted = true;
  weak.accepted = false;
  if (Violation(EdgeOf(pair), solver.Solve(pairs, reference, in_site), options) > 1.0) {
    weak.accepted = true;
    pair.accepted = false;
    return false;
  }
  std::ostringstream note;
  note << "rejected: hypothesis " << weak.edge_hypothesis + 1 << " (walls " << weakest_walls
       << ") disagrees with a pair of one of its maps with stronger walls (" << walls
       << "), which agrees with its cycles without it";
  weak.note = note.str();
  return true;
}

// Takes out the worst inconsistent edge of the component of `reference`; returns false when
// every edge agrees with the poses.
bool FixWorstEdge(Solver& solver, std::vector<PairOutcome>& pairs, int reference,
                  const PoseGraphOptions& options, bool in_site, double weak_wall_agreement) {
  const auto poses = solver.Solve(pairs, reference, in_site);
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
  const auto& without = solver.Solve(pairs, reference, in_site);
  for (int h = 0; h < static_cast<int>(pair.hypotheses.size()); ++h) {
    if (h == rejected_hypothesis) continue;
    const PoseGraphEdge candidate{pair.a, pair.b, pair.hypotheses[h].T_a_b, 1.0, 0.0, 0.0};
    if (without[pair.a] && without[pair.b] && Violation(candidate, without, options) <= 1.0) {
      pair.accepted = true;
      pair.edge_hypothesis = h;
      pair.note = "hypothesis " + std::to_string(rejected_hypothesis + 1) +
                  " disagreed with its cycles; replaced by hypothesis " + std::to_string(h + 1);
      return true;
    }
  }
  if (BlameAWeakNeighbour(solver, pairs, worst, reference, options, in_site, weak_wall_agreement)) {
    return true;
  }
  std::ostringstream note;
  note << "rejected: hypothesis " << rejected_hypothesis + 1
       << " disagrees with its cycles and no other hypothesis agrees";
  pair.note = note.str();
  return true;
}

// The accepted edges as poses both ways (index [from][to]), each with its rotation matrix. The
// triangle votes compose them (accepted edges) x (maps) times per pass, and every solve of the
// fleet makes a pass: made once per edge, the inverses and rotations cost O(edges), not
// O(edges x maps) sines and cosines (100 robots: the refine stage's main cost). The same
// arithmetic as Pose2's operators, so the same votes.
class AcceptedEdges {
 public:
  AcceptedEdges(int map_count, const std::vector<PairOutcome>& pairs)
      : map_count_(map_count), edges_(std::size_t(map_count) * map_count) {
    for (const PairOutcome& pair : pairs) Update(pair);
  }

  // After `pair` was accepted, refused or given another hypothesis.
  void Update(const PairOutcome& pair) {
    Edge& forward = edges_[std::size_t(pair.a) * map_count_ + pair.b];
    Edge& backward = edges_[std::size_t(pair.b) * map_count_ + pair.a];
    forward.accepted = backward.accepted = pair.accepted;
    if (!pair.accepted) return;
    forward = Edge(pair.hypotheses[pair.edge_hypothesis].T_a_b);
    backward = Edge(forward.T.inverse());
  }

  // (supporting, contradicting) triangles of hypothesis T_a_b among the accepted edges a-c, c-b.
  std::pair<int, int> Votes(int a, int b, const Pose2& T_a_b,
                            const PoseGraphOptions& options) const {
    const Edge T_b_a(T_a_b.inverse());
    const double max_yaw_rad = 2.0 * options.max_edge_yaw_error_rad;
    const double max_translation_m = 2.0 * options.max_edge_translation_error_m;
    int support = 0, contradict = 0;
    for (int c = 0; c < map_count_; ++c) {
      if (c == a || c == b) continue;
      const Edge& a_c = edges_[std::size_t(a) * map_count_ + c];
      const Edge& c_b = edges_[std::size_t(c) * map_count_ + b];
      if (!a_c.accepted || !c_b.accepted) continue;
      // Whether T_a_b agrees with the path a -> c -> b (tolerances doubled: three pairwise
      // errors add up around a triangle). delta = T_a_b^-1 * (T_a_c * T_c_b).
      const Pose2 delta = T_b_a * (a_c * c_b.T);
      const bool agrees = std::abs(delta.yaw_rad()) <= max_yaw_rad &&
                          delta.translation_m().norm() <= max_translation_m;
      (agrees ? support : contradict)++;
    }
    return {support, contradict};
  }

 private:
  struct Edge {
    Edge() = default;
    explicit Edge(const Pose2& T) : accepted(true), T(T), R(T.rotation()) {}
    // Pose2::operator*, with the rotation made once.
    Pose2 operator*(const Pose2& T_b_c) const {
      return Pose2(T.translation_m() + R * T_b_c.translation_m(), T.yaw_rad() + T_b_c.yaw_rad());
    }
    bool accepted = false;
    Pose2 T;
    Eigen::Matrix2d R = Eigen::Matrix2d::Identity();
  };
  int map_count_;
  std::vector<Edge> edges_;
};

// Before any solve (so the spanning tree cannot be led by a wrong edge): the edge most
// contradicted by its triangles is replaced by a hypothesis they support, or rejected; repeat.
void ResolveTriangleConflicts(int map_count, std::vector<PairOutcome>& pairs,
                              const PoseGraphOptions& options) {
  AcceptedEdges edges(map_count, pairs);
  // Each accepted pair's contradicting minus supporting triangles. The triangles of pair a-b
  // are a-c-b, so a change of edge x-y changes the votes of the pairs with an end at x or y
  // only: those are counted again after each round, not every pair against every map.
  std::vector<int> margins(pairs.size(), 0);
  const auto count_margin = [&](std::size_t k) {
    const PairOutcome& p = pairs[k];
    if (!p.accepted) return;
    const auto [support, contradict] =
        edges.Votes(p.a, p.b, p.hypotheses[p.edge_hypothesis].T_a_b, options);
    margins[k] = contradict - support;
  };
  for (std::size_t k = 0; k < pairs.size(); ++k) count_margin(k);
  for (std::size_t round = 0; round < pairs.size(); ++round) {
    int worst = -1, worst_margin = 0;
    for (int k = 0; k < static_cast<int>(pairs.size()); ++k) {
      if (!pairs[k].accepted) continue;
      const int margin = margins[k];
      // Equal margins: the pair with the weaker walls goes first (two wrong edges of one map
      // contradict each other's right neighbours as much as themselves).
      if (margin > worst_margin || (margin == worst_margin && worst >= 0 &&
                                    pairs[k].wall_agreement < pairs[worst].wall_agreement)) {
        worst = k, worst_margin = margin;
      }
    }
    if (worst < 0) return;
    PairOutcome& pair = pairs[worst];
    const int rejected = pair.edge_hypothesis;
    pair.accepted = false;
    edges.Update(pair);
    for (int h = 0; h < static_cast<int>(pair.hypotheses.size()); ++h) {
      if (h == rejected) continue;
      const auto [support, contradict] =
          edges.Votes(pair.a, pair.b, pair.hypotheses[h].T_a_b, options);
      if (support > contradict) {
        pair.accepted = true;
        pair.edge_hypothesis = h;
        edges.Update(pair);
        pair.note = "hypothesis " + std::to_string(rejected + 1) +
                    " contradicted its triangles; replaced by hypothesis " + std::to_string(h + 1);
        break;
      }
    }
    if (!pair.accepted) {
      pair.note = "rejected: hypothesis " + std::to_string(rejected + 1) + " contradicted by " +
                  std::to_string(worst_margin) +
                  " more triangles than support it, and no other hypothesis agrees";
    }
    const int x = pair.a, y = pair.b;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      if (HasAMapOf(pairs[k], x, y)) count_margin(k);
    }
  }
}

// The map whose frame is component c's: the job's reference if it is in c, else c's first map.
int ComponentReference(const std::vector<int>& component_of, int c, int reference) {
  if (component_of[reference] == c) return reference;
  return static_cast<int>(std::find(component_of.begin(), component_of.end(), c) -
                          component_of.begin());
}

}  // namespace

FleetGraph SolveFleetGraph(int map_count, std::vector<PairOutcome>& pairs, int reference,
                           const PoseGraphOptions& options, const FixedPoses& fixed,
                           const PosePriors& priors, const EdgeAnchor& anchor,
                           double weak_wall_agreement) {
  FleetGraph graph;
  const Known known{fixed, priors, anchor};
  Solver solver(map_count, options, known);
  ResolveTriangleConflicts(map_count, pairs, options);
  // Longer cycles: solve, take out the worst edge, repeat. Each fix removes or replaces one edge,
  // so this ends; the bound is for safety.
  for (std::size_t round = 0; round <= 2 * pairs.size(); ++round) {
    graph.component_of = SiteComponents(map_count, pairs, known);
    const int site = SiteComponent(graph.component_of, known);
    bool changed = false;
    for (int c = 0, n = 1 + *std::max_element(graph.component_of.begin(), graph.component_of.end());
         c < n && !changed; ++c) {
      changed = FixWorstEdge(solver, pairs, ComponentReference(graph.component_of, c, reference),
                             options, c == site, weak_wall_agreement);
    }
    if (!changed) break;
  }
  graph.component_of = SiteComponents(map_count, pairs, known);
  const int site = SiteComponent(graph.component_of, known);
  const int components =
      1 + *std::max_element(graph.component_of.begin(), graph.component_of.end());
  graph.component_reference.assign(components, -1);
  graph.T_component_map.assign(map_count, Pose2());
  for (int c = 0; c < components; ++c) {
    const int ref = ComponentReference(graph.component_of, c, reference);
    graph.component_reference[c] = ref;
    // The site component's poses are in the site frame (the fixed maps' frame): the merged frame.
    const auto& poses = solver.Solve(pairs, ref, c == site);
    for (int m = 0; m < map_count; ++m) {
      if (graph.component_of[m] == c && poses[m]) graph.T_component_map[m] = *poses[m];
    }
  }
  // Which maps the pairs alone (with the fixed maps' ties) link together: the groups.
  const std::vector<int> group_of =
      TiedComponents(map_count, pairs, [&](int m) { return IsFixed(fixed, m); });
  std::vector<int> group_size(map_count, 0);
  for (const int g : group_of) ++group_size[g];
  // Per component, the group that pairs place in its frame (the anchor): the reference's. In the
  // site component that is the fixed maps' group; without fixed maps the site frame is the
  // priors' and no map's, so the anchor is the largest group (the reference's on a tie, else the
  // first): a reference map that no pair links to another is placed by its prior like any other.
  std::vector<int> anchor_of(components, -1);
  for (int c = 0; c < components; ++c) {
    anchor_of[c] = group_of[graph.component_reference[c]];
  }
  const bool any_fixed =
      std::any_of(fixed.begin(), fixed.end(), [](const auto& pose) { return pose.has_value(); });
  if (site >= 0 && !any_fixed) {
    for (int m = 0; m < map_count; ++m) {
      if (graph.component_of[m] == site && group_size[group_of[m]] > group_size[anchor_of[site]]) {
        anchor_of[site] = group_of[m];
      }
    }
  }
  std::vector<int> component_size(components, 0);
  for (const int c : graph.component_of) ++component_size[c];
  graph.placed_by.assign(map_count, PlacedBy::kPairs);
  for (int m = 0; m < map_count; ++m) {
    const int c = graph.component_of[m];
    PlacedBy& placed = graph.placed_by[m];
    if (IsFixed(fixed, m)) {
      placed = PlacedBy::kFixed;
    } else if (component_size[c] == 1) {
      // Alone, a map with a prior is still where its prior puts it in the site frame (the only
      // map with one, so the site frame is its prior's); a map without one has no frame but its
      // own.
      placed = HasPrior(priors, m) ? PlacedBy::kPrior : PlacedBy::kUnmerged;
    } else if (group_of[m] != anchor_of[c]) {
      placed = PlacedBy::kPrior;  // its group's priors place it in the site frame
    } else if (m == graph.component_reference[c]) {
      placed = PlacedBy::kReference;
    }
  }
  return graph;
}

}  // namespace fleetmerge
