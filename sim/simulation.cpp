#include "sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "core/parallel.hpp"
#include "sim/portable_rng.hpp"
#include "sim/simulation_explore.hpp"
#include "sim/simulation_robot.hpp"

namespace fleetmerge {
namespace {

void Require(bool condition, const std::string& option, const std::string& expected, double value) {
  if (condition) return;
  std::ostringstream msg;
  msg << "simulation option " << option << ": expected " << expected << ", got " << value;
  throw Error(msg.str());
}

bool Finite(double v) { return std::isfinite(v); }

// One robot to simulate: where it starts, which cells it may cross, its map frame and seed.
struct RobotPlan {
  const SimulationBuilding* building = nullptr;
  cv::Mat1b walkable;
  Eigen::Array2i start;
  Pose2 T_building_map;
  double resolution_m = 0.0;
  std::uint32_t seed = 0;
};

Pose2 RandomFrame(double max_offset_m, PortableRng& rng) {
  const double x = rng.Uniform(-max_offset_m, max_offset_m);
  const double y = rng.Uniform(-max_offset_m, max_offset_m);
  return Pose2(x, y, rng.Uniform(-M_PI, M_PI));
}

std::vector<RobotPlan> PlanRobots(const SimulationBuilding& building,
                                  const std::optional<SimulationBuilding>& foreign,
                                  const SimulationOptions& options) {
  PortableRng rng(options.seed);
  const int total = options.robots + (foreign ? 1 : 0);
  const auto& res = options.resolutions_m;
  if (res.size() != 1 && static_cast<int>(res.size()) != total) {
    throw Error(
        "simulation option resolutions_m (--resolutions): expected one value or one per robot (" +
        std::to_string(total) + (foreign ? ", the foreign robot last" : "") + "), got " +
        std::to_string(res.size()));
  }
  std::vector<RobotPlan> plans(total);
  const cv::Mat1b traversable = TraversableCells(building.grid, options.clearance_m);
  const std::vector<Eigen::Array2i> starts =
      ChooseStarts(traversable, options.robots, options.little_overlap, rng);
  cv::Mat1i territory;
  if (options.little_overlap) territory = Territories(traversable, starts);
  // The building's robots draw everything before the foreign one, so adding a foreign robot
  // leaves their maps unchanged.
  auto draw_frame_and_seed = [&](RobotPlan& plan, int k) {
    plan.T_building_map = RandomFrame(options.max_frame_offset_m, rng);
    plan.resolution_m = res.size() == 1 ? res.front() : res[k];
    plan.seed = rng.NextSeed();
  };
  for (int k = 0; k < options.robots; ++k) {
    RobotPlan& plan = plans[k];
    plan.building = &building;
    plan.walkable = options.little_overlap ? cv::Mat1b(territory == k) : traversable;
    plan.start = starts[k];
    draw_frame_and_seed(plan, k);
  }
  if (foreign) {
    RobotPlan& plan = plans.back();
    plan.building = &*foreign;
    plan.walkable = TraversableCells(foreign->grid, options.clearance_m);
    plan.start = ChooseStarts(plan.walkable, 1, false, rng).front();
    draw_frame_and_seed(plan, total - 1);
  }
  return plans;
}

}  // namespace

void ValidateSimulationOptions(const SimulationOptions& o) {
  // Each option is named as in the struct and, where it has one, as on the command line.
  Require(o.robots >= 1 && o.robots <= 100, "robots (--robots)", "an integer in [1, 100]",
          o.robots);
  Require(o.lidar.beams >= 3 && o.lidar.beams <= 100000, "lidar.beams (--beams)",
          "an integer in [3, 100000]", o.lidar.beams);
  const std::pair<const char*, double> positive[] = {
      {"lidar.range_m (--range)", o.lidar.range_m},
      {"path_length_m (--path-length)", o.path_length_m},
      {"scan_spacing_m", o.scan_spacing_m}};
  for (const auto& [name, value] : positive) {
    Require(Finite(value) && value > 0.0, name, "a finite number > 0", value);
  }
  const std::pair<const char*, double> non_negative[] = {
      {"lidar.range_noise_m (--range-noise)", o.lidar.range_noise_m},
      {"pose_noise.xy_m (--pose-noise)", o.pose_noise.xy_m},
      {"pose_noise.yaw_deg (--pose-noise-yaw)", o.pose_noise.yaw_deg},
      {"pose_noise.drift_xy_m (--drift)", o.pose_noise.drift_xy_m},
      {"pose_noise.drift_yaw_deg (--drift-yaw)", o.pose_noise.drift_yaw_deg},
      {"clearance_m (--clearance)", o.clearance_m},
      {"goal_spread_m", o.goal_spread_m},
      {"max_frame_offset_m", o.max_frame_offset_m}};
  for (const auto& [name, value] : non_negative) {
    Require(Finite(value) && value >= 0.0, name, "a finite number >= 0", value);
  }
  Require(o.occupied_ratio > 0.0 && o.occupied_ratio <= 1.0, "occupied_ratio", "a number in (0, 1]",
          o.occupied_ratio);
  Require(o.threads >= 0, "threads (--threads)", "an integer >= 0", o.threads);
  if (o.priors) {
    Require(Finite(o.priors->error_m) && o.priors->error_m >= 0.0, "priors.error_m (--priors)",
            "a finite number >= 0", o.priors->error_m);
    Require(Finite(o.priors->error_deg) && std::abs(o.priors->error_deg) <= 180.0,
            "priors.error_deg (--priors)", "a number in [-180, 180]", o.priors->error_deg);
    Require(Finite(o.priors->sigma_m) && o.priors->sigma_m > 0.0, "priors.sigma_m (--priors)",
            "a finite number > 0", o.priors->sigma_m);
    Require(
        Finite(o.priors->sigma_deg) && o.priors->sigma_deg > 0.0 && o.priors->sigma_deg <= 180.0,
        "priors.sigma_deg (--priors)", "a number in (0, 180]", o.priors->sigma_deg);
  }
  Require(!o.resolutions_m.empty(), "resolutions_m (--resolutions)", "at least one value", 0.0);
  for (const double r : o.resolutions_m) {
    Require(Finite(r) && r >= 0.005 && r <= 1.0, "resolutions_m (--resolutions)",
            "cell sizes in [0.005, 1] m", r);
  }
}

SimulationBuilding OfficeBuilding(std::uint32_t seed, const std::string& name,
                                  const OfficeOptions& office) {
  return {GenerateOfficeFloor(office, seed), name, "synthetic office seed " + std::to_string(seed)};
}

cv::Mat1b KnownMaskInBuilding(const GridGeometry& building_geometry, const OccupancyGrid& map,
                              const Pose2& T_building_map) {
  const GridGeometry& gm = map.geometry();
  // Building grid frame -> map grid frame, composed once.
  const Pose2 T_mgrid_bgrid =
      gm.T_map_grid().inverse() * T_building_map.inverse() * building_geometry.T_map_grid();
  cv::Mat1b mask = cv::Mat1b::zeros(building_geometry.height(), building_geometry.width());
  for (int j = 0; j < building_geometry.height(); ++j) {
    for (int i = 0; i < building_geometry.width(); ++i) {
      const Eigen::Vector2d p_bgrid = building_geometry.CellCenterInGrid({i, j});
      const Eigen::Array2i cell = gm.CellOfGridPoint(T_mgrid_bgrid * p_bgrid);
      if (map.StateOrUnknown(cell) != CellState::kUnknown) mask(j, i) = 255;
    }
  }
  return mask;
}

SimulatedCase SimulateFleet(const SimulationBuilding& building, const SimulationOptions& options,
                            const std::optional<SimulationBuilding>& foreign) {
  ValidateSimulationOptions(options);
  if (foreign && foreign->name == building.name) {
    throw Error("simulation: the foreign building needs a name other than '" + building.name + "'");
  }
  const std::vector<RobotPlan> plans = PlanRobots(building, foreign, options);
  std::vector<RobotRun> runs(plans.size());
  ParallelFor(plans.size(), options.threads, [&](std::size_t k) {
    const RobotPlan& p = plans[k];
    runs[k] = RunRobot(p.building->grid, p.walkable, p.start, p.T_building_map, p.resolution_m,
                       options, p.seed);
  });

  SimulatedCase result;
  result.truth.seed = options.seed;
  result.truth.buildings.push_back({building.name, building.source});
  if (foreign) result.truth.buildings.push_back({foreign->name, foreign->source});
  std::vector<cv::Mat1b> known(plans.size());
  for (std::size_t k = 0; k < plans.size(); ++k) {
    const std::string name = "robot" + std::to_string(k + 1);
    result.names.push_back(name);
    result.maps.push_back(std::move(runs[k].map));
    result.paths.push_back(std::move(runs[k].T_building_scanner));
    result.truth.maps.push_back({name, name + ".yaml", plans[k].building->name,
                                 plans[k].resolution_m, plans[k].T_building_map});
    known[k] = KnownMaskInBuilding(plans[k].building->grid.geometry(), result.maps[k],
                                   plans[k].T_building_map);
  }
  for (std::size_t a = 0; a < plans.size(); ++a) {
    for (std::size_t b = a + 1; b < plans.size(); ++b) {
      if (plans[a].building != plans[b].building) continue;
      const long long cells = cv::countNonZero(known[a] & known[b]);
      const long long smaller = std::min(cv::countNonZero(known[a]), cv::countNonZero(known[b]));
      result.truth.overlaps.push_back({result.names[a], result.names[b], cells,
                                       smaller > 0 ? double(cells) / double(smaller) : 0.0});
    }
  }
  if (options.fixed_base) {
    // The base's frame is the building's: its known cells are the building's, cell for cell.
    SimulatedBase base;
    base.map = building.grid;
    base.truth = {"base", "base.yaml", building.name, building.grid.geometry().resolution_m(),
                  Pose2()};
    const cv::Mat1b base_known = building.grid.cells() != 0;  // CellState::kUnknown is 0
    const long long base_cells = cv::countNonZero(base_known);
    for (std::size_t k = 0; k < plans.size(); ++k) {
      if (plans[k].building != &building) continue;
      const long long cells = cv::countNonZero(known[k] & base_known);
      const long long smaller = std::min<long long>(cv::countNonZero(known[k]), base_cells);
      base.overlaps.push_back({base.truth.name, result.names[k], cells,
                               smaller > 0 ? double(cells) / double(smaller) : 0.0});
    }
    result.base = std::move(base);
  }
  if (options.priors) {
    // A generator of its own: the robots, their maps and frames are the case without priors.
    PortableRng rng(options.seed ^ 0x9e3779b9u);
    const SimulationOptions::Priors& p = *options.priors;
    result.priors.resize(plans.size());
    for (std::size_t k = 0; k < plans.size(); ++k) {
      const double direction_rad = rng.Uniform(-M_PI, M_PI);
      const double yaw_sign = rng.Uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0;
      if (plans[k].building != &building) continue;
      const Pose2& T = plans[k].T_building_map;
      PosePrior prior;
      prior.T_site_map =
          Pose2(T.translation_m() +
                    p.error_m * Eigen::Vector2d(std::cos(direction_rad), std::sin(direction_rad)),
                T.yaw_rad() + yaw_sign * p.error_deg * M_PI / 180.0);
      prior.translation_sigma_m = p.sigma_m;
      prior.yaw_sigma_rad = p.sigma_deg * M_PI / 180.0;
      result.priors[k] = prior;
    }
  }
  return result;
}

}  // namespace fleetmerge
