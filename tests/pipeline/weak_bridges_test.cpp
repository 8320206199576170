// Lone links (pipeline/weak_bridges.hpp): which accepted edges are bridges and miss the standard
// of a lone link, on hand-made pair outcomes; and the simulated case that showed the need: four
// robots in a synthetic office with little overlap and a fifth from another office, whose map
// matched one robot's by chance (omega 0.938, walls 0.861, 6600 cells) and was merged.
#include "pipeline/weak_bridges.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pipeline/fleet_merge.hpp"
#include "sim/simulation.hpp"

namespace fleetmerge {
namespace {

PairOutcome Edge(int a, int b, double walls) {
  PairOutcome p;
  p.a = a, p.b = b;
  p.hypotheses = {{Pose2(), 0.95}};
  p.overlap_cells = 8000;
  p.wall_agreement = walls;
  p.accepted = true;
  p.edge_hypothesis = 0;
  return p;
}

constexpr double kStandard = 0.89;

TEST(WeakBridges, OnlyBridgesBelowTheStandardAreNamed) {
  // A triangle 0-1-2 of weak edges (each closes a cycle) and a strong pendant 3.
  std::vector<PairOutcome> pairs = {Edge(0, 1, 0.82), Edge(1, 2, 0.82), Edge(0, 2, 0.82),
                                    Edge(2, 3, 0.90)};
  EXPECT_FALSE(WeakestBridge(4, pairs, kStandard).has_value());
  // The pendant's walls below the standard: it is named.
  pairs[3].wall_agreement = 0.86;
  EXPECT_EQ(WeakestBridge(4, pairs, kStandard), 3);
  // Cut the triangle open: 0-1 and 1-2 become bridges too, the weakest walls first.
  pairs[2].accepted = false;
  pairs[0].wall_agreement = 0.81;
  EXPECT_EQ(WeakestBridge(4, pairs, kStandard), 0);
  // Rejected edges are no bridges.
  pairs[0].accepted = pairs[3].accepted = false;
  EXPECT_FALSE(WeakestBridge(4, pairs, kStandard).has_value()) << "1-2 is a two-map component";
}

TEST(AmbiguousEdges, StandOnlyWhenACycleOrAnotherPairConfirmsThem) {
  // A triangle 0-1-2 and a pendant 2-3; edges 0-1 (in the cycle) and 2-3 (a bridge) ambiguous.
  std::vector<PairOutcome> pairs = {Edge(0, 1, 0.95), Edge(1, 2, 0.95), Edge(0, 2, 0.95),
                                    Edge(2, 3, 0.95)};
  pairs[0].ambiguous = pairs[3].ambiguous = true;
  // No verdicts: the cycle confirms 0-1, nothing confirms the bridge 2-3.
  EXPECT_EQ(UnconfirmedAmbiguousEdge(4, pairs, {}), 3);
  // The bridge's own pair judged agreeing is no confirmation; a cross pair 1-3 that disagrees
  // neither; one that agrees is.
  EXPECT_EQ(UnconfirmedAmbiguousEdge(4, pairs, {{2, 3, true, 0.95}, {1, 3, false, 0.4}}), 3);
  EXPECT_FALSE(UnconfirmedAmbiguousEdge(4, pairs, {{1, 3, true, 0.95}}).has_value());
  // An edge on another hypothesis was chosen by its cycles; a rejected one is no edge.
  pairs[3].edge_hypothesis = 1;
  EXPECT_FALSE(UnconfirmedAmbiguousEdge(4, pairs, {}).has_value());
  pairs[3].edge_hypothesis = 0;
  pairs[3].accepted = false;
  EXPECT_FALSE(UnconfirmedAmbiguousEdge(4, pairs, {}).has_value());
  // Open the cycle: 0-1 is a bridge now, and a two-map pair alone has nothing to confirm it.
  pairs[2].accepted = false;
  EXPECT_EQ(UnconfirmedAmbiguousEdge(4, pairs, {}), 0);
  EXPECT_EQ(UnconfirmedAmbiguousEdge(2, {pairs[0]}, {}), 0);
}

TEST(WeakBridges, TwoMapComponentsAreExempt) {
  // Maps 0-1 alone and 2-3-4 in a chain, all below the standard: only the chain's edges count.
  std::vector<PairOutcome> pairs = {Edge(0, 1, 0.80), Edge(2, 3, 0.86), Edge(3, 4, 0.85)};
  EXPECT_EQ(WeakestBridge(5, pairs, kStandard), 2);
  pairs[2].accepted = false;
  EXPECT_FALSE(WeakestBridge(5, pairs, kStandard).has_value());
}

TEST(WeakBridges, BridgesToAFixedMapOnTheirBestHypothesisAreExempt) {
  // Map 0 fixed (a site map), robots 1 and 2 on it, robot 3 on robot 2: all below the standard.
  std::vector<PairOutcome> pairs = {Edge(0, 1, 0.84), Edge(0, 2, 0.85), Edge(2, 3, 0.86)};
  const std::vector<char> fixed = {1, 0, 0, 0};
  EXPECT_EQ(WeakestBridge(4, pairs, kStandard), 0);         // nothing fixed: the weakest
  EXPECT_EQ(WeakestBridge(4, pairs, kStandard, fixed), 2);  // only the robots' bridge
  pairs[2].accepted = false;
  EXPECT_FALSE(WeakestBridge(4, pairs, kStandard, fixed).has_value());
  // An edge on another hypothesis was chosen by cycles, not by its search: not exempt.
  pairs[1].hypotheses.push_back({Pose2(1.0, 0.0, 0.0), 0.93});
  pairs[1].edge_hypothesis = 1;
  EXPECT_EQ(WeakestBridge(4, pairs, kStandard, fixed), 1);
}

TEST(WeakBridges, BridgeOnAnotherHypothesisHasNoMeasuredWalls) {
  // The pair's walls belong to its best hypothesis; an edge on another one that is a bridge is
  // named whatever they are.
  std::vector<PairOutcome> pairs = {Edge(0, 1, 0.99), Edge(1, 2, 0.99)};
  pairs[0].hypotheses.push_back({Pose2(1.0, 0.0, 0.0), 0.93});
  EXPECT_FALSE(WeakestBridge(3, pairs, kStandard).has_value());
  pairs[0].edge_hypothesis = 1;
  EXPECT_EQ(WeakestBridge(3, pairs, kStandard), 0);
}

TEST(WeakBridges, ChanceLinkOfAForeignOfficeIsRejected) {
  // `fleetmerge simulate --robots 4 --seed 64 --little-overlap --foreign-office-seed 1064
  // --path-length 100`: robot2 - robot5 reached omega 0.938, walls 0.861, 6600 cells.
  SimulationOptions options;
  options.robots = 4;
  options.seed = 64;
  options.path_length_m = 100.0;
  options.little_overlap = true;
  const SimulatedCase sim =
      SimulateFleet(OfficeBuilding(64), options, OfficeBuilding(1064, "foreign"));
  ASSERT_EQ(sim.names.size(), 5u);
  std::vector<const OccupancyGrid*> maps;
  for (const auto& m : sim.maps) maps.push_back(&m);
  const FleetOptions defaults;
  const FleetResult result = MergeFleet(maps, 0, defaults);

  bool chance_link_passed = false;
  for (const PairOutcome& p : result.pairs) {
    if (p.b != 4) continue;
    EXPECT_FALSE(p.accepted) << sim.names[p.a] << " - robot5: " << p.note;
    if (p.best_omega() >= defaults.omega_threshold &&
        p.overlap_cells >= defaults.min_overlap_cells &&
        p.wall_agreement >= defaults.min_wall_agreement) {
      chance_link_passed = true;
      EXPECT_NE(p.note.find("the only link between two groups"), std::string::npos) << p.note;
    }
  }
  EXPECT_TRUE(chance_link_passed) << "the case no longer shows a chance link";
  for (int m = 1; m < 4; ++m) {
    EXPECT_EQ(result.component_of[m], result.component_of[0]) << sim.names[m];
  }
  EXPECT_NE(result.component_of[4], result.component_of[0]) << "the foreign map was merged";

  // The building's robots stay where the truth puts them (within the coarse tolerances).
  const Pose2 T_w_0 = sim.truth.maps[0].T_building_map;
  for (int m = 1; m < 4; ++m) {
    const Pose2 T_0_m = T_w_0.inverse() * sim.truth.maps[m].T_building_map;
    const Pose2 error = T_0_m.inverse() * result.T_component_map[m];
    EXPECT_LT(std::abs(error.yaw_rad()), 1.0 * M_PI / 180.0) << sim.names[m];
    EXPECT_LT(error.translation_m().norm(), 0.15) << sim.names[m];
  }
}

}  // namespace
}  // namespace fleetmerge
