#include "sim/simulation_mapping.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace fleetmerge {

RobotMapper::RobotMapper(const GridGeometry& geometry, double occupied_ratio)
    : geometry_(geometry),
      occupied_ratio_(occupied_ratio),
      hits_(geometry.height(), geometry.width(), 0),
      visits_(geometry.height(), geometry.width(), 0) {}

void RobotMapper::Integrate(const LidarScan& scan, const Pose2& T_map_sensor) {
  const double r = geometry_.resolution_m();
  const Pose2 T_grid_sensor = geometry_.T_map_grid().inverse() * T_map_sensor;
  const Eigen::Vector2d origin_cells = T_grid_sensor.translation_m() / r;
  // A return is pushed a quarter cell past the surface so that it lands in the wall rather than
  // in the free cell in front of it when the surface lies on a cell boundary of this grid.
  const double push_cells = 0.25;
  const int width = geometry_.width(), height = geometry_.height();
  int* hits = hits_.ptr<int>(0);
  int* visits = visits_.ptr<int>(0);
  const std::size_t step = hits_.step1();
  for (std::size_t k = 0; k < scan.ranges_m.size(); ++k) {
    const double angle = T_grid_sensor.yaw_rad() + scan.first_angle_rad +
                         static_cast<double>(k) * scan.angle_step_rad;
    const bool hit = scan.hit[k] != 0;
    const double length_cells = scan.ranges_m[k] / r + (hit ? push_cells : 0.0);
    const Eigen::Vector2d end =
        origin_cells + length_cells * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    const int end_i = static_cast<int>(std::floor(end.x()));
    const int end_j = static_cast<int>(std::floor(end.y()));
    TraverseSegment(origin_cells, end, [&](int i, int j, double) {
      if (static_cast<unsigned>(i) >= static_cast<unsigned>(width) ||
          static_cast<unsigned>(j) >= static_cast<unsigned>(height)) {
        return false;
      }
      ++visits[j * step + i];
      if (hit && i == end_i && j == end_j) ++hits[j * step + i];
      return true;
    });
  }
}

OccupancyGrid RobotMapper::ToGrid() const {
  const cv::Mat1b known = visits_ > 0;
  const cv::Rect box = cv::boundingRect(known);
  const double r = geometry_.resolution_m();
  const Pose2 T_map_crop = geometry_.T_map_grid() * Pose2(box.x * r, box.y * r, 0.0);
  cv::Mat1b cells(box.height, box.width, static_cast<std::uint8_t>(CellState::kUnknown));
  for (int y = 0; y < box.height; ++y) {
    const int* hits = hits_.ptr<int>(box.y + y) + box.x;
    const int* visits = visits_.ptr<int>(box.y + y) + box.x;
    std::uint8_t* out = cells.ptr<std::uint8_t>(y);
    for (int x = 0; x < box.width; ++x) {
      if (visits[x] == 0) continue;
      out[x] = static_cast<std::uint8_t>(
          hits[x] >= occupied_ratio_ * visits[x] ? CellState::kOccupied : CellState::kFree);
    }
  }
  return OccupancyGrid(GridGeometry(r, {box.width, box.height}, T_map_crop), cells);
}

GridGeometry MapperGeometry(const GridGeometry& building, const Pose2& T_building_map,
                            double resolution_m, double margin_m) {
  const Pose2 T_map_bgrid = T_building_map.inverse() * building.T_map_grid();
  const double w = building.width() * building.resolution_m();
  const double h = building.height() * building.resolution_m();
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e300), hi = -lo;
  for (const Eigen::Vector2d& corner : {Eigen::Vector2d(0, 0), Eigen::Vector2d(w, 0),
                                        Eigen::Vector2d(0, h), Eigen::Vector2d(w, h)}) {
    const Eigen::Vector2d p_map = T_map_bgrid * corner;
    lo = lo.cwiseMin(p_map);
    hi = hi.cwiseMax(p_map);
  }
  lo -= Eigen::Vector2d::Constant(margin_m);
  hi += Eigen::Vector2d::Constant(margin_m);
  const Eigen::Array2i size = ((hi - lo) / resolution_m).array().ceil().cast<int>();
  return GridGeometry(resolution_m, size, Pose2(lo, 0.0));
}

}  // namespace fleetmerge
