// Evaluate() against oracles: a report built from the true poses (in any merged frame) scores
// 100 % with zero errors; one map's pose perturbed by a known rigid motion gives exactly that
// yaw and translation error, and the displacement computed here by brute force, on its pairs
// only; maps of two buildings in one component are false merges; a map left alone is missed;
// names that do not match fail naming both files.
//
// Cases: 4 robots cut (CutFleet) from a synthetic office, plus 2 from a second office.
#include "sim/evaluation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/error.hpp"
#include "sim/cut_fleet_case.hpp"
#include "sim/ground_truth_pair.hpp"
#include "sim/synthetic_office.hpp"

namespace fleetmerge {
namespace {

// Maps of the truth and their grids (same order).
struct Case {
  GroundTruth truth;
  std::vector<OccupancyGrid> grids;
  std::vector<const OccupancyGrid*> Pointers() const {
    std::vector<const OccupancyGrid*> p;
    for (const auto& g : grids) p.push_back(&g);
    return p;
  }
};

void AddBuilding(Case& c, const std::string& building, std::uint32_t seed, int robots,
                 const std::string& prefix) {
  const OccupancyGrid floor = GenerateOfficeFloor(OfficeOptions{}, seed);
  std::mt19937 rng(seed);
  const GroundTruthFleet fleet = CutFleet(floor, robots, rng);
  std::vector<std::string> names;
  c.truth.buildings.push_back({building, "synthetic office seed " + std::to_string(seed)});
  for (int k = 0; k < robots; ++k) {
    names.push_back(prefix + std::to_string(k + 1));
    c.truth.maps.push_back(
        {names.back(), names.back() + ".yaml", building, 0.05, fleet.T_building_map[k]});
    c.grids.push_back(fleet.maps[k]);
  }
  for (const TruthOverlap& o : TrueOverlaps(floor, fleet.maps, names, fleet.T_building_map)) {
    c.truth.overlaps.push_back(o);
  }
}

const Case& OneBuilding() {
  static const Case c = [] {
    Case c;
    AddBuilding(c, "office", 3, 4, "robot");
    return c;
  }();
  return c;
}

const Case& TwoBuildings() {
  static const Case c = [] {
    Case c;
    AddBuilding(c, "office", 3, 4, "robot");
    AddBuilding(c, "annex", 11, 2, "annex");
    return c;
  }();
  return c;
}

// Every map in component 0 at its true pose seen from an arbitrary merged frame.
MergeReport TrueReport(const GroundTruth& truth) {
  const Pose2 T_component_building(-7.5, 3.25, 2.0);
  MergeReport report;
  report.components.push_back({0, {}});
  for (const TruthMap& map : truth.maps) {
    report.maps.push_back({map.name, 0, T_component_building * map.T_building_map});
    report.components[0].maps.push_back(map.name);
  }
  return report;
}

Evaluation EvaluateCase(const Case& c, const MergeReport& report, const EvalOptions& options = {}) {
  return Evaluate(report, c.truth, c.Pointers(), options, "report.json", "truth.yaml");
}

TEST(EvaluationTest, CutFleetOverlapsAreAllLargeEnoughToScore) {
  // 2 x 2 tiles grown by 30 %: neighbours and diagonal tiles overlap.
  const Case& c = OneBuilding();
  ASSERT_EQ(c.truth.overlaps.size(), 6u);
  for (const TruthOverlap& o : c.truth.overlaps) {
    EXPECT_GE(o.cells, 2000) << o.a << " " << o.b;
    EXPECT_GT(o.share, 0.0);
    EXPECT_LE(o.share, 1.0);
  }
}

TEST(EvaluationTest, TruePosesScoreFullMarksWithZeroErrors) {
  const Case& c = OneBuilding();
  const Evaluation e = EvaluateCase(c, TrueReport(c.truth));
  ASSERT_EQ(e.pairs.size(), 6u);
  for (const EvalPair& p : e.pairs) {
    EXPECT_TRUE(p.scored && p.merged && p.coarse && p.fine) << p.a << " " << p.b;
    EXPECT_LT(p.yaw_error_deg, 1e-9);
    EXPECT_LT(p.translation_error_m, 1e-9);
    EXPECT_LT(p.displacement_cells, 1e-9);
  }
  EXPECT_EQ(e.summary.scored_pairs, 6);
  EXPECT_EQ(e.summary.coarse_pairs, 6);
  EXPECT_EQ(e.summary.fine_pairs, 6);
  EXPECT_EQ(e.summary.coarse_rate, 1.0);
  EXPECT_EQ(e.summary.fine_rate, 1.0);
  EXPECT_EQ(e.summary.false_merges, 0);
  EXPECT_TRUE(e.summary.missed_maps.empty());
}

TEST(EvaluationTest, PerturbedPoseGivesExactlyItsErrorOnItsPairs) {
  // robot4 (last, so always b of its pairs) is off by D in its own frame: the estimate of
  // T_a_robot4 is T_a_robot4 * D, so yaw error |yaw_D|, translation error |t_D|, and each
  // occupied cell p of robot4 moves by |D p - p|.
  const Case& c = OneBuilding();
  const Pose2 D(0.12, -0.05, 0.4 * M_PI / 180.0);
  MergeReport report = TrueReport(c.truth);
  report.maps[3].T_component_map = report.maps[3].T_component_map * D;
  const Evaluation e = EvaluateCase(c, report);

  const OccupancyGrid& b = c.grids[3];
  double sum = 0.0;
  int count = 0;
  for (int j = 0; j < b.height(); ++j) {
    for (int i = 0; i < b.width(); ++i) {
      if (b.at({i, j}) != CellState::kOccupied) continue;
      const Eigen::Vector2d p = b.geometry().CellCenter({i, j});
      sum += (D * p - p).norm();
      ++count;
    }
  }
  ASSERT_GT(count, 100);
  const double displacement_cells = sum / count / 0.05;

  int affected = 0;
  for (const EvalPair& p : e.pairs) {
    ASSERT_TRUE(p.merged);
    if (p.b == "robot4") {
      ++affected;
      EXPECT_NEAR(p.yaw_error_deg, 0.4, 1e-9);
      EXPECT_NEAR(p.translation_error_m, std::hypot(0.12, 0.05), 1e-9);
      EXPECT_NEAR(p.displacement_cells, displacement_cells, 1e-6);
      EXPECT_TRUE(p.coarse == (displacement_cells <= 3.0)) << displacement_cells;
      EXPECT_FALSE(p.fine);  // 0.4 deg > 0.25 deg
    } else {
      EXPECT_LT(p.yaw_error_deg, 1e-9);
      EXPECT_LT(p.translation_error_m, 1e-9);
      EXPECT_TRUE(p.fine);
    }
  }
  EXPECT_EQ(affected, 3);
  EXPECT_EQ(e.summary.fine_pairs, 3);
  EXPECT_DOUBLE_EQ(e.summary.fine_rate, 0.5);
  EXPECT_NEAR(e.summary.max_yaw_error_deg, 0.4, 1e-9);
}

TEST(EvaluationTest, MapsOfTwoBuildingsInOneComponentAreFalseMerges) {
  const Case& c = TwoBuildings();
  MergeReport report = TrueReport(c.truth);  // all six maps in one component
  const Evaluation e = EvaluateCase(c, report);
  // Every (office map, annex map) pair: 4 x 2.
  EXPECT_EQ(e.summary.false_merges, 8);
  for (const EvalFalseMerge& f : e.false_merges) {
    EXPECT_EQ(f.a.rfind("robot", 0), 0u);
    EXPECT_EQ(f.b.rfind("annex", 0), 0u);
  }
  // The office pairs and the annex pair are still scored (and right).
  EXPECT_EQ(e.summary.scored_pairs, 7);
  EXPECT_EQ(e.summary.fine_pairs, 7);

  // Each building in a component of its own: no false merge.
  report.components = {{0, {}}, {1, {}}};
  for (std::size_t m = 0; m < report.maps.size(); ++m) {
    report.maps[m].component = m < 4 ? 0 : 1;
    report.components[m < 4 ? 0 : 1].maps.push_back(report.maps[m].name);
  }
  EXPECT_EQ(EvaluateCase(c, report).summary.false_merges, 0);
}

TEST(EvaluationTest, MapLeftAloneIsMissedAndItsPairsUnmerged) {
  const Case& c = OneBuilding();
  MergeReport report = TrueReport(c.truth);
  report.maps[1].component = 1;  // robot2 alone
  report.components[0].maps.erase(report.components[0].maps.begin() + 1);
  report.components.push_back({1, {"robot2"}});
  const Evaluation e = EvaluateCase(c, report);
  EXPECT_EQ(e.summary.missed_maps, std::vector<std::string>{"robot2"});
  EXPECT_EQ(e.summary.scored_pairs, 6);
  EXPECT_EQ(e.summary.merged_pairs, 3);
  EXPECT_EQ(e.summary.coarse_pairs, 3);
  for (const EvalPair& p : e.pairs) {
    EXPECT_EQ(p.merged, p.a != "robot2" && p.b != "robot2");
  }
}

TEST(EvaluationTest, SmallOverlapsAreListedButNotScored) {
  // A threshold above every overlap: nothing truly overlaps, so nothing is scored or missed.
  const Case& c = OneBuilding();
  EvalOptions options;
  options.min_overlap_cells = 1LL << 40;
  MergeReport report = TrueReport(c.truth);
  const Evaluation e = EvaluateCase(c, report, options);
  EXPECT_EQ(e.summary.scored_pairs, 0);
  EXPECT_EQ(e.pairs.size(), 6u);
  for (const EvalPair& p : e.pairs) EXPECT_FALSE(p.scored);
  EXPECT_TRUE(e.summary.missed_maps.empty());
}

TEST(EvaluationTest, MapsMissingFromEitherSideNameBothFiles) {
  const Case& c = OneBuilding();
  MergeReport report = TrueReport(c.truth);
  report.maps[2].name = "robot9";
  try {
    EvaluateCase(c, report);
    FAIL() << "accepted a renamed map";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "map 'robot3' of truth.yaml is not in report.json");
  }
  report.maps[2].name = "robot3";
  report.maps.push_back({"extra", 0, Pose2()});
  try {
    EvaluateCase(c, report);
    FAIL() << "accepted an extra map";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "map 'extra' of report.json is not in truth.yaml");
  }
}

}  // namespace
}  // namespace fleetmerge
