#include "core/acceptance_index.hpp"

#include <cmath>

namespace fleetmerge {

Agreement CountAgreement(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb,
                         int stride) {
  stride = std::max(stride, 1);
  Agreement result;
  const Eigen::Matrix2d R = T_ga_gb.rotation();
  const Eigen::Vector2d step = R.col(0) * stride;  // moving one visited cell along b's row
  const int a_width = a.width();
  const int a_height = a.height();
  for (int j = 0; j < b.height(); j += stride) {
    const std::uint8_t* b_row = b.cells().ptr<std::uint8_t>(j);
    Eigen::Vector2d p_a = T_ga_gb * Eigen::Vector2d(0.5, j + 0.5);
    for (int i = 0; i < b.width(); i += stride, p_a += step) {
      const std::uint8_t state_b = b_row[i];
      if (state_b == static_cast<std::uint8_t>(CellState::kUnknown)) continue;
      const int ia = static_cast<int>(std::floor(p_a.x()));
      const int ja = static_cast<int>(std::floor(p_a.y()));
      if (ia < 0 || ja < 0 || ia >= a_width || ja >= a_height) continue;
      const std::uint8_t state_a = a.cells()(ja, ia);
      if (state_a == static_cast<std::uint8_t>(CellState::kUnknown)) continue;
      if (state_a == state_b) {
        ++result.agree;
      } else {
        ++result.disagree;
      }
    }
  }
  return result;
}

}  // namespace fleetmerge
