// The pose graph (refine/pose_graph.hpp) and its cycle checks (pipeline/fleet_graph.hpp) on
// seeded synthetic graphs with known poses. Judged by relative poses, not absolute parameters.
#include "refine/pose_graph.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pipeline/fleet_graph.hpp"

namespace fleetmerge {
namespace {

std::vector<Pose2> RandomPoses(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> xy(-20, 20), yaw(-M_PI, M_PI);
  std::vector<Pose2> poses{Pose2()};
  for (int k = 1; k < n; ++k) poses.emplace_back(xy(rng), xy(rng), yaw(rng));
  return poses;
}

Pose2 Noisy(const Pose2& T, double sigma_m, double sigma_rad, std::mt19937& rng) {
  std::normal_distribution<double> t(0.0, sigma_m), r(0.0, sigma_rad);
  return T * Pose2(t(rng), t(rng), r(rng));
}

// Mean over all node pairs of the relative-pose translation error (gauge-free).
double RelativeError(const std::vector<std::optional<Pose2>>& est,
                     const std::vector<Pose2>& truth) {
  double sum = 0.0;
  int n = 0;
  for (std::size_t a = 0; a < truth.size(); ++a) {
    for (std::size_t b = a + 1; b < truth.size(); ++b) {
      const Pose2 e = (est[a]->inverse() * *est[b]).inverse() * (truth[a].inverse() * truth[b]);
      sum += e.translation_m().norm();
      ++n;
    }
  }
  return sum / n;
}

TEST(PoseGraph, ExactEdgesGiveExactPosesAndReferenceStaysFixed) {
  std::mt19937 rng(1);
  const auto truth = RandomPoses(5, rng);
  std::vector<PoseGraphEdge> edges;
  for (int a = 0; a < 5; ++a) {
    for (int b = a + 1; b < 5; ++b) edges.push_back({a, b, truth[a].inverse() * truth[b], 0.95});
  }
  const auto init = SpanningTreePoses(5, edges, 2);
  const auto poses = OptimizePoseGraph(init, edges, 2, PoseGraphOptions{});
  EXPECT_EQ(poses[2]->x_m(), 0.0);
  EXPECT_EQ(poses[2]->yaw_rad(), 0.0);
  EXPECT_LT(RelativeError(poses, truth), 1e-6);
}

// Several fixed maps: every anchor keeps its pose bit for bit, also when the edges contradict
// the anchors; a free node between two anchors that both edges agree on lands exactly there.
TEST(PoseGraph, AnchorsKeepTheirPoses) {
  std::vector<std::optional<Pose2>> anchors(3);
  anchors[0] = Pose2(0.0, 0.0, 0.0);
  anchors[2] = Pose2(2.0, 0.0, 0.5);
  const Pose2 T_0_1(1.0, 0.0, 0.2);
  const std::vector<PoseGraphEdge> agree = {{0, 1, T_0_1, 1.0},
                                            {2, 1, anchors[2]->inverse() * T_0_1, 1.0}};
  const std::vector<bool> constant = {true, false, true};
  const auto initial = SpanningTreePoses(3, agree, anchors);
  ASSERT_TRUE(initial[1].has_value());
  const auto solved = OptimizePoseGraph(initial, agree, constant, PoseGraphOptions{});
  EXPECT_NEAR((solved[1]->translation_m() - T_0_1.translation_m()).norm(), 0.0, 1e-9);
  EXPECT_NEAR(solved[1]->yaw_rad(), T_0_1.yaw_rad(), 1e-9);
  // An edge between the anchors 1 m off what their poses say: they do not move.
  std::vector<PoseGraphEdge> contradict = agree;
  contradict.push_back({0, 2, Pose2(3.0, 0.0, 0.5), 10.0});
  const auto held = OptimizePoseGraph(initial, contradict, constant, PoseGraphOptions{});
  for (const int n : {0, 2}) {
    EXPECT_EQ(held[n]->x_m(), anchors[n]->x_m());
    EXPECT_EQ(held[n]->y_m(), anchors[n]->y_m());
    EXPECT_EQ(held[n]->yaw_rad(), anchors[n]->yaw_rad());
  }
  const EdgeError e = EdgeDisagreement(contradict.back(), *held[0], *held[2]);
  EXPECT_NEAR(e.translation_m, 1.0, 1e-9);  // left to the cycle check to reject
}

TEST(PoseGraph, AnEdgesOwnSigmasWeighIt) {
  // Node 1 measured from the held node 0 twice, 1 m apart along x: once at the options' 0.10 m
  // (a pair), once at its own 1.0 m (a prior). Without a robust loss the solution is the
  // weighted mean, 1/0.1^2 : 1/1^2 = 100 : 1, so 1/101 m from the pair's measurement; the yaw
  // likewise with 0.5 deg against 5 deg.
  PoseGraphOptions options;
  options.loss = RobustLoss::kNone;
  const double yaw_sigma = 10.0 * options.yaw_sigma_rad;
  const std::vector<PoseGraphEdge> edges = {{0, 1, Pose2(5.0, 0.0, 0.0), 1.0, 0.0, 0.0},
                                            {0, 1, Pose2(6.0, 0.0, 0.01), 1.0, 1.0, yaw_sigma}};
  std::vector<std::optional<Pose2>> initial = {Pose2(), Pose2(5.0, 0.0, 0.0)};
  const auto poses = OptimizePoseGraph(initial, edges, 0, options);
  ASSERT_TRUE(poses[1].has_value());
  EXPECT_NEAR(poses[1]->x_m(), 5.0 + 1.0 / 101.0, 1e-6);
  EXPECT_NEAR(poses[1]->yaw_rad(), 0.01 / 101.0, 1e-8);
}

// cost_scale multiplies an edge's cost after the loss. Without a loss the weights are then
// 100 : 0.25, so the prior's measurement pulls by 0.25/100.25 of its 1 m. With the Cauchy loss the
// prior 10 of its own sigmas off is trimmed as before, whatever its scale: its pull, scaled or
// not, is far below the unscaled least-squares share.
TEST(PoseGraph, ACostScaleWeighsAnEdgeAfterTheLoss) {
  PoseGraphOptions options;
  options.loss = RobustLoss::kNone;
  std::vector<PoseGraphEdge> edges = {{0, 1, Pose2(5.0, 0.0, 0.0), 1.0, 0.0, 0.0},
                                      {0, 1, Pose2(6.0, 0.0, 0.0), 1.0, 1.0, 0.1}};
  edges[1].cost_scale = 0.25;
  const std::vector<std::optional<Pose2>> initial = {Pose2(), Pose2(5.0, 0.0, 0.0)};
  auto poses = OptimizePoseGraph(initial, edges, 0, options);
  ASSERT_TRUE(poses[1].has_value());
  EXPECT_NEAR(poses[1]->x_m(), 5.0 + 0.25 / 100.25, 1e-6);

  options.loss = RobustLoss::kCauchy;      // loss_scale 3 sigmas
  edges[1].T_a_b = Pose2(15.0, 0.0, 0.0);  // 10 m: 10 of the prior's sigmas
  edges[1].cost_scale = 1.0;
  const double unscaled = OptimizePoseGraph(initial, edges, 0, options)[1]->x_m() - 5.0;
  edges[1].cost_scale = 0.25;
  const double scaled = OptimizePoseGraph(initial, edges, 0, options)[1]->x_m() - 5.0;
  EXPECT_GT(unscaled, 0.0);
  EXPECT_LT(unscaled, 0.1 * 10.0 / 101.0);  // trimmed: least squares would pull 10/101 m
  EXPECT_NEAR(scaled, 0.25 * unscaled, 0.05 * unscaled);  // the trimmed pull, scaled
}

// The two linear solvers are exact: on a noisy graph with a wrong edge (the robust loss at work),
// two fixed maps and a prior's own sigmas, they reach the same poses, far from the start.
// kAutomatic takes the dense Schur solver on a dense graph and the sparse Cholesky one on a
// sparse graph: its poses equal that solver's bit for bit.
TEST(PoseGraph, BothLinearSolversGiveTheSamePoses) {
  for (const int edge_percent : {100, 5}) {
    std::mt19937 rng(3);
    const int n = 40;
    const auto truth = RandomPoses(n, rng);
    std::vector<PoseGraphEdge> edges;
    for (int a = 0; a < n; ++a) {
      for (int b = a + 1; b < n; ++b) {
        // Every pair, or a chain and every 20th pair (5 % of them).
        if (edge_percent == 100 || b == a + 1 || (a * n + b) % 20 == 0) {
          edges.push_back(
              {a, b, Noisy(truth[a].inverse() * truth[b], 0.1, 0.5 * M_PI / 180, rng), 0.9});
        }
      }
    }
    edges.push_back({3, 9, truth[3].inverse() * truth[9] * Pose2(2.0, -1.0, 0.3), 0.9});  // wrong
    edges.push_back({0, 7, truth[7], 1.0, 1.0, 0.2});  // a prior with its own sigmas
    std::vector<bool> constant(n, false);
    constant[0] = constant[5] = true;
    std::vector<std::optional<Pose2>> anchors(n);
    anchors[0] = truth[0];
    anchors[5] = truth[5];
    const auto initial = SpanningTreePoses(n, edges, anchors);
    EXPECT_EQ(UseDenseSchur(n - 2, edges.size()), edge_percent == 100);

    PoseGraphOptions options;
    options.solver = PoseGraphSolver::kSparseCholesky;
    const auto sparse = OptimizePoseGraph(initial, edges, constant, options);
    options.solver = PoseGraphSolver::kDenseSchur;
    const auto dense = OptimizePoseGraph(initial, edges, constant, options);
    options.solver = PoseGraphSolver::kAutomatic;
    const auto automatic = OptimizePoseGraph(initial, edges, constant, options);
    const auto& chosen = edge_percent == 100 ? dense : sparse;
    double moved_m = 0.0;
    for (int m = 0; m < n; ++m) {
      ASSERT_TRUE(sparse[m] && dense[m] && automatic[m]);
      EXPECT_NEAR(sparse[m]->x_m(), dense[m]->x_m(), 1e-9) << "map " << m;
      EXPECT_NEAR(sparse[m]->y_m(), dense[m]->y_m(), 1e-9) << "map " << m;
      EXPECT_NEAR(sparse[m]->yaw_rad(), dense[m]->yaw_rad(), 1e-11) << "map " << m;
      EXPECT_EQ(automatic[m]->x_m(), chosen[m]->x_m()) << "map " << m;
      EXPECT_EQ(automatic[m]->y_m(), chosen[m]->y_m()) << "map " << m;
      EXPECT_EQ(automatic[m]->yaw_rad(), chosen[m]->yaw_rad()) << "map " << m;
      moved_m = std::max(moved_m, (dense[m]->translation_m() - initial[m]->translation_m()).norm());
    }
    EXPECT_GT(moved_m, 0.05) << "the solve must move the maps for the comparison to mean anything";
    EXPECT_LT(RelativeError(dense, truth), RelativeError(initial, truth));
  }
}

// A star around the held reference (robots that each overlap only the site map): every free node
// is in the independent set that the Schur solver eliminates, none is left to factorise. It
// solves it as the sparse solver does: map 1 between its two measurements (by symmetry, to the
// solve's tolerance), map 2 on its one.
TEST(PoseGraph, TheDenseSchurSolverSolvesAStarAroundTheReference) {
  const std::vector<PoseGraphEdge> edges = {{0, 1, Pose2(5.0, 0.0, 0.1), 1.0},
                                            {0, 1, Pose2(5.2, 0.0, 0.1), 1.0},
                                            {0, 2, Pose2(0.0, 3.0, -0.2), 1.0}};
  const std::vector<std::optional<Pose2>> initial = {Pose2(), Pose2(4.0, 1.0, 0.0),
                                                     Pose2(1.0, 2.0, 0.0)};
  PoseGraphOptions options;
  options.solver = PoseGraphSolver::kDenseSchur;
  const auto dense = OptimizePoseGraph(initial, edges, 0, options);
  options.solver = PoseGraphSolver::kSparseCholesky;
  const auto sparse = OptimizePoseGraph(initial, edges, 0, options);
  EXPECT_NEAR(dense[1]->x_m(), 5.1, 1e-3);
  EXPECT_NEAR(dense[1]->yaw_rad(), 0.1, 1e-6);
  EXPECT_NEAR(dense[2]->y_m(), 3.0, 1e-6);
  EXPECT_NEAR(dense[2]->yaw_rad(), -0.2, 1e-9);
  for (const int m : {1, 2}) {
    EXPECT_NEAR(dense[m]->x_m(), sparse[m]->x_m(), 1e-9);
    EXPECT_NEAR(dense[m]->y_m(), sparse[m]->y_m(), 1e-9);
    EXPECT_NEAR(dense[m]->yaw_rad(), sparse[m]->yaw_rad(), 1e-11);
  }
}

TEST(PoseGraph, SpanningTreeLeavesUnconnectedNodesWithoutPose) {
  const std::vector<PoseGraphEdge> edges = {{0, 1, Pose2(1, 0, 0), 0.9}};
  const auto poses = SpanningTreePoses(3, edges, 0);
  EXPECT_TRUE(poses[1].has_value());
  EXPECT_FALSE(poses[2].has_value());
}

TEST(PoseGraph, JointRefinementImprovesOnTheSpanningTreeWithNoisyPairs) {
  // Every pair measured with noise (0.1 m, 0.5 deg): the spanning tree uses n - 1 of them, the
  // pose graph all of them. Averaged over seeds, the joint solution must be clearly better.
  double tree_error = 0.0, graph_error = 0.0;
  for (std::uint32_t seed = 0; seed < 20; ++seed) {
    std::mt19937 rng(seed);
    const auto truth = RandomPoses(6, rng);
    std::vector<PoseGraphEdge> edges;
    for (int a = 0; a < 6; ++a) {
      for (int b = a + 1; b < 6; ++b) {
        edges.push_back(
            {a, b, Noisy(truth[a].inverse() * truth[b], 0.1, 0.5 * M_PI / 180, rng), 0.95});
      }
    }
    const auto tree = SpanningTreePoses(6, edges, 0);
    tree_error += RelativeError(tree, truth);
    graph_error += RelativeError(OptimizePoseGraph(tree, edges, 0, PoseGraphOptions{}), truth);
  }
  std::printf("[ pose graph ] mean relative-pose error: spanning tree %.3f m, refined %.3f m\n",
              tree_error / 20, graph_error / 20);
  EXPECT_LT(graph_error, 0.8 * tree_error);
}

TEST(PoseGraph, AnEdgeMeasuredAtItsMapsCellsKeepsThemInPlace) {
  // Each map's cells lie 40 m from its frame's origin (as a robot's map can). A pair search
  // recovers a pose best where the cells are: its error is a small turn (0.15 deg) about them,
  // which at the far origin looks like a 10 cm shift. Measured at the origin, the edges let the
  // solution turn maps about their origins and move their cells; measured at the cells (each
  // edge's anchor_b_m), the cells stay within the edges' own error.
  const Eigen::Vector2d cells_m(40.0, 0.0);  // in every map's frame
  const auto about_cells = [&](double yaw_rad) {
    return Pose2(cells_m.x(), cells_m.y(), 0.0) * Pose2(0, 0, yaw_rad) *
           Pose2(-cells_m.x(), -cells_m.y(), 0.0);
  };
  // Where each map's cells are against the truth, averaged over the maps (map 0 is the gauge).
  const auto cells_error_m = [&](const std::vector<std::optional<Pose2>>& est,
                                 const std::vector<Pose2>& truth) {
    double sum = 0.0;
    for (std::size_t m = 1; m < truth.size(); ++m) {
      sum += ((*est[m]) * cells_m - truth[m] * cells_m).norm();
    }
    return sum / (truth.size() - 1);
  };
  double at_origin_m = 0.0, at_cells_m = 0.0;
  for (std::uint32_t seed = 0; seed < 20; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> turn_rad(0.0, 0.15 * M_PI / 180);
    const auto truth = RandomPoses(6, rng);
    std::vector<PoseGraphEdge> edges;
    for (int a = 0; a < 6; ++a) {
      for (int b = a + 1; b < 6; ++b) {
        edges.push_back({a, b, truth[a].inverse() * truth[b] * about_cells(turn_rad(rng)), 0.95});
      }
    }
    const auto tree = SpanningTreePoses(6, edges, 0);
    at_origin_m += cells_error_m(OptimizePoseGraph(tree, edges, 0, PoseGraphOptions{}), truth);
    for (PoseGraphEdge& edge : edges) edge.anchor_b_m = cells_m;
    at_cells_m += cells_error_m(OptimizePoseGraph(tree, edges, 0, PoseGraphOptions{}), truth);
  }
  at_origin_m /= 20;
  at_cells_m /= 20;
  std::printf(
      "[ pose graph ] mean error of the maps' cells: edges at the origin %.3f m, "
      "at the cells %.3f m\n",
      at_origin_m, at_cells_m);
  EXPECT_LT(at_cells_m, 0.5 * at_origin_m);
  EXPECT_LT(at_cells_m, 0.05);  // a cell at 5 cm
}

// Pair outcomes for the fleet graph: the truth as hypothesis, with an optional wrong best.
PairOutcome Outcome(int a, int b, const std::vector<Pose2>& truth,
                    std::optional<Pose2> wrong_best) {
  PairOutcome p;
  p.a = a;
  p.b = b;
  const Pose2 T = truth[a].inverse() * truth[b];
  if (wrong_best) p.hypotheses.push_back({*wrong_best, 0.99});
  p.hypotheses.push_back({T, 0.97});
  p.accepted = true;
  p.edge_hypothesis = 0;
  return p;
}

TEST(FleetGraph, CyclesReplaceAWrongBestHypothesisByTheOneThatAgrees) {
  std::mt19937 rng(4);
  const auto truth = RandomPoses(4, rng);
  std::vector<PairOutcome> pairs;
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) {
      // Pair 1-2's best hypothesis is the corridor confusion: 180 degrees off and shifted.
      const bool wrong = a == 1 && b == 2;
      pairs.push_back(Outcome(
          a, b, truth,
          wrong ? std::optional<Pose2>((truth[a].inverse() * truth[b]) * Pose2(3.0, 0.5, M_PI))
                : std::nullopt));
    }
  }
  const FleetGraph graph = SolveFleetGraph(4, pairs, 0, PoseGraphOptions{});
  const PairOutcome& fixed = pairs[3];  // (1, 2) in row order
  ASSERT_EQ(fixed.a, 1);
  ASSERT_EQ(fixed.b, 2);
  EXPECT_TRUE(fixed.accepted);
  EXPECT_EQ(fixed.edge_hypothesis, 1) << fixed.note;
  EXPECT_NE(fixed.note.find("replaced by hypothesis 2"), std::string::npos) << fixed.note;
  for (const auto& p : pairs) EXPECT_TRUE(p.accepted) << p.a << "-" << p.b << " " << p.note;
  for (int m = 0; m < 4; ++m) EXPECT_EQ(graph.component_of[m], 0);
  std::vector<std::optional<Pose2>> est(graph.T_component_map.begin(), graph.T_component_map.end());
  EXPECT_LT(RelativeError(est, truth), 1e-3);
}

TEST(FleetGraph, AWrongEdgeWithoutAnAgreeingAlternativeIsRejected) {
  // Four maps, all pairs; pair 0-2 has only a wrong hypothesis (and the highest omega, so a
  // spanning tree would start with it). With three maps one wrong edge of a triangle could not
  // be told from the others; with four it is outvoted.
  std::mt19937 rng(6);
  const auto truth = RandomPoses(4, rng);
  std::vector<PairOutcome> pairs;
  for (int a = 0; a < 4; ++a) {
    for (int b = a + 1; b < 4; ++b) pairs.push_back(Outcome(a, b, truth, std::nullopt));
  }
  pairs[1].hypotheses = {{truth[0].inverse() * truth[2] * Pose2(2.0, -1.0, 0.5), 0.99}};
  const FleetGraph graph = SolveFleetGraph(4, pairs, 0, PoseGraphOptions{});
  EXPECT_FALSE(pairs[1].accepted) << pairs[1].note;
  EXPECT_NE(pairs[1].note.find("rejected"), std::string::npos) << pairs[1].note;
  std::vector<std::optional<Pose2>> est(graph.T_component_map.begin(), graph.T_component_map.end());
  EXPECT_LT(RelativeError(est, truth), 1e-3);
}

TEST(FleetGraph, AStrongEdgeIsKeptWhereAWeakEdgeBesideItIsOff) {
  // Three maps. Pair 1-2 is 0.4 m off (a corridor's aliasing: within the triangle's doubled
  // tolerance, beyond an edge's 0.25 m) with weak walls (0.80); pair 0-2 is right with strong walls
  // (0.99) but a low omega. The solve then sides with 1-2, and 0-2 is the edge in error.
  std::mt19937 rng(8);
  const auto truth = RandomPoses(3, rng);
  const auto outcomes = [&] {
    std::vector<PairOutcome> pairs = {Outcome(0, 1, truth, std::nullopt),
                                      Outcome(0, 2, truth, std::nullopt),
                                      Outcome(1, 2, truth, std::nullopt)};
    for (PairOutcome& p : pairs) {
      p.hypotheses.resize(1);  // the truth only
      p.hypotheses[0].wall_agreement = 0.99;
    }
    pairs[1].hypotheses[0].omega = 0.05;
    pairs[2].hypotheses[0].T_a_b = pairs[2].hypotheses[0].T_a_b * Pose2(0.4, 0.0, 0.0);
    pairs[2].hypotheses[0].wall_agreement = 0.80;
    return pairs;
  };
  const auto error_of_map2_m = [&](const FleetGraph& graph) {
    const Pose2 T_0_2 = graph.T_component_map[0].inverse() * graph.T_component_map[2];
    return ((truth[0].inverse() * truth[2]).inverse() * T_0_2).translation_m().norm();
  };

  // With the rule off (no edge is weak), the edge in error is rejected: map 2 follows the weak
  // edge.
  std::vector<PairOutcome> plain = outcomes();
  const FleetGraph plain_graph = SolveFleetGraph(3, plain, 0, PoseGraphOptions{});
  EXPECT_FALSE(plain[1].accepted) << plain[1].note;
  EXPECT_NEAR(error_of_map2_m(plain_graph), 0.4, 0.05);

  std::vector<PairOutcome> pairs = outcomes();
  const FleetGraph graph = SolveFleetGraph(3, pairs, 0, PoseGraphOptions{}, {}, {}, {}, 0.89);
  EXPECT_TRUE(pairs[0].accepted) << pairs[0].note;
  EXPECT_TRUE(pairs[1].accepted) << pairs[1].note;
  EXPECT_FALSE(pairs[2].accepted);
  EXPECT_NE(pairs[2].note.find("stronger walls (0.99)"), std::string::npos) << pairs[2].note;
  EXPECT_LT(error_of_map2_m(graph), 1e-3);
}

}  // namespace
}  // namespace fleetmerge
