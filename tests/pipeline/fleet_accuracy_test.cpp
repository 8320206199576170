// The accuracy suite of issue 4: seeded simulated fleets (pipeline/simulation.hpp) on six real
// buildings and on synthetic offices, 3 to 8 robots each, one case with little overlap, one with
// different resolutions and two with a robot from a foreign building, merged by MergeFleet and
// scored by Evaluate against the simulator's ground truth. Asserted over all cases: at least
// 95 % of the truly overlapping pairs within the coarse tolerance (1 deg, 3 cells) and no false
// merge. The fine-tolerance rate (0.25 deg, 1 cell) is printed, a target for later work.
//
// Willow Garage is printed separately and not asserted: the method fails there today (see
// README, "Accuracy suite").
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "io/map_io.hpp"
#include "pipeline/evaluation.hpp"
#include "pipeline/fleet_merge.hpp"
#include "pipeline/simulation.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

struct SuiteCase {
  std::string label;
  std::string building;  // a map in ../shared/data/maps (without .yaml), or "office"
  int robots = 4;
  std::uint32_t seed = 1;
  bool little_overlap = false;
  std::vector<double> resolutions_m = {0.05};
  std::string foreign;  // "" none, "office" a synthetic office of another seed, else a map
};

// Robots explore 100 m each: a mission's worth of a floor, so that most robots share a good part
// of it (the little-overlap case is the exception).
constexpr double kPathLength_m = 100.0;

SimulationBuilding LoadBuilding(const std::string& name, std::uint32_t office_seed) {
  if (name == "office") return OfficeBuilding(office_seed);
  const auto path = *testing::SharedMapsDir() / (name + ".yaml");
  return {LoadMap(path).grid, name, path.string()};
}

MergeReport ReportOf(const SimulatedCase& sim, const FleetResult& result) {
  MergeReport report;
  for (std::size_t c = 0; c < result.components.size(); ++c) {
    ReportComponent component;
    component.id = static_cast<int>(c);
    for (const int m : result.components[c].maps) component.maps.push_back(sim.names[m]);
    report.components.push_back(component);
  }
  for (std::size_t m = 0; m < sim.maps.size(); ++m) {
    report.maps.push_back({sim.names[m], result.component_of[m], result.T_component_map[m]});
  }
  return report;
}

struct Tally {
  int scored = 0, coarse = 0, fine = 0, false_merges = 0;
  void Add(const EvalSummary& s) {
    scored += s.scored_pairs, coarse += s.coarse_pairs, fine += s.fine_pairs;
    false_merges += s.false_merges;
  }
};

EvalSummary RunCase(const SuiteCase& c) {
  SimulationOptions options;
  options.robots = c.robots;
  options.seed = c.seed;
  options.path_length_m = kPathLength_m;
  options.little_overlap = c.little_overlap;
  options.resolutions_m = c.resolutions_m;
  std::optional<SimulationBuilding> foreign;
  if (!c.foreign.empty()) {
    foreign = LoadBuilding(c.foreign, c.seed + 1000);
    foreign->name = "foreign";
  }
  const SimulatedCase sim = SimulateFleet(LoadBuilding(c.building, c.seed), options, foreign);
  std::vector<const OccupancyGrid*> maps;
  for (const auto& m : sim.maps) maps.push_back(&m);
  const FleetResult result = MergeFleet(maps, 0, FleetOptions{});

  std::map<std::string, const OccupancyGrid*> by_name;
  for (std::size_t m = 0; m < sim.maps.size(); ++m) by_name[sim.names[m]] = &sim.maps[m];
  std::vector<const OccupancyGrid*> truth_maps;
  for (const auto& t : sim.truth.maps) truth_maps.push_back(by_name.at(t.name));
  const Evaluation e =
      Evaluate(ReportOf(sim, result), sim.truth, truth_maps, EvalOptions{}, "merge", "truth");
  const EvalSummary& s = e.summary;
  std::printf("%-34s pairs %3d  coarse %3d  fine %3d  false merges %d  missed %zu  components %d\n",
              c.label.c_str(), s.scored_pairs, s.coarse_pairs, s.fine_pairs, s.false_merges,
              s.missed_maps.size(), s.components);
  for (const auto& p : e.pairs) {
    if (p.scored && !p.coarse) {
      std::printf("    miss %s-%s (overlap %lld cells): %s\n", p.a.c_str(), p.b.c_str(),
                  p.overlap_cells, p.merged ? "merged off the truth" : "not merged");
    }
  }
  return s;
}

void PrintTally(const char* what, const Tally& t) {
  std::printf(
      "%s: %d truly overlapping pairs; coarse %d (%.1f %%), fine %d (%.1f %%); false "
      "merges %d\n",
      what, t.scored, t.coarse, 100.0 * t.coarse / std::max(t.scored, 1), t.fine,
      100.0 * t.fine / std::max(t.scored, 1), t.false_merges);
}

TEST(FleetAccuracySuite, SimulatedFleetsOnRealAndSyntheticBuildings) {
  std::vector<SuiteCase> cases = {
      {"office, 4 robots, seed 1", "office", 4, 1},
      {"office, 4 robots, seed 2", "office", 4, 2},
      {"office, 6 robots, seed 3", "office", 6, 3},
      {"office, little overlap, seed 4", "office", 4, 4, true},
      {"office, 5/10 cm robots, seed 5", "office", 4, 5, false, {0.05, 0.10, 0.05, 0.10}},
      {"office + foreign office, seed 6", "office", 4, 6, false, {0.05}, "office"},
  };
  const bool real = testing::SharedMapsDir().has_value();
  if (real) {
    const std::vector<SuiteCase> real_cases = {
        {"intel_lab, 8 robots, seed 1", "intel_lab", 8, 1},
        {"intel_lab, 3 robots, seed 2", "intel_lab", 3, 2},
        {"aces3_austin, 5 robots, seed 1", "aces3_austin", 5, 1},
        {"aces3_austin, 5 robots, seed 2", "aces3_austin", 5, 2},
        {"mit_csail, 6 robots, seed 1", "mit_csail", 6, 1},
        {"mit_csail, 4 robots, seed 2", "mit_csail", 4, 2},
        {"stata_basement, 4 robots, seed 1", "stata_basement", 4, 1},
        {"stata_basement, 5 robots, seed 2", "stata_basement", 5, 2},
        {"mit_building_31, 3 robots, seed 1", "mit_building_31", 3, 1},
        {"mit_building_31, 5 robots, seed 2", "mit_building_31", 5, 2},
        {"gdc_floor1_full, 5 robots, seed 1", "gdc_floor1_full", 5, 1},
        {"gdc_floor1_full, 4 robots, seed 2", "gdc_floor1_full", 4, 2},
        {"stata_basement + foreign intel, s3", "stata_basement", 4, 3, false, {0.05}, "intel_lab"},
    };
    cases.insert(cases.end(), real_cases.begin(), real_cases.end());
  } else {
    std::printf("SKIPPED the real buildings: %s\n", testing::SharedMapsDirDescription().c_str());
  }
  Tally tally;
  for (const auto& c : cases) tally.Add(RunCase(c));
  PrintTally("suite", tally);
  ASSERT_GT(tally.scored, 0);
  EXPECT_GE(tally.coarse, 0.95 * tally.scored) << "coarse success below 95 %";
  EXPECT_EQ(tally.false_merges, 0);
}

// Not asserted: where the method fails today, printed so that progress shows.
TEST(FleetAccuracySuite, KnownHardBuildingReported) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  Tally tally;
  for (const std::uint32_t seed : {1u, 2u}) {
    tally.Add(RunCase(
        {"willow-full-0.05, 5 robots, seed " + std::to_string(seed), "willow-full-0.05", 5, seed}));
  }
  PrintTally("willow (not asserted)", tally);
  EXPECT_EQ(tally.false_merges, 0);
}

}  // namespace
}  // namespace fleetmerge
