#include "sim/simulation_lidar.hpp"

#include <algorithm>

namespace fleetmerge {

LidarScan CastScan(const OccupancyGrid& building, const Pose2& T_building_sensor,
                   const LidarOptions& options, PortableRng& rng, cv::Mat1b* seen) {
  const GridGeometry& g = building.geometry();
  const double r = g.resolution_m();
  const Pose2 T_grid_sensor = g.T_map_grid().inverse() * T_building_sensor;
  const Eigen::Vector2d origin_cells = T_grid_sensor.translation_m() / r;
  const double range_cells = options.range_m / r;

  const int width = building.width(), height = building.height();
  const std::uint8_t* cells = building.cells().ptr<std::uint8_t>(0);
  const std::size_t step = building.cells().step1();
  std::uint8_t* seen_cells = seen != nullptr ? seen->ptr<std::uint8_t>(0) : nullptr;
  const std::size_t seen_step = seen != nullptr ? seen->step1() : 0;
  LidarScan scan;
  scan.first_angle_rad = 0.0;
  scan.angle_step_rad = 2.0 * M_PI / options.beams;
  scan.ranges_m.resize(options.beams);
  scan.hit.resize(options.beams);
  for (int k = 0; k < options.beams; ++k) {
    const double angle = T_grid_sensor.yaw_rad() + k * scan.angle_step_rad;
    const Eigen::Vector2d end =
        origin_cells + range_cells * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    double stop_cells = range_cells;
    bool hit = false;
    TraverseSegment(origin_cells, end, [&](int i, int j, double t_enter) {
      const CellState state = static_cast<unsigned>(i) < static_cast<unsigned>(width) &&
                                      static_cast<unsigned>(j) < static_cast<unsigned>(height)
                                  ? static_cast<CellState>(cells[j * step + i])
                                  : CellState::kUnknown;
      if (state == CellState::kFree) {
        if (seen_cells != nullptr) seen_cells[j * seen_step + i] = 255;
        return true;
      }
      stop_cells = t_enter;
      hit = state == CellState::kOccupied;
      if (hit && seen_cells != nullptr) seen_cells[j * seen_step + i] = 255;
      return false;
    });
    double range_m = stop_cells * r;
    if (hit) range_m = std::max(0.0, range_m + rng.Normal(options.range_noise_m));
    scan.ranges_m[k] = range_m;
    scan.hit[k] = hit ? 1 : 0;
  }
  return scan;
}

}  // namespace fleetmerge
