// The fleet simulator (sim/simulation.hpp) against oracles: its grid traversal against
// dense sampling, its lidar against brute-force ray marching, the robot maps against the
// building they were made from (through the true poses), the paths against the walls, the true
// overlaps against a brute-force recount, determinism, the foreign robot, resolutions, little
// overlap, option checks, and the default case merged by MergeFleet within 1 deg / 3 cells.
#include "sim/simulation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <set>
#include <utility>

#include "core/error.hpp"
#include "io/map_io.hpp"
#include "pipeline/fleet_merge.hpp"
#include "sim/ground_truth_pair.hpp"
#include "sim/simulation_lidar.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

SimulationOptions NoiseFree() {
  SimulationOptions o;
  o.lidar.range_noise_m = 0.0;
  o.pose_noise = PoseNoiseOptions{0.0, 0.0, 0.0, 0.0};
  return o;
}

const SimulationBuilding& Office() {
  static const SimulationBuilding office = OfficeBuilding(3);
  return office;
}

// The noise-free 4-robot case on office seed 3, made once.
const SimulatedCase& NoiseFreeCase() {
  static const SimulatedCase c = SimulateFleet(Office(), NoiseFree());
  return c;
}

// Building cells within `radius` cells of a cell in `state` (255).
cv::Mat1b NearState(const OccupancyGrid& building, CellState state, int radius) {
  cv::Mat1b mask = building.cells() == static_cast<std::uint8_t>(state);
  cv::dilate(mask, mask, cv::Mat1b::ones(2 * radius + 1, 2 * radius + 1));
  return mask;
}

struct Landing {
  int cells = 0;  // cells of the robot map in the given state
  int exact = 0;  // ... whose centre lands on a building cell in that state
  int near = 0;   // ... within `radius` building cells of one
};

// Where the cells of `map` in `state` land in the building under the true pose.
Landing LandCells(const OccupancyGrid& map, const Pose2& T_building_map,
                  const OccupancyGrid& building, CellState state, int radius) {
  const cv::Mat1b near = NearState(building, state, radius);
  Landing landing;
  for (const Eigen::Array2i& cell : map.CellsIn(state)) {
    const Eigen::Array2i b =
        building.geometry().CellOf(T_building_map * map.geometry().CellCenter(cell));
    ++landing.cells;
    if (building.StateOrUnknown(b) == state) ++landing.exact;
    if (building.geometry().Contains(b) && near(b.y(), b.x())) ++landing.near;
  }
  return landing;
}

TEST(TraverseSegment, VisitsExactlyTheCellsTheSegmentCrosses) {
  PortableRng rng(5);
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector2d p0(rng.Uniform(-5, 5), rng.Uniform(-5, 5));
    const Eigen::Vector2d p1 = trial % 10 == 0
                                   ? Eigen::Vector2d(p0.x(), rng.Uniform(-5, 5))
                                   : Eigen::Vector2d(rng.Uniform(-5, 5), rng.Uniform(-5, 5));
    std::vector<std::pair<int, int>> visited;
    double last_t = -1.0;
    TraverseSegment(p0, p1, [&](int i, int j, double t) {
      EXPECT_GE(t, last_t) << "cells come in order along the segment";
      last_t = t;
      visited.emplace_back(i, j);
      return true;
    });
    // Oracle: the cells of dense samples along the segment (a sample every 1e-4 cells).
    std::set<std::pair<int, int>> sampled;
    const int n = static_cast<int>((p1 - p0).norm() / 1e-4) + 1;
    for (int k = 0; k <= n; ++k) {
      const Eigen::Vector2d p = p0 + (p1 - p0) * (double(k) / n);
      sampled.emplace(int(std::floor(p.x())), int(std::floor(p.y())));
    }
    const std::set<std::pair<int, int>> visited_set(visited.begin(), visited.end());
    EXPECT_EQ(visited.size(), visited_set.size()) << "no cell twice";
    for (const auto& cell : sampled) {
      EXPECT_TRUE(visited_set.count(cell)) << "missed " << cell.first << "," << cell.second;
    }
    // A visited cell the samples missed can only be a corner grazed within the sample step.
    EXPECT_LE(visited_set.size(), sampled.size() + 1);
    EXPECT_EQ(visited.front(), std::make_pair(int(std::floor(p0.x())), int(std::floor(p0.y()))));
  }
}

TEST(CastScan, RangesMatchBruteForceRayMarching) {
  const OccupancyGrid& building = Office().grid;
  const double r = building.geometry().resolution_m();
  LidarOptions lidar;
  lidar.beams = 90;
  lidar.range_noise_m = 0.0;
  PortableRng rng(1);
  const std::vector<Eigen::Array2i> free_cells = building.CellsIn(CellState::kFree);
  int returns = 0;
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Array2i start = free_cells[rng.UniformInt(0, int(free_cells.size()) - 1)];
    const Pose2 T_building_sensor(building.geometry().CellCenter(start), rng.Uniform(-M_PI, M_PI));
    const LidarScan scan = CastScan(building, T_building_sensor, lidar, rng);
    for (int k = 0; k < lidar.beams; ++k) {
      const double angle = T_building_sensor.yaw_rad() + k * scan.angle_step_rad;
      const Eigen::Vector2d dir(std::cos(angle), std::sin(angle));
      // March in steps of 1 % of a cell until the first cell that is not free.
      double range = lidar.range_m;
      CellState stop = CellState::kFree;
      for (double t = 0.0; t <= lidar.range_m; t += 0.01 * r) {
        const CellState s = building.StateOrUnknown(
            building.geometry().CellOf(T_building_sensor.translation_m() + t * dir));
        if (s != CellState::kFree) {
          range = t, stop = s;
          break;
        }
      }
      ASSERT_EQ(scan.hit[k] != 0, stop == CellState::kOccupied) << "beam " << k;
      EXPECT_NEAR(scan.ranges_m[k], range, 0.011 * r) << "beam " << k;
      returns += scan.hit[k];
    }
  }
  EXPECT_GT(returns, 1000) << "the office's walls return most beams within 8 m";
}

TEST(SimulateFleet, NoiseFreeMapsShowTheBuildingAtTheTruePoses) {
  const SimulatedCase& c = NoiseFreeCase();
  ASSERT_EQ(c.maps.size(), 4u);
  for (std::size_t k = 0; k < c.maps.size(); ++k) {
    const Pose2& T = c.truth.maps[k].T_building_map;
    const Landing walls = LandCells(c.maps[k], T, Office().grid, CellState::kOccupied, 1);
    const Landing free = LandCells(c.maps[k], T, Office().grid, CellState::kFree, 1);
    std::printf("[ oracle ] %s: %d walls (%.4f exact, %.4f within 1 cell), %d free (%.4f, %.4f)\n",
                c.names[k].c_str(), walls.cells, double(walls.exact) / walls.cells,
                double(walls.near) / walls.cells, free.cells, double(free.exact) / free.cells,
                double(free.near) / free.cells);
    EXPECT_GT(walls.cells, 1000);
    EXPECT_EQ(walls.near, walls.cells) << c.names[k] << ": every wall within one cell of a wall";
    // A wall surface on a boundary of the robot's rotated grid makes a straddling cell
    // occupied: measured 71-75 % land exactly on a wall cell, all within one cell.
    EXPECT_GT(walls.exact, 0.6 * walls.cells) << c.names[k];
    EXPECT_EQ(free.near, free.cells) << c.names[k] << ": every free cell within one of free space";
    EXPECT_GT(free.exact, 0.99 * free.cells) << c.names[k];
    // The map frame is axis-aligned: the building appears rotated by -yaw in it.
    EXPECT_EQ(c.maps[k].geometry().T_map_grid().yaw_rad(), 0.0);
  }
}

// Share of all robots' wall cells within one cell of a building wall, under the true poses.
double WallsNearWalls(const SimulatedCase& c, const OccupancyGrid& building) {
  int cells = 0, near = 0;
  for (std::size_t k = 0; k < c.maps.size(); ++k) {
    const Landing walls =
        LandCells(c.maps[k], c.truth.maps[k].T_building_map, building, CellState::kOccupied, 1);
    cells += walls.cells;
    near += walls.near;
  }
  return double(near) / cells;
}

// Noise blurs the maps a little; drift bends them: walls drawn at drifted poses leave the
// building's walls, and more the stronger the drift.
TEST(SimulateFleet, PoseNoiseAndDriftDisplaceTheWalls) {
  SimulationOptions jitter;  // the defaults: range and per-scan pose noise, no drift
  SimulationOptions drift = jitter;
  drift.pose_noise.drift_xy_m = 0.01;
  drift.pose_noise.drift_yaw_deg = 0.2;
  SimulationOptions strong = drift;
  strong.pose_noise.drift_yaw_deg = 0.5;
  const double near_jitter = WallsNearWalls(SimulateFleet(Office(), jitter), Office().grid);
  const double near_drift = WallsNearWalls(SimulateFleet(Office(), drift), Office().grid);
  const double near_strong = WallsNearWalls(SimulateFleet(Office(), strong), Office().grid);
  std::printf(
      "[ noise ] walls within 1 cell of a wall: default noise %.4f, drift 0.2 deg/sqrt(m) "
      "%.3f, 0.5 deg/sqrt(m) %.3f\n",
      near_jitter, near_drift, near_strong);
  EXPECT_GT(near_jitter, 0.95);
  EXPECT_LT(near_jitter, 1.0) << "the default noise is on";
  EXPECT_LT(near_drift, near_jitter);
  EXPECT_LT(near_strong, near_drift);
}

TEST(SimulateFleet, PathsKeepTheClearanceAndStayInTheBuilding) {
  const SimulatedCase& c = NoiseFreeCase();
  const OccupancyGrid& building = Office().grid;
  cv::Mat1b free_cells = building.cells() == static_cast<std::uint8_t>(CellState::kFree);
  cv::Mat1f clearance_cells;
  cv::distanceTransform(free_cells, clearance_cells, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const double r = building.geometry().resolution_m();
  for (std::size_t k = 0; k < c.paths.size(); ++k) {
    ASSERT_GT(c.paths[k].size(), 100u) << "50 m of path, a scan every 0.2 m";
    double length_m = 0.0;
    for (std::size_t s = 0; s < c.paths[k].size(); ++s) {
      const Eigen::Array2i cell = building.geometry().CellOf(c.paths[k][s].translation_m());
      ASSERT_EQ(building.StateOrUnknown(cell), CellState::kFree) << c.names[k] << " scan " << s;
      EXPECT_GT(clearance_cells(cell.y(), cell.x()) * r, NoiseFree().clearance_m)
          << c.names[k] << " scan " << s;
      if (s == 0) continue;
      const double step_m =
          (c.paths[k][s].translation_m() - c.paths[k][s - 1].translation_m()).norm();
      EXPECT_LE(step_m, 0.2 + 2 * r) << "no jumps between scans";
      length_m += step_m;
    }
    EXPECT_GT(length_m, 0.8 * NoiseFree().path_length_m) << c.names[k];
  }
}

// Brute force: every building cell, looked up in both maps through the inverse true poses.
long long RecountOverlap(const OccupancyGrid& building, const OccupancyGrid& a, const Pose2& T_ba,
                         const OccupancyGrid& b, const Pose2& T_bb) {
  long long cells = 0;
  for (int j = 0; j < building.height(); ++j) {
    for (int i = 0; i < building.width(); ++i) {
      const Eigen::Vector2d p = building.geometry().CellCenter({i, j});
      const bool in_a =
          a.StateOrUnknown(a.geometry().CellOf(T_ba.inverse() * p)) != CellState::kUnknown;
      const bool in_b =
          b.StateOrUnknown(b.geometry().CellOf(T_bb.inverse() * p)) != CellState::kUnknown;
      cells += in_a && in_b;
    }
  }
  return cells;
}

TEST(SimulateFleet, TrueOverlapsEqualABruteForceRecount) {
  const SimulatedCase& c = NoiseFreeCase();
  ASSERT_EQ(c.truth.overlaps.size(), 6u) << "every pair of 4 maps of one building";
  for (const TruthOverlap& o : c.truth.overlaps) {
    const int a = std::stoi(o.a.substr(5)) - 1, b = std::stoi(o.b.substr(5)) - 1;
    ASSERT_LT(a, b);
    const long long recount =
        RecountOverlap(Office().grid, c.maps[a], c.truth.maps[a].T_building_map, c.maps[b],
                       c.truth.maps[b].T_building_map);
    EXPECT_EQ(o.cells, recount) << o.a << "-" << o.b;
    EXPECT_GT(o.share, 0.0);
    EXPECT_LE(o.share, 1.0);
  }
}

// SimulationOptions::fixed_base: the building's own map joins the case at the identity, and its
// true overlap with each robot is what a brute-force recount finds. The robots are the case
// without a base, bit for bit.
TEST(SimulateFleet, AFixedBaseOverlapsEachRobotAsABruteForceRecount) {
  EXPECT_FALSE(NoiseFreeCase().base.has_value()) << "no base unless asked";
  SimulationOptions options = NoiseFree();
  options.fixed_base = true;
  const SimulatedCase c = SimulateFleet(Office(), options);
  ASSERT_TRUE(c.base.has_value());
  const SimulatedBase& base = *c.base;
  const OccupancyGrid& building = Office().grid;
  EXPECT_EQ(cv::countNonZero(base.map.cells() != building.cells()), 0);
  EXPECT_EQ(base.truth.name, "base");
  EXPECT_EQ(base.truth.file, "base.yaml");
  EXPECT_EQ(base.truth.building, Office().name);
  EXPECT_EQ(base.truth.T_building_map.translation_m().norm(), 0.0);
  EXPECT_EQ(base.truth.T_building_map.yaw_rad(), 0.0);
  ASSERT_EQ(c.maps.size(), NoiseFreeCase().maps.size());
  ASSERT_EQ(base.overlaps.size(), c.maps.size());
  for (std::size_t k = 0; k < c.maps.size(); ++k) {
    EXPECT_EQ(cv::countNonZero(c.maps[k].cells() != NoiseFreeCase().maps[k].cells()), 0);
    const TruthOverlap& o = base.overlaps[k];
    EXPECT_EQ(o.a, "base");
    EXPECT_EQ(o.b, c.names[k]);
    const long long recount =
        RecountOverlap(building, building, Pose2(), c.maps[k], c.truth.maps[k].T_building_map);
    EXPECT_EQ(o.cells, recount) << o.b;
    // A robot sees only the building: nearly all its known cells are the base's known cells.
    EXPECT_GT(o.share, 0.95) << o.b;
    EXPECT_LE(o.share, 1.0) << o.b;
  }
}

// Each robot of the building gets a prior exactly `error_m` and `error_deg` off its true frame
// pose, the directions differ between robots, the foreign robot gets none, and the case is
// otherwise the case without priors.
TEST(SimulateFleet, PriorsAreTheTruePosesOffByTheGivenErrors) {
  EXPECT_TRUE(NoiseFreeCase().priors.empty()) << "no priors unless asked";
  SimulationOptions o = NoiseFree();
  o.robots = 3;
  o.path_length_m = 25.0;
  o.priors = SimulationOptions::Priors{0.3, 5.0, 0.7, 12.0};
  const SimulationBuilding foreign = OfficeBuilding(11, "foreign");
  const SimulatedCase c = SimulateFleet(Office(), o, foreign);
  ASSERT_EQ(c.priors.size(), 4u);
  EXPECT_FALSE(c.priors[3].has_value()) << "the foreign robot's building is not the site";
  std::vector<double> directions_rad;
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(c.priors[k].has_value()) << k;
    const PosePrior& prior = *c.priors[k];
    const Pose2& truth = c.truth.maps[k].T_building_map;
    const Eigen::Vector2d off_m = prior.T_site_map.translation_m() - truth.translation_m();
    EXPECT_NEAR(off_m.norm(), 0.3, 1e-9) << k;
    EXPECT_NEAR(std::abs(WrapAngle(prior.T_site_map.yaw_rad() - truth.yaw_rad())),
                5.0 * M_PI / 180.0, 1e-9)
        << k;
    EXPECT_EQ(prior.translation_sigma_m, 0.7);
    EXPECT_NEAR(prior.yaw_sigma_rad, 12.0 * M_PI / 180.0, 1e-12);
    directions_rad.push_back(std::atan2(off_m.y(), off_m.x()));
  }
  EXPECT_NE(directions_rad[0], directions_rad[1]);
  EXPECT_NE(directions_rad[1], directions_rad[2]);
  const SimulatedCase without = SimulateFleet(
      Office(),
      [&] {
        SimulationOptions plain = o;
        plain.priors.reset();
        return plain;
      }(),
      foreign);
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(cv::countNonZero(without.maps[k].cells() != c.maps[k].cells()), 0) << k;
    EXPECT_EQ(without.truth.maps[k].T_building_map.translation_m(),
              c.truth.maps[k].T_building_map.translation_m());
  }
  o.priors->sigma_m = 0.0;
  EXPECT_THROW(SimulateFleet(Office(), o), Error);
}

bool SameCells(const OccupancyGrid& a, const OccupancyGrid& b) {
  return a.cells().size() == b.cells().size() && cv::countNonZero(a.cells() != b.cells()) == 0;
}

TEST(SimulateFleet, SameSeedSameCaseWhateverTheThreads) {
  SimulationOptions one_thread;
  one_thread.robots = 3;
  one_thread.path_length_m = 20.0;
  one_thread.threads = 1;
  SimulationOptions two_threads = one_thread;
  two_threads.threads = 2;
  const SimulatedCase a = SimulateFleet(Office(), one_thread);
  const SimulatedCase b = SimulateFleet(Office(), two_threads);
  SimulationOptions other_seed = one_thread;
  other_seed.seed = 2;
  const SimulatedCase c = SimulateFleet(Office(), other_seed);
  for (int k = 0; k < 3; ++k) {
    EXPECT_TRUE(SameCells(a.maps[k], b.maps[k])) << k;
    EXPECT_EQ(a.maps[k].geometry().T_map_grid().translation_m(),
              b.maps[k].geometry().T_map_grid().translation_m());
    EXPECT_EQ(a.truth.maps[k].T_building_map.translation_m(),
              b.truth.maps[k].T_building_map.translation_m());
    EXPECT_FALSE(SameCells(a.maps[k], c.maps[k])) << "another seed, another case";
  }
  for (std::size_t k = 0; k < a.truth.overlaps.size(); ++k) {
    EXPECT_EQ(a.truth.overlaps[k].cells, b.truth.overlaps[k].cells);
  }
}

TEST(SimulateFleet, ForeignRobotMapsTheOtherBuildingAndOverlapsNothing) {
  SimulationOptions o = NoiseFree();
  o.robots = 3;
  o.path_length_m = 25.0;
  const SimulationBuilding foreign = OfficeBuilding(11, "foreign");
  const SimulatedCase c = SimulateFleet(Office(), o, foreign);
  ASSERT_EQ(c.maps.size(), 4u);
  EXPECT_EQ(c.names.back(), "robot4");
  ASSERT_EQ(c.truth.buildings.size(), 2u);
  EXPECT_EQ(c.truth.buildings[1].name, "foreign");
  EXPECT_EQ(c.truth.buildings[1].source, "synthetic office seed 11");
  EXPECT_EQ(c.truth.maps.back().building, "foreign");
  for (int k = 0; k < 3; ++k) EXPECT_EQ(c.truth.maps[k].building, "office");
  EXPECT_EQ(c.truth.overlaps.size(), 3u) << "only the pairs within the office";
  for (const auto& ov : c.truth.overlaps) EXPECT_NE(ov.b, "robot4");
  // Its map shows the foreign building, not the office.
  const Pose2& T = c.truth.maps.back().T_building_map;
  const Landing in_foreign = LandCells(c.maps.back(), T, foreign.grid, CellState::kOccupied, 1);
  const Landing in_office = LandCells(c.maps.back(), T, Office().grid, CellState::kOccupied, 1);
  EXPECT_EQ(in_foreign.near, in_foreign.cells);
  EXPECT_LT(in_office.near, 0.8 * in_office.cells);
  // Adding the foreign robot leaves the building's robots as they were.
  const SimulatedCase without = SimulateFleet(Office(), o);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(cv::countNonZero(without.maps[k].cells() != c.maps[k].cells()), 0) << k;
    EXPECT_EQ(without.truth.maps[k].T_building_map.translation_m(),
              c.truth.maps[k].T_building_map.translation_m());
  }
}

TEST(SimulateFleet, HonoursAResolutionPerRobot) {
  SimulationOptions o = NoiseFree();
  o.robots = 3;
  o.path_length_m = 25.0;
  o.resolutions_m = {0.05, 0.1, 0.075};
  const SimulatedCase c = SimulateFleet(Office(), o);
  for (int k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(c.maps[k].geometry().resolution_m(), o.resolutions_m[k]);
    EXPECT_DOUBLE_EQ(c.truth.maps[k].resolution_m, o.resolutions_m[k]);
    // A coarse cell's centre lies within half its diagonal of what it shows.
    const int radius = static_cast<int>(std::ceil(o.resolutions_m[k] / 0.05)) + 1;
    const Landing walls = LandCells(c.maps[k], c.truth.maps[k].T_building_map, Office().grid,
                                    CellState::kOccupied, radius);
    EXPECT_EQ(walls.near, walls.cells) << "robot" << k + 1;
  }
  o.resolutions_m = {0.05, 0.1};
  EXPECT_THROW(SimulateFleet(Office(), o), Error) << "two resolutions for three robots";
}

double MeanShare(const SimulatedCase& c) {
  double sum = 0.0;
  for (const auto& o : c.truth.overlaps) sum += o.share;
  return sum / c.truth.overlaps.size();
}

TEST(SimulateFleet, LittleOverlapModeSharesLess) {
  SimulationOptions o;
  o.path_length_m = 30.0;
  SimulationOptions little = o;
  little.little_overlap = true;
  double normal_sum = 0.0, little_sum = 0.0;
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    o.seed = little.seed = seed;
    const double normal_share = MeanShare(SimulateFleet(Office(), o));
    const SimulatedCase c = SimulateFleet(Office(), little);
    const double little_share = MeanShare(c);
    std::printf("[ overlap ] seed %u: mean share %.2f, little-overlap %.2f\n", seed, normal_share,
                little_share);
    normal_sum += normal_share;
    little_sum += little_share;
    // Each robot explores its own part: the starts are far apart.
    for (std::size_t a = 0; a < c.paths.size(); ++a) {
      for (std::size_t b = a + 1; b < c.paths.size(); ++b) {
        EXPECT_GT((c.paths[a][0].translation_m() - c.paths[b][0].translation_m()).norm(), 4.0);
      }
    }
  }
  EXPECT_LT(little_sum, 0.6 * normal_sum);
}

TEST(SimulateFleet, RejectsBadOptionsNamingThem) {
  auto message = [](SimulationOptions o) {
    try {
      SimulateFleet(Office(), o);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SimulationOptions o;
  o.robots = 0;
  EXPECT_NE(message(o).find("robots"), std::string::npos) << message(o);
  o = {};
  o.lidar.range_noise_m = -1.0;
  EXPECT_NE(message(o).find("--range-noise"), std::string::npos) << message(o);
  o = {};
  o.lidar.range_m = std::nan("");
  EXPECT_NE(message(o).find("range"), std::string::npos) << message(o);
  o = {};
  o.resolutions_m = {0.0};
  EXPECT_NE(message(o).find("resolutions"), std::string::npos) << message(o);
  o = {};
  o.clearance_m = 5.0;
  EXPECT_NE(message(o).find("clearance"), std::string::npos) << message(o);
  EXPECT_THROW(SimulateFleet(Office(), SimulationOptions{}, OfficeBuilding(4, "office")), Error)
      << "the foreign building needs its own name";
}

std::vector<const OccupancyGrid*> Pointers(const std::vector<OccupancyGrid>& maps) {
  std::vector<const OccupancyGrid*> out;
  for (const auto& m : maps) out.push_back(&m);
  return out;
}

// The default case (what `fleetmerge simulate DIR` writes: office seed 1, default options,
// noise on) merges into one component, every pose within 1 degree and 3 cells of the truth.
TEST(SimulateFleet, DefaultCaseMergesWithTheTruePoses) {
  const SimulationOptions defaults;
  const SimulatedCase c = SimulateFleet(OfficeBuilding(defaults.seed), defaults);
  const FleetResult merged = MergeFleet(Pointers(c.maps), 0, FleetOptions{});
  for (std::size_t j = 1; j < c.maps.size(); ++j) {
    ASSERT_EQ(merged.component_of[j], merged.component_of[0]) << c.names[j];
    const Pose2 estimate = merged.T_component_map[0].inverse() * merged.T_component_map[j];
    const Pose2 truth = c.truth.maps[0].T_building_map.inverse() * c.truth.maps[j].T_building_map;
    const PoseError e = ComparePoses(c.maps[j], estimate, truth);
    std::printf("[ merge ] robot1-%s: yaw error %.3f deg, displacement %.2f cells\n",
                c.names[j].c_str(), e.yaw_deg, e.mean_displacement_cells);
    EXPECT_LE(e.yaw_deg, 1.0) << c.names[j];
    EXPECT_LE(e.mean_displacement_cells, 3.0) << c.names[j];
  }
}

TEST(SimulateFleet, RealMapIntelLab) {
  FLEETMERGE_REQUIRE_SHARED_MAPS();
  const auto yaml = *testing::SharedMapsDir() / "intel_lab.yaml";
  const SimulationBuilding intel{LoadMap(yaml).grid, "intel", yaml.string()};
  SimulationOptions o = NoiseFree();
  o.robots = 6;
  const SimulatedCase c = SimulateFleet(intel, o);
  ASSERT_EQ(c.maps.size(), 6u);
  for (std::size_t k = 0; k < c.maps.size(); ++k) {
    const Landing walls =
        LandCells(c.maps[k], c.truth.maps[k].T_building_map, intel.grid, CellState::kOccupied, 1);
    EXPECT_GT(walls.cells, 1000) << c.names[k];
    EXPECT_EQ(walls.near, walls.cells) << c.names[k];
  }
  long long connected = 0;
  for (const auto& ov : c.truth.overlaps) connected += ov.cells >= 2000;
  EXPECT_GE(connected, 5) << "six robots in one lab overlap";
}

}  // namespace
}  // namespace fleetmerge
