// The corroboration step (pipeline/corroboration.hpp) on the cases that motivated it: four
// simulated robots in a synthetic office and a fifth robot that explored another synthetic
// office. The foreign map can match one robot's map by chance above the per-pair thresholds, an
// edge no cycle can check; the other robots that see the same place contradict it, so it is split
// off, or, where none of them overlaps it enough to judge, the lone-link check
// (pipeline/weak_bridges.hpp) cuts the weak bridge. The split itself is also checked on hand-made
// verdicts: a lone map, a group of maps joined by consistent wrong edges, and ties.
#include "pipeline/corroboration.hpp"

#include <gtest/gtest.h>

#include "pipeline/fleet_merge.hpp"
#include "sim/simulation.hpp"

namespace fleetmerge {
namespace {

struct ForeignCase {
  SimulatedCase sim;
  FleetResult result;
};

// Per map, how many of the judged pairs it is in support (agree) and conflict.
struct Tally {
  int supporters = 0;
  int conflicts = 0;
};

std::vector<Tally> TallyPerMap(const std::vector<PairVerdict>& verdicts, int map_count) {
  std::vector<Tally> per_map(map_count);
  for (const PairVerdict& v : verdicts) {
    for (const int m : {v.a, v.b}) (v.agrees ? per_map[m].supporters : per_map[m].conflicts)++;
  }
  return per_map;
}

ForeignCase MergeWithForeignOffice(std::uint32_t seed) {
  SimulationOptions options;  // the defaults of `fleetmerge simulate --seed S`
  options.seed = seed;
  ForeignCase c{SimulateFleet(OfficeBuilding(seed), options, OfficeBuilding(105, "foreign")), {}};
  std::vector<const OccupancyGrid*> maps;
  for (const auto& m : c.sim.maps) maps.push_back(&m);
  c.result = MergeFleet(maps, 0, FleetOptions{});
  return c;
}

class ForeignOffice : public ::testing::TestWithParam<std::uint32_t> {};

TEST_P(ForeignOffice, ChanceEdgeIsDetachedAndTheBuildingStaysWhole) {
  const ForeignCase c = MergeWithForeignOffice(GetParam());
  ASSERT_EQ(c.sim.names.size(), 5u);
  const auto& component_of = c.result.component_of;
  for (int m = 1; m < 4; ++m) EXPECT_EQ(component_of[m], component_of[0]) << c.sim.names[m];
  EXPECT_NE(component_of[4], component_of[0]) << "the foreign map was merged";

  // Every foreign pair that passed the per-pair thresholds was cut: by its triangles before the
  // solve ("hypothesis k contradicted by n more triangles ..."), by the pairs that overlap once
  // the graph is solved ("... is contradicted by n of the pairs ..."), or as a weak lone link
  // ("the only link between two groups ..."; which one comes first depends on the chance edge the
  // search finds, and that differs between compilers).
  const FleetOptions defaults;
  for (const PairOutcome& p : c.result.pairs) {
    if (p.b != 4) continue;
    EXPECT_FALSE(p.accepted);
    const bool passed = p.best_omega() >= defaults.omega_threshold &&
                        p.wall_agreement >= defaults.min_wall_agreement &&
                        p.overlap_cells >= defaults.min_overlap_cells;
    if (passed) {
      const bool cut = p.note.find("contradicted by") != std::string::npos ||
                       p.note.find("the only link between two groups") != std::string::npos;
      EXPECT_TRUE(cut) << p.note;
    }
  }

  // Placed by any hypothesis of its pairs with the building's robots (chance matches), the
  // foreign map is split off, and only it, wherever the robots that see the same place
  // contradict it more than they support it.
  int contradicted = 0, split_off = 0;
  std::vector<MapWalls> walls;
  for (const OccupancyGrid& map : c.result.maps) walls.emplace_back(map);
  for (const PairOutcome& p : c.result.pairs) {
    if (p.b != 4) continue;
    for (const PairHypothesis& h : p.hypotheses) {
      FleetGraph forced{c.result.component_of, {}, c.result.T_component_map, c.result.placed_by};
      forced.component_of[4] = forced.component_of[p.a];
      forced.T_component_map[4] = forced.T_component_map[p.a] * h.T_a_b;
      const auto verdicts =
          JudgeSolvedPairs(c.result.maps, walls, c.result.pairs, forced, defaults.min_overlap_cells,
                           defaults.min_wall_agreement, defaults.pose_graph);
      const Tally foreign = TallyPerMap(verdicts, 5)[4];
      // Overlapping nobody enough, or supported by a robot that agrees by chance as often as
      // contradicted: corroboration cannot tell (the lone-link check's case).
      if (foreign.conflicts <= foreign.supporters) continue;
      ++contradicted;
      const auto split = MostContradictedSplit(verdicts, forced.component_of);
      split_off += split && split->detached == std::vector<int>{4};
    }
  }
  EXPECT_GT(contradicted, 0);
  EXPECT_EQ(split_off, contradicted);

  // After the step every map of the building is corroborated and the foreign one is alone.
  FleetGraph graph{c.result.component_of, {}, c.result.T_component_map, c.result.placed_by};
  // On two threads: the verdicts must not depend on the count.
  const auto verdicts =
      JudgeSolvedPairs(c.result.maps, walls, c.result.pairs, graph, defaults.min_overlap_cells,
                       defaults.min_wall_agreement, defaults.pose_graph, /*threads=*/2);
  EXPECT_FALSE(MostContradictedSplit(verdicts, graph.component_of).has_value());
  const auto per_map = TallyPerMap(verdicts, 5);
  for (int m = 0; m < 4; ++m) {
    EXPECT_EQ(per_map[m].conflicts, 0) << c.sim.names[m];
    EXPECT_EQ(per_map[m].supporters, 3) << c.sim.names[m];
  }
}

INSTANTIATE_TEST_SUITE_P(Seeds, ForeignOffice, ::testing::Values(1u, 3u));

TEST(Corroboration, LoneMapIsSplitOffByMajorityAndTiesKeepIt) {
  // Maps 0, 1, 2 agree; map 3 conflicts with 0 and 1, agrees with 2.
  const std::vector<int> one_component = {0, 0, 0, 0};
  const auto split = MostContradictedSplit(
      {{0, 1, true}, {0, 2, true}, {1, 2, true}, {0, 3, false}, {1, 3, false}, {2, 3, true}},
      one_component);
  ASSERT_TRUE(split.has_value());
  EXPECT_EQ(split->detached, std::vector<int>{3});
  EXPECT_EQ(split->conflicts, 2);
  EXPECT_EQ(split->supporters, 1);
  // One conflict, one support: a pair search can miss a true pose, the map stays.
  EXPECT_FALSE(MostContradictedSplit({{0, 1, true}, {0, 2, false}, {1, 2, true}}, {0, 0, 0}));
  EXPECT_FALSE(MostContradictedSplit({}, {0, 0}));
}

TEST(Corroboration, SupportOverMoreCellsKeepsTheMap) {
  // Map 3 conflicts with maps 0 and 1 over slivers (7,000 and 9,000 cells) and agrees with map 2
  // over most of it (86,000): it stays. Where the conflicts cover more cells, it is split off.
  std::vector<PairVerdict> verdicts = {{0, 1, true, 0.99, 100000}, {0, 2, true, 0.99, 90000},
                                       {1, 2, true, 0.99, 80000},  {0, 3, false, 0.5, 7000},
                                       {1, 3, false, 0.6, 9000},   {2, 3, true, 0.97, 86000}};
  EXPECT_FALSE(MostContradictedSplit(verdicts, {0, 0, 0, 0}));
  verdicts.back().overlap_cells = 12000;
  const auto split = MostContradictedSplit(verdicts, {0, 0, 0, 0});
  ASSERT_TRUE(split.has_value());
  EXPECT_EQ(split->detached, std::vector<int>{3});
  EXPECT_EQ(split->conflict_cells, 16000);
  EXPECT_EQ(split->supporter_cells, 12000);
}

TEST(Corroboration, GroupJoinedByConsistentWrongEdgesIsSplitOff) {
  // Maps 0-2 of one building, 3-4 of another that agree with each other and (by chance, weaker
  // walls) with map 0; maps 1 and 2 contradict both. Detaching a single map resolves nothing
  // (each has as many supporters as conflicts); the splits {3, 4} and {1, 2} both cut four
  // conflicts and two supporters, and the weaker walls name {3, 4}.
  const std::vector<PairVerdict> verdicts = {
      {0, 1, true, 0.99}, {0, 2, true, 0.98}, {1, 2, true, 0.99}, {3, 4, true, 1.0},
      {0, 3, true, 0.81}, {0, 4, true, 0.82}, {1, 3, false, 0.3}, {1, 4, false, 0.2},
      {2, 3, false, 0.4}, {2, 4, false, 0.3}};
  const auto split = MostContradictedSplit(verdicts, {0, 0, 0, 0, 0});
  ASSERT_TRUE(split.has_value());
  EXPECT_EQ(split->detached, (std::vector<int>{3, 4}));
  EXPECT_EQ(split->conflicts, 4);
  EXPECT_EQ(split->supporters, 2);
  // Limited to single maps (as for large components) nothing is split.
  EXPECT_FALSE(MostContradictedSplit(verdicts, {0, 0, 0, 0, 0}, 1));
}

TEST(Corroboration, SplitsStayWithinTheirComponent) {
  // Two components; only component 1 (maps 2-4) has a contradicted map.
  const auto split = MostContradictedSplit(
      {{0, 1, true}, {2, 3, true}, {2, 4, false}, {3, 4, false}}, {0, 0, 1, 1, 1});
  ASSERT_TRUE(split.has_value());
  EXPECT_EQ(split->detached, std::vector<int>{4});
}

}  // namespace
}  // namespace fleetmerge
