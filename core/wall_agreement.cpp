#include "core/wall_agreement.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace fleetmerge {

cv::Mat1b NearWallMask(const OccupancyGrid& grid) {
  cv::Mat1b near_wall = grid.cells() == static_cast<std::uint8_t>(CellState::kOccupied);
  cv::dilate(near_wall, near_wall, cv::Mat());
  return near_wall;
}

double WallAgreement(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb) {
  return WallAgreement(a, NearWallMask(a), b, T_ga_gb);
}

double WallAgreement(const OccupancyGrid& a, const cv::Mat1b& near_wall, const OccupancyGrid& b,
                     const Pose2& T_ga_gb) {
  const auto occupied = static_cast<std::uint8_t>(CellState::kOccupied);
  const auto unknown = static_cast<std::uint8_t>(CellState::kUnknown);
  long on_known = 0, on_wall = 0;
  for (int j = 0; j < b.height(); ++j) {
    const std::uint8_t* row = b.cells().ptr<std::uint8_t>(j);
    for (int i = 0; i < b.width(); ++i) {
      if (row[i] != occupied) continue;
      const Eigen::Vector2d p = T_ga_gb * Eigen::Vector2d(i + 0.5, j + 0.5);
      const int ia = static_cast<int>(std::floor(p.x()));
      const int ja = static_cast<int>(std::floor(p.y()));
      if (ia < 0 || ja < 0 || ia >= a.width() || ja >= a.height()) continue;
      if (a.cells()(ja, ia) == unknown) continue;
      ++on_known;
      on_wall += near_wall(ja, ia) != 0;
    }
  }
  return on_known < kMinWallsJudged ? 0.0 : double(on_wall) / double(on_known);
}

double SymmetricWallAgreement(const OccupancyGrid& a, const OccupancyGrid& b,
                              const Pose2& T_ga_gb) {
  return std::min(WallAgreement(a, b, T_ga_gb), WallAgreement(b, a, T_ga_gb.inverse()));
}

}  // namespace fleetmerge
