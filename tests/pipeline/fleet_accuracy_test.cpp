// The accuracy suite of issue 4: seeded simulated fleets (sim/simulation.hpp) on six real
// buildings and on synthetic offices, 3 to 8 robots each, one case with little overlap, one with
// different resolutions and two with a robot from a foreign building, merged by MergeFleet and
// scored by Evaluate against the simulator's ground truth. Asserted over all cases: no false
// merge, and at least 95 % (the target) of the truly overlapping pairs within the coarse
// tolerance (1 deg, 3 cells). The measured rates are in docs/accuracy.md, "Accuracy suite". The
// fine-tolerance rate (0.25 deg, 1 cell) is printed, not asserted.
//
// Willow Garage is printed separately and not asserted: the method fails there today (see
// docs/accuracy.md, "Accuracy suite").
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/map_io.hpp"
#include "pipeline/fleet_merge.hpp"
#include "sim/evaluation.hpp"
#include "sim/simulation.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

struct SuiteCase {
  SuiteCase(std::string building, int robots, std::uint32_t seed)
      : building(std::move(building)), robots(robots), seed(seed) {}
  SuiteCase& LittleOverlap() { return little_overlap = true, *this; }
  SuiteCase& Resolutions(std::vector<double> r) { return resolutions_m = std::move(r), *this; }
  SuiteCase& Foreign(std::string f) { return foreign = std::move(f), *this; }
  std::string Label() const {
    return building + ", " + std::to_string(robots) + " robots, seed " + std::to_string(seed) +
           (little_overlap ? ", little overlap" : "") +
           (resolutions_m.size() > 1 ? ", mixed resolutions" : "") +
           (foreign.empty() ? "" : ", foreign " + foreign);
  }

  std::string building;  // a map in ../shared/data/maps (without .yaml), or "office"
  int robots;
  std::uint32_t seed;
  bool little_overlap = false;
  std::vector<double> resolutions_m = {0.05};
  std::string foreign;  // "" none, "office" a synthetic office of another seed, else a map
};

// Robots explore 100 m each: a mission's worth of a floor, so that most robots share a good part
// of it (the little-overlap case is the exception).
constexpr double kPathLength_m = 100.0;

// The target.
constexpr double kAssertedCoarseRate = 0.95;

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
  std::printf("%-52s pairs %3d  coarse %3d  fine %3d  false merges %d  missed %zu  components %d\n",
              c.Label().c_str(), s.scored_pairs, s.coarse_pairs, s.fine_pairs, s.false_merges,
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
      {"office", 4, 1},
      {"office", 4, 2},
      {"office", 6, 3},
      SuiteCase("office", 4, 4).LittleOverlap(),
      SuiteCase("office", 4, 5).Resolutions({0.05, 0.10, 0.05, 0.10}),
      SuiteCase("office", 4, 6).Foreign("office"),
  };
  const bool real = testing::SharedMapsDir().has_value();
  if (real) {
    const std::vector<SuiteCase> real_cases = {
        {"intel_lab", 8, 1},
        {"intel_lab", 3, 2},
        {"aces3_austin", 5, 1},
        {"aces3_austin", 5, 2},
        {"mit_csail", 6, 1},
        {"mit_csail", 4, 2},
        {"stata_basement", 4, 1},
        {"stata_basement", 5, 2},
        {"mit_building_31", 3, 1},
        {"mit_building_31", 5, 2},
        {"gdc_floor1_full", 5, 1},
        {"gdc_floor1_full", 4, 2},
        SuiteCase("stata_basement", 4, 3).Foreign("intel_lab"),
    };
    cases.insert(cases.end(), real_cases.begin(), real_cases.end());
  } else {
    std::printf("SKIPPED the real buildings: %s\n", testing::SharedMapsDirDescription().c_str());
  }
  // The sanitizer build runs the first cases only (FLEETMERGE_TEST_SCALE).
  cases.erase(cases.begin() + testing::ScaledCount(static_cast<int>(cases.size()), 2), cases.end());
  Tally tally;
  for (const auto& c : cases) tally.Add(RunCase(c));
  PrintTally("suite", tally);
  ASSERT_GT(tally.scored, 0);
  EXPECT_GE(tally.coarse, kAssertedCoarseRate * tally.scored) << "coarse success fell";
  EXPECT_EQ(tally.false_merges, 0);
}

// Not asserted: where the method fails today, printed so that progress shows.
TEST(FleetAccuracySuite, KnownHardBuildingReported) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  Tally tally;
  for (std::uint32_t seed = 1; seed <= std::uint32_t(testing::ScaledCount(2, 1)); ++seed) {
    tally.Add(RunCase({"willow-full-0.05", 5, seed}));
  }
  PrintTally("willow (not asserted)", tally);
  EXPECT_EQ(tally.false_merges, 0);
}

}  // namespace
}  // namespace fleetmerge
