// Known start poses (MergeFleet with `priors`, pipeline/pose_priors.hpp): robots simulated in a
// real building (gdc_floor1_full), merged against the building's map fixed at a site pose, or
// among themselves. Asserted against the simulation's truth:
//  - priors off by 0.3 m and 5 deg with sigma (0.5 m, 10 deg): every pair that is right without
//    priors stays accepted and right, every robot within 1 deg and 3 cells of the truth (among
//    themselves without a fixed map: relative to each other, and the merged frame is the site's);
//  - a robot that explored another building (intel_lab, a wing nobody else saw) is placed at its
//    prior, reported as placed by it, instead of left unmerged;
//  - a wrong prior (5 m off, sigma 0.2 m) gets its pair with the fixed map refused, with a note
//    naming the priors and the distance in sigmas.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "io/map_io.hpp"
#include "pipeline/fleet_merge.hpp"
#include "pipeline/pose_priors.hpp"
#include "refine/pose_graph.hpp"
#include "sim/simulation.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The site frame: the building's map sits there at a turn that is no multiple of 90 deg.
const Pose2 kT_site_building(7.3, -12.1, 0.6);
// The other building's wing, far beyond gdc's walls in the site frame.
const Pose2 kT_site_wing(260.0, 40.0, -0.4);

struct SiteCase {
  OccupancyGrid base;  // the building's map as it is
  SimulatedCase sim;   // robots; with a foreign robot last (it explored intel_lab)
  bool foreign = false;
};

SiteCase SimulateSite(int robots, std::uint32_t seed, bool foreign) {
  const auto dir = *testing::SharedMapsDir();
  const auto path = dir / "gdc_floor1_full.yaml";
  SiteCase c{LoadMap(path).grid, {}, foreign};
  SimulationOptions options;
  options.robots = robots;
  options.seed = seed;
  options.path_length_m = 100.0;
  std::optional<SimulationBuilding> other;
  if (foreign) {
    const auto other_path = dir / "intel_lab.yaml";
    other = SimulationBuilding{LoadMap(other_path).grid, "foreign", other_path.string()};
  }
  c.sim = SimulateFleet({c.base, "gdc_floor1_full", path.string()}, options, other);
  return c;
}

// Where robot r's map truly is in the site frame.
Pose2 TrueT_site_robot(const SiteCase& c, int r) {
  const bool in_wing = c.foreign && r + 1 == static_cast<int>(c.sim.maps.size());
  return (in_wing ? kT_site_wing : kT_site_building) * c.sim.truth.maps[r].T_building_map;
}

// A prior off the truth by 0.3 m (in a direction that turns with r) and +-5 deg.
PosePrior SlightlyOffPrior(const SiteCase& c, int r) {
  const Pose2 truth = TrueT_site_robot(c, r);
  const double direction = 0.7 + r * 2.1;
  return {Pose2(truth.x_m() + 0.3 * std::cos(direction), truth.y_m() + 0.3 * std::sin(direction),
                truth.yaw_rad() + (r % 2 ? -5.0 : 5.0) * kDeg),
          0.5, 10.0 * kDeg};
}

// Yaw error (deg) and the displacement (cells) of the centre of robot r's known cells, for the
// estimate T_x_robot against the truth T_x_robot (x: any frame).
std::pair<double, double> PoseError(const SiteCase& c, int r, const Pose2& estimate,
                                    const Pose2& truth) {
  const OccupancyGrid& robot = c.sim.maps[r];
  const cv::Rect known = cv::boundingRect(robot.cells());
  const Eigen::Vector2d centre =
      robot.geometry().CellCenter({known.x + known.width / 2, known.y + known.height / 2});
  return {std::abs(WrapAngle(estimate.yaw_rad() - truth.yaw_rad())) / kDeg,
          (estimate * centre - truth * centre).norm() / robot.geometry().resolution_m()};
}

// Whether pair p is accepted at a hypothesis that agrees with the truth (the fleet's edge
// tolerances). `truth[m]` is map m's true pose in the site frame.
bool RightPair(const PairOutcome& p, const std::vector<Pose2>& truth) {
  if (!p.accepted) return false;
  const PoseGraphEdge edge{p.a, p.b, p.hypotheses[p.edge_hypothesis].T_a_b, 1.0, 0.0, 0.0};
  const EdgeError e = EdgeDisagreement(edge, truth[p.a], truth[p.b]);
  const PoseGraphOptions tolerance;
  return e.yaw_rad <= tolerance.max_edge_yaw_error_rad &&
         e.translation_m <= tolerance.max_edge_translation_error_m;
}

struct SiteMerge {
  std::vector<const OccupancyGrid*> maps;  // the base first (when there is one), then the robots
  std::vector<Pose2> truth;                // per map, in the site frame
  FixedPoses fixed;
  PosePriors priors;
  int first_robot = 0;
};

SiteMerge WithBase(const SiteCase& c) {
  SiteMerge s;
  s.maps = {&c.base};
  s.truth = {kT_site_building};
  s.first_robot = 1;
  for (int r = 0; r < static_cast<int>(c.sim.maps.size()); ++r) {
    s.maps.push_back(&c.sim.maps[r]);
    s.truth.push_back(TrueT_site_robot(c, r));
  }
  s.fixed.resize(s.maps.size());
  s.fixed[0] = kT_site_building;
  return s;
}

void WithSlightlyOffPriors(const SiteCase& c, SiteMerge& s) {
  s.priors.assign(s.maps.size(), std::nullopt);
  for (int r = 0; r < static_cast<int>(c.sim.maps.size()); ++r) {
    s.priors[s.first_robot + r] = SlightlyOffPrior(c, r);
  }
}

// 4 robots (seed 1) merged with the base, without priors and with SlightlyOffPrior's; made once,
// in place (s points into c).
struct BaseMerges {
  SiteCase c;
  SiteMerge s;  // with the priors
  FleetResult without, with;
};
const BaseMerges& SlightlyOffPriorsOnTheBase() {
  static const BaseMerges* const merges = [] {
    auto* m = new BaseMerges;
    m->c = SimulateSite(4, 1, false);
    m->s = WithBase(m->c);
    m->without = MergeFleet(m->s.maps, 0, m->s.fixed, FleetOptions{});
    WithSlightlyOffPriors(m->c, m->s);
    m->with = MergeFleet(m->s.maps, 0, m->s.fixed, m->s.priors, FleetOptions{});
    return m;
  }();
  return *merges;
}

TEST(Priors, SlightlyOffPriorsKeepEveryRightPairAndPlaceEveryRobot) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const BaseMerges& m = SlightlyOffPriorsOnTheBase();
  const SiteCase& c = m.c;
  const SiteMerge& s = m.s;
  const FleetResult& without = m.without;
  const FleetResult& with = m.with;
  int right = 0;
  for (std::size_t k = 0; k < without.pairs.size(); ++k) {
    const PairOutcome& p = with.pairs[k];
    std::printf("pair %d-%d: without priors %s, with priors %s (%s)\n", p.a + 1, p.b + 1,
                RightPair(without.pairs[k], s.truth) ? "right" : "not accepted right",
                RightPair(p, s.truth) ? "right" : "not accepted right", p.note.c_str());
    if (!RightPair(without.pairs[k], s.truth)) continue;
    ++right;
    EXPECT_TRUE(RightPair(p, s.truth)) << "pair " << p.a + 1 << "-" << p.b + 1 << ": " << p.note;
  }
  EXPECT_GE(right, 4);  // not vacuous: every robot has a right pair with the base or another
  EXPECT_EQ(with.T_component_map[0].x_m(), kT_site_building.x_m());  // the base never moves
  EXPECT_EQ(with.T_component_map[0].yaw_rad(), kT_site_building.yaw_rad());
  EXPECT_EQ(with.placed_by[0], PlacedBy::kFixed);
  for (int r = 0; r < static_cast<int>(c.sim.maps.size()); ++r) {
    const auto [yaw_deg, cells] = PoseError(c, r, with.T_component_map[r + 1], s.truth[r + 1]);
    std::printf("slightly off priors, fixed base: robot%d %.3f deg, %.2f cells (%s)\n", r + 1,
                yaw_deg, cells, PlacedByName(with.placed_by[r + 1]));
    EXPECT_EQ(with.component_of[r + 1], with.component_of[0]);
    EXPECT_EQ(with.placed_by[r + 1], PlacedBy::kPairs);
    EXPECT_LT(yaw_deg, 1.0) << "robot" << r + 1;
    EXPECT_LT(cells, 3.0) << "robot" << r + 1;
  }
}

// Where pairs place a robot, priors a few decimetres off must not move it: they are metres-level
// knowledge and the pairs are good to a tenth of a cell, so the pose graph weighs a prior at
// kPriorCostScale against the pairs (pipeline/fleet_graph.hpp). With the base fixed in both runs
// the frame is the same, so each robot's pose with priors is compared with its pose without.
TEST(Priors, SlightlyOffPriorsDoNotMoveWhatThePairsPlace) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const BaseMerges& m = SlightlyOffPriorsOnTheBase();
  for (int r = 0; r < static_cast<int>(m.c.sim.maps.size()); ++r) {
    ASSERT_EQ(m.without.placed_by[r + 1], PlacedBy::kPairs) << "robot" << r + 1;
    ASSERT_EQ(m.with.placed_by[r + 1], PlacedBy::kPairs) << "robot" << r + 1;
    const auto [yaw_deg, cells] =
        PoseError(m.c, r, m.with.T_component_map[r + 1], m.without.T_component_map[r + 1]);
    std::printf("robot%d with priors against without: %.4f deg, %.3f cells\n", r + 1, yaw_deg,
                cells);
    EXPECT_LT(yaw_deg, 0.01) << "robot" << r + 1;
    EXPECT_LT(cells, 0.05) << "robot" << r + 1;
  }
}

TEST(Priors, WithoutAFixedMapTheMergedFrameIsTheSiteFrame) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const SiteCase c = SimulateSite(4, 1, false);
  std::vector<const OccupancyGrid*> maps;
  PosePriors priors;
  for (int r = 0; r < static_cast<int>(c.sim.maps.size()); ++r) {
    maps.push_back(&c.sim.maps[r]);
    priors.push_back(SlightlyOffPrior(c, r));
  }
  const FleetResult result = MergeFleet(maps, 0, FixedPoses{}, priors, FleetOptions{});
  ASSERT_EQ(result.components.size(), 1u);  // the priors tie every robot in
  EXPECT_EQ(result.placed_by[0], PlacedBy::kReference);
  int by_pairs = 0;
  for (int r = 0; r < static_cast<int>(maps.size()); ++r) {
    // Among themselves as the pairs put them (robot1's frame is the reference)...
    const Pose2 estimate = result.T_component_map[0].inverse() * result.T_component_map[r];
    const Pose2 truth = TrueT_site_robot(c, 0).inverse() * TrueT_site_robot(c, r);
    const auto [yaw_deg, cells] = PoseError(c, r, estimate, truth);
    // ...and in the site frame as the priors, 0.3 m and 5 deg off each, put the whole fleet.
    const auto [site_yaw_deg, site_cells] =
        PoseError(c, r, result.T_component_map[r], TrueT_site_robot(c, r));
    std::printf(
        "slightly off priors, no fixed map: robot%d %.3f deg, %.2f cells relative to robot1; "
        "%.2f deg, %.1f cells from the truth in the site frame (%s)\n",
        r + 1, yaw_deg, cells, site_yaw_deg, site_cells, PlacedByName(result.placed_by[r]));
    if (result.placed_by[r] == PlacedBy::kPrior) {
      // No pair links it to robot1's group (without the base, robot2 shares too little with the
      // others, measured): it sits at its prior, 0.3 m and 5 deg off, as given.
      const Pose2& prior = priors[r]->T_site_map;
      EXPECT_NEAR(result.T_component_map[r].x_m(), prior.x_m(), 1e-6);
      EXPECT_NEAR(result.T_component_map[r].y_m(), prior.y_m(), 1e-6);
      EXPECT_NEAR(WrapAngle(result.T_component_map[r].yaw_rad() - prior.yaw_rad()), 0.0, 1e-8);
      continue;
    }
    ++by_pairs;
    EXPECT_LT(yaw_deg, 1.0) << "robot" << r + 1;
    EXPECT_LT(cells, 3.0) << "robot" << r + 1;
    // In the site frame, not robot1's (tens of metres off): as far as the priors' mean error.
    EXPECT_LT(site_cells * c.sim.maps[r].geometry().resolution_m(), 0.3) << "robot" << r + 1;
    EXPECT_LT(site_yaw_deg, 5.0) << "robot" << r + 1;
  }
  EXPECT_GE(by_pairs, 3);
}

TEST(Priors, ARobotThatOverlapsNobodyIsPlacedByItsPrior) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const SiteCase c = SimulateSite(3, 1, true);
  SiteMerge s = WithBase(c);
  const int lone = static_cast<int>(s.maps.size()) - 1;  // the robot in the other building
  const FleetResult without = MergeFleet(s.maps, 0, s.fixed, FleetOptions{});
  std::printf("without priors the lone robot is in component %d of %zu (base: %d)\n",
              without.component_of[lone], without.components.size(), without.component_of[0]);
  EXPECT_NE(without.component_of[lone], without.component_of[0]);  // today: left unmerged
  WithSlightlyOffPriors(c, s);
  const FleetResult with = MergeFleet(s.maps, 0, s.fixed, s.priors, FleetOptions{});
  EXPECT_EQ(with.component_of[lone], with.component_of[0]);
  EXPECT_EQ(with.placed_by[lone], PlacedBy::kPrior);
  // No pair links it: its pose is its prior, exactly as given (in the site frame).
  const Pose2& prior = s.priors[lone]->T_site_map;
  const Pose2& placed = with.T_component_map[lone];
  std::printf("lone robot placed at (%.4f, %.4f, %.5f), prior (%.4f, %.4f, %.5f)\n", placed.x_m(),
              placed.y_m(), placed.yaw_rad(), prior.x_m(), prior.y_m(), prior.yaw_rad());
  EXPECT_NEAR(placed.x_m(), prior.x_m(), 1e-6);
  EXPECT_NEAR(placed.y_m(), prior.y_m(), 1e-6);
  EXPECT_NEAR(WrapAngle(placed.yaw_rad() - prior.yaw_rad()), 0.0, 1e-8);
  for (const PairOutcome& p : with.pairs) {
    if (p.a == lone || p.b == lone) {
      EXPECT_FALSE(p.accepted) << p.a + 1 << "-" << p.b + 1;
    }
  }
  // Composited with the rest: the site's merged map holds it.
  const FleetComponent& site = with.components[with.component_of[0]];
  EXPECT_NE(std::find(site.maps.begin(), site.maps.end(), lone), site.maps.end());
  ASSERT_TRUE(site.merged.has_value());
  for (int r = 0; r + 1 < static_cast<int>(c.sim.maps.size()); ++r) {
    const auto [yaw_deg, cells] = PoseError(c, r, with.T_component_map[r + 1], s.truth[r + 1]);
    EXPECT_LT(yaw_deg, 1.0) << "robot" << r + 1;
    EXPECT_LT(cells, 3.0) << "robot" << r + 1;
  }
}

TEST(Priors, AWrongPriorGetsItsPairRefusedWithAReason) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const SiteCase c = SimulateSite(4, 1, false);
  SiteMerge s = WithBase(c);
  const int wrong = 2;  // robot2
  s.priors.assign(s.maps.size(), std::nullopt);
  const Pose2& truth = s.truth[wrong];
  s.priors[wrong] = PosePrior{Pose2(truth.x_m() + 3.0, truth.y_m() - 4.0, truth.yaw_rad()), 0.2,
                              10.0 * kDeg};  // 5 m off
  const FleetResult without = MergeFleet(s.maps, 0, s.fixed, FleetOptions{});
  ASSERT_TRUE(RightPair(without.pairs[wrong - 1], s.truth)) << "base-robot2 is right without";
  const FleetResult with = MergeFleet(s.maps, 0, s.fixed, s.priors, FleetOptions{});
  const PairOutcome& refused = with.pairs[wrong - 1];  // pairs in row order: (0, 1), (0, 2), ...
  ASSERT_EQ(refused.a, 0);
  ASSERT_EQ(refused.b, wrong);
  std::printf("base-robot2: %s\n", refused.note.c_str());
  EXPECT_FALSE(refused.accepted);
  EXPECT_TRUE(refused.refused_by_priors);
  EXPECT_NE(refused.note.find("refused: every hypothesis contradicts the fixed pose of map 1 and "
                              "initial_pose of map 3; the nearest, hypothesis "),
            std::string::npos)
      << refused.note;
  EXPECT_NE(refused.note.find(" sigma from them ("), std::string::npos) << refused.note;
  // The other robots' pairs with the base do not involve the prior and stay right.
  for (int b = 1; b < static_cast<int>(s.maps.size()); ++b) {
    if (b == wrong) continue;
    EXPECT_EQ(RightPair(with.pairs[b - 1], s.truth), RightPair(without.pairs[b - 1], s.truth));
  }
  const auto [yaw_deg, cells] = PoseError(c, wrong - 1, with.T_component_map[wrong], truth);
  std::printf("robot2 with the wrong prior: %s, %.2f deg, %.1f cells from the truth\n",
              PlacedByName(with.placed_by[wrong]), yaw_deg, cells);
}

TEST(Priors, AReferenceThatOverlapsNobodyIsPlacedByItsPrior) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  // The robot of the other building first: the job's reference, without a fixed map. The site
  // frame is the priors', and pairs link the building's robots to each other, not to it.
  const SiteCase c = SimulateSite(5, 1, true);
  const int foreign = static_cast<int>(c.sim.maps.size()) - 1;
  std::vector<const OccupancyGrid*> maps = {&c.sim.maps[foreign]};
  PosePriors priors = {SlightlyOffPrior(c, foreign)};
  for (int r = 0; r < foreign; ++r) {
    maps.push_back(&c.sim.maps[r]);
    priors.push_back(SlightlyOffPrior(c, r));
  }
  const FleetResult result = MergeFleet(maps, 0, FixedPoses{}, priors, FleetOptions{});
  ASSERT_EQ(result.components.size(), 1u);
  int by_pairs = 0;
  for (int m = 0; m < static_cast<int>(maps.size()); ++m) {
    std::printf("map %d: %s\n", m + 1, PlacedByName(result.placed_by[m]));
    by_pairs += result.placed_by[m] == PlacedBy::kPairs;
    EXPECT_NE(result.placed_by[m], PlacedBy::kReference) << "map " << m + 1;
  }
  EXPECT_EQ(result.placed_by[0], PlacedBy::kPrior);
  EXPECT_GE(by_pairs, 3);  // the largest group, which the priors place as a whole
  const Pose2& placed = result.T_component_map[0];
  EXPECT_NEAR(placed.x_m(), priors[0]->T_site_map.x_m(), 1e-6);
  EXPECT_NEAR(placed.y_m(), priors[0]->T_site_map.y_m(), 1e-6);
}

// The only map with a prior overlaps nobody (the robot of the other building; the building's
// robots have none): it is placed at its prior all the same, as its own component in the site
// frame with its cells as its merged map, and the robots without priors come out as without it.
// So is the map of a one-map job.
TEST(Priors, TheOnlyMapWithAPriorIsPlacedByItAlone) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const SiteCase c = SimulateSite(4, 1, true);
  const int lone = static_cast<int>(c.sim.maps.size()) - 1;
  std::vector<const OccupancyGrid*> maps;
  for (const OccupancyGrid& map : c.sim.maps) maps.push_back(&map);
  PosePriors priors(maps.size());
  priors[lone] = SlightlyOffPrior(c, lone);
  const FleetResult without = MergeFleet(maps, 0, FixedPoses{}, FleetOptions{});
  const FleetResult with = MergeFleet(maps, 0, FixedPoses{}, priors, FleetOptions{});
  ASSERT_EQ(without.placed_by[lone], PlacedBy::kUnmerged);
  EXPECT_EQ(with.placed_by[lone], PlacedBy::kPrior);
  const FleetComponent& site = with.components[with.component_of[lone]];
  EXPECT_EQ(site.maps, std::vector<int>{lone});
  const Pose2& prior = priors[lone]->T_site_map;
  const auto expect_at_prior = [&](const FleetResult& result, const OccupancyGrid& map, int m) {
    const Pose2& placed = result.T_component_map[m];
    EXPECT_NEAR(placed.x_m(), prior.x_m(), 1e-9);
    EXPECT_NEAR(placed.y_m(), prior.y_m(), 1e-9);
    EXPECT_NEAR(WrapAngle(placed.yaw_rad() - prior.yaw_rad()), 0.0, 1e-12);
    const FleetComponent& component = result.components[result.component_of[m]];
    ASSERT_TRUE(component.merged.has_value()) << "the site's merged map: the map where it is";
    EXPECT_EQ(cv::countNonZero(component.merged->cells() != map.cells()), 0);
    const Pose2 T_grid = component.merged->geometry().T_map_grid();
    const Pose2 expected = prior * map.geometry().T_map_grid();
    EXPECT_NEAR((T_grid.translation_m() - expected.translation_m()).norm(), 0.0, 1e-9);
    EXPECT_NEAR(WrapAngle(T_grid.yaw_rad() - expected.yaw_rad()), 0.0, 1e-12);
  };
  expect_at_prior(with, *maps[lone], lone);
  // The robots without priors: the same components, poses, placements and merged maps.
  for (int r = 0; r < lone; ++r) {
    EXPECT_EQ(with.placed_by[r], without.placed_by[r]) << "robot" << r + 1;
    EXPECT_EQ(with.component_of[r] == with.component_of[0],
              without.component_of[r] == without.component_of[0])
        << "robot" << r + 1;
    const Pose2 d = without.T_component_map[r].inverse() * with.T_component_map[r];
    EXPECT_NEAR(d.translation_m().norm(), 0.0, 1e-9) << "robot" << r + 1;
    EXPECT_NEAR(d.yaw_rad(), 0.0, 1e-12) << "robot" << r + 1;
  }
  const FleetComponent& robots_with = with.components[with.component_of[0]];
  const FleetComponent& robots_without = without.components[without.component_of[0]];
  ASSERT_TRUE(robots_with.merged && robots_without.merged);
  EXPECT_EQ(robots_with.maps, robots_without.maps);
  EXPECT_EQ(cv::countNonZero(robots_with.merged->cells() != robots_without.merged->cells()), 0);

  const FleetResult one = MergeFleet({maps[lone]}, 0, FixedPoses{}, {priors[lone]}, FleetOptions{});
  EXPECT_EQ(one.placed_by[0], PlacedBy::kPrior);
  expect_at_prior(one, *maps[lone], 0);
}

// configs/site_with_priors.yaml in memory: run1 of the ROBOTIS corridor fixed at (10, 5, 0), runs
// 2-4 with priors; run4 shares too little with any map for a pair.
struct CorridorSite {
  std::vector<OccupancyGrid> grids;
  FixedPoses fixed;
  PosePriors priors;
  std::vector<const OccupancyGrid*> maps() const {
    std::vector<const OccupancyGrid*> out;
    for (const OccupancyGrid& g : grids) out.push_back(&g);
    return out;
  }
};

CorridorSite Corridor() {
  const auto dir = *testing::SharedMapsDir();
  CorridorSite site;
  for (int run = 1; run <= 4; ++run) {
    site.grids.push_back(
        LoadMap(dir / ("robotis_corridor_run" + std::to_string(run) + ".yaml")).grid);
  }
  site.fixed = {Pose2(10.0, 5.0, 0.0), std::nullopt, std::nullopt, std::nullopt};
  site.priors = {std::nullopt, PosePrior{Pose2(10.3, 4.7, -0.1)},
                 PosePrior{Pose2(10.0, 5.0, 0.0), 0.3, 0.1},
                 PosePrior{Pose2(10.0, 5.0, 0.0), 1.0, 0.35}};
  return site;
}

TEST(Priors, APairThatFailsTheThresholdsAnywayIsNotRefusedByThem) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  CorridorSite site = Corridor();
  // Tight enough that every hypothesis of site-run4 contradicts it: the one nearest the site's
  // pose (the fixed map's pair search, FleetOptions::fixed_map_free_penalty) is 0.66 m off.
  site.priors[3] = PosePrior{Pose2(10.0, 5.0, 0.0), 0.1, 0.02};
  const FleetResult result = MergeFleet(site.maps(), 0, site.fixed, site.priors, FleetOptions{});
  const PairOutcome& site_run4 = result.pairs[2];  // (0, 1), (0, 2), (0, 3), ...
  ASSERT_EQ(site_run4.b, 3);
  std::printf("site-run4: %s\n", site_run4.note.c_str());
  EXPECT_FALSE(site_run4.accepted);
  EXPECT_FALSE(site_run4.refused_by_priors);  // its best omega is 0.83: no pair either way
  EXPECT_EQ(site_run4.note.rfind("best omega below the threshold; also, every hypothesis "
                                 "contradicts the fixed pose of map 1 and initial_pose of map 4",
                                 0),
            0u)
      << site_run4.note;
  EXPECT_EQ(result.placed_by, (std::vector<PlacedBy>{PlacedBy::kFixed, PlacedBy::kPairs,
                                                     PlacedBy::kPairs, PlacedBy::kPrior}));
}

TEST(Priors, HypothesesThePriorsDropStayInTheResult) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const CorridorSite site = Corridor();
  const FleetResult without = MergeFleet(site.maps(), 0, site.fixed, FleetOptions{});
  const FleetResult with = MergeFleet(site.maps(), 0, site.fixed, site.priors, FleetOptions{});
  const PairOutcome& free = without.pairs[0];  // site-run2
  const PairOutcome& judged = with.pairs[0];
  ASSERT_TRUE(judged.accepted);
  ASSERT_FALSE(judged.dropped_by_priors.empty());
  // Kept and dropped together are the search's hypotheses, each dropped one in its search rank.
  EXPECT_EQ(judged.hypotheses.size() + judged.dropped_by_priors.size(), free.hypotheses.size());
  for (const PairOutcome::Dropped& d : judged.dropped_by_priors) {
    ASSERT_GE(d.search_rank, 1);
    const PairHypothesis& searched = free.hypotheses[d.search_rank - 1];
    EXPECT_EQ(d.hypothesis.omega, searched.omega);
    EXPECT_EQ(d.hypothesis.T_a_b.x_m(), searched.T_a_b.x_m());
    EXPECT_GT(d.sigmas, kPriorContradictionSigmas);
    EXPECT_NEAR(
        d.sigmas,
        SigmasFromPriors(searched.T_a_b, PosePrior{*site.fixed[0], 0.0, 0.0}, *site.priors[1]),
        1e-12);
  }
  EXPECT_NE(judged.note.find("of the search dropped"), std::string::npos) << judged.note;
  // A job names its maps in notes (FleetOptions::map_names); the library without names numbers
  // them.
  EXPECT_NE(judged.note.find("from the fixed pose of map 1 and initial_pose of map 2"),
            std::string::npos)
      << judged.note;
  FleetOptions named;
  named.map_names = {"site", "run2", "run3", "run4"};
  const FleetResult by_name = MergeFleet(site.maps(), 0, site.fixed, site.priors, named);
  EXPECT_NE(by_name.pairs[0].note.find("from the fixed pose of map 'site' and initial_pose of "
                                       "map 'run2'"),
            std::string::npos)
      << by_name.pairs[0].note;
  named.map_names.pop_back();
  EXPECT_THROW(MergeFleet(site.maps(), 0, site.fixed, site.priors, named), Error);
}

TEST(Priors, PosesKilometresApartAreRefusedBeforeAllocating) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  CorridorSite site = Corridor();
  site.priors[3]->T_site_map = Pose2(1e5, 0.0, 0.0);  // run4, 100 km off: a typo
  try {
    MergeFleet(site.maps(), 0, site.fixed, site.priors, FleetOptions{});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("compositing maps 1, 2, 3, 4 (in job order): the merged "
                                         "map would be 1999"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("check fixed poses and initial_poses"), std::string::npos);
  }
}

TEST(Priors, BadPriorsAreRefused) {
  OccupancyGrid a(GridGeometry(0.05, {4, 4}));
  OccupancyGrid b(GridGeometry(0.05, {4, 4}));
  const std::vector<const OccupancyGrid*> maps = {&a, &b};
  const auto expect_error = [&](const FixedPoses& fixed, const PosePriors& priors,
                                const std::string& what) {
    try {
      MergeFleet(maps, 0, fixed, priors, FleetOptions{});
      ADD_FAILURE() << "no error for " << what;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  PosePriors priors(2);
  priors[1] = PosePrior{Pose2(0.0, std::nan(""), 0.0)};
  expect_error({}, priors, "map 2 (in job order): initial_pose [0, nan, 0] is not finite");
  priors[1] = PosePrior{Pose2(), -0.5, 0.1};
  expect_error({}, priors, "map 2 (in job order): initial_pose_sigma [-0.5, 0.1]");
  priors[1] = PosePrior{Pose2(), 0.5, 0.0};
  expect_error({}, priors, "expected finite [metres, radians] > 0");
  priors[1] = PosePrior{Pose2()};
  FixedPoses fixed(2);
  fixed[0] = Pose2();
  fixed[1] = Pose2();
  expect_error(fixed, priors, "a fixed map has no initial_pose");
  expect_error({}, PosePriors(3), "initial poses: 3 given for 2 maps");
  priors.assign(2, std::nullopt);
  priors[1] = PosePrior{Pose2(), 0.5, 10.0};  // ten degrees written as 10
  expect_error({}, priors, "initial_pose_sigma yaw 10 rad looks like degrees (10 deg is 0.174533");
}

TEST(Priors, SigmasFromPriorsCombineBothMapsAndTheLeverArm) {
  // a at the origin, b predicted 10 m ahead; b's prior 1 m to the side of that.
  const PosePrior a{Pose2(), 0.3, 0.1};
  const PosePrior b{Pose2(10.0, 1.0, 0.0), 0.4, 0.1};
  const double lever = 0.1 * 10.0;
  EXPECT_NEAR(SigmasFromPriors(Pose2(10.0, 0.0, 0.0), a, b),
              1.0 / std::sqrt(0.09 + 0.16 + lever * lever), 1e-12);
  // Yaw: 0.5 rad off against sqrt(0.1^2 + 0.1^2).
  EXPECT_NEAR(SigmasFromPriors(Pose2(10.0, 1.0, 0.5), a, b), 0.5 / std::sqrt(0.02), 1e-12);
  // A fixed map has sigma 0: only b's own sigma (and no lever: a's yaw is exact).
  const PosePrior fixed{Pose2(), 0.0, 0.0};
  EXPECT_NEAR(SigmasFromPriors(Pose2(10.0, 0.0, 0.0), fixed, b), 1.0 / 0.4, 1e-12);
}

}  // namespace
}  // namespace fleetmerge
