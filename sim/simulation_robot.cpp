#include "sim/simulation_robot.hpp"

#include <algorithm>
#include <cmath>

#include "sim/portable_rng.hpp"
#include "sim/simulation_explore.hpp"
#include "sim/simulation_lidar.hpp"
#include "sim/simulation_mapping.hpp"

namespace fleetmerge {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// The SLAM estimate of the robot's pose in its map frame: odometry increments with random-walk
// drift (standard deviation growing as the square root of the path), plus per-scan jitter.
class PoseEstimate {
 public:
  PoseEstimate(const Pose2& T_map_start, const PoseNoiseOptions& noise, PortableRng& rng)
      : T_map_robot_(T_map_start), noise_(noise), rng_(rng) {}

  // The robot moved from T_building_from to T_building_to over path_m metres.
  void Move(const Pose2& T_building_from, const Pose2& T_building_to, double path_m) {
    const double s = std::sqrt(path_m);
    const Pose2 drift(rng_.Normal(noise_.drift_xy_m * s), rng_.Normal(noise_.drift_xy_m * s),
                      rng_.Normal(noise_.drift_yaw_deg * kDegToRad * s));
    T_map_robot_ = T_map_robot_ * (T_building_from.inverse() * T_building_to) * drift;
  }
  // The pose a scan is drawn at: the estimate with this scan's jitter.
  Pose2 ScanPose() {
    const Pose2 jitter(rng_.Normal(noise_.xy_m), rng_.Normal(noise_.xy_m),
                       rng_.Normal(noise_.yaw_deg * kDegToRad));
    return T_map_robot_ * jitter;
  }

 private:
  Pose2 T_map_robot_;
  PoseNoiseOptions noise_;
  PortableRng& rng_;
};

// Room for where a drifting estimate may draw the building: the drift's 3-sigma reach.
double MapperMarginM(const SimulationOptions& o) {
  const double s = std::sqrt(o.path_length_m);
  const double yaw_rad = std::min(1.0, 3.0 * o.pose_noise.drift_yaw_deg * kDegToRad * s);
  return 1.0 + 3.0 * o.pose_noise.drift_xy_m * s + (o.path_length_m + o.lidar.range_m) * yaw_rad;
}

}  // namespace

RobotRun RunRobot(const OccupancyGrid& building, const cv::Mat1b& walkable,
                  const Eigen::Array2i& start, const Pose2& T_building_map, double resolution_m,
                  const SimulationOptions& options, std::uint32_t seed) {
  PortableRng rng(seed);
  const GridGeometry& g = building.geometry();
  RobotMapper mapper(MapperGeometry(g, T_building_map, resolution_m, MapperMarginM(options)),
                     options.occupied_ratio);
  cv::Mat1b seen = cv::Mat1b::zeros(building.height(), building.width());
  RobotRun run;
  auto scan_at = [&](const Pose2& T_building_robot, PoseEstimate& estimate) {
    const LidarScan scan = CastScan(building, T_building_robot, options.lidar, rng, &seen);
    mapper.Integrate(scan, estimate.ScanPose());
    run.T_building_scanner.push_back(T_building_robot);
  };

  const double start_yaw_rad = rng.Uniform(-M_PI, M_PI);
  Pose2 T_building_last(g.CellCenter(start), start_yaw_rad);  // at the last scan
  PoseEstimate estimate(T_building_map.inverse() * T_building_last, options.pose_noise, rng);
  scan_at(T_building_last, estimate);

  const int spread_cells = static_cast<int>(std::lround(options.goal_spread_m / g.resolution_m()));
  Eigen::Array2i cell = start;
  double travelled_m = 0.0, since_scan_m = 0.0;
  while (travelled_m < options.path_length_m) {
    const std::vector<Eigen::Array2i> path =
        PathToNextGoal(walkable, seen, cell, spread_cells, rng);
    if (path.empty()) break;  // everything reachable has been seen
    for (const Eigen::Array2i& next : path) {
      const double step_m = (next - cell).cast<double>().matrix().norm() * g.resolution_m();
      cell = next;
      travelled_m += step_m;
      since_scan_m += step_m;
      if (since_scan_m < options.scan_spacing_m) continue;
      // The robot faces the way it came since the last scan.
      const Eigen::Vector2d position = g.CellCenter(cell);
      const Eigen::Vector2d motion = position - T_building_last.translation_m();
      const Pose2 T_building_robot(position, std::atan2(motion.y(), motion.x()));
      estimate.Move(T_building_last, T_building_robot, since_scan_m);
      scan_at(T_building_robot, estimate);
      T_building_last = T_building_robot;
      since_scan_m = 0.0;
      if (travelled_m >= options.path_length_m) break;
    }
  }
  run.map = mapper.ToGrid();
  return run;
}

}  // namespace fleetmerge
