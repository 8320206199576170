#include "core/acceptance_index.hpp"

#include <cmath>

namespace fleetmerge {
namespace {

// static_cast<int>(std::floor(x)) in fewer instructions (omega's inner loop): truncation rounds
// toward zero, so a negative non-integer x truncates one above its floor.
inline int FloorToInt(double x) {
  const int t = static_cast<int>(x);
  return t - (x < t);
}

}  // namespace

RowSpans KnownRowSpans(const OccupancyGrid& grid) {
  RowSpans spans(grid.height(), {0, 0});
  const auto unknown = static_cast<std::uint8_t>(CellState::kUnknown);
  for (int j = 0; j < grid.height(); ++j) {
    const std::uint8_t* row = grid.cells().ptr<std::uint8_t>(j);
    int first = 0, last = grid.width() - 1;
    while (first <= last && row[first] == unknown) ++first;
    while (last >= first && row[last] == unknown) --last;
    spans[j] = {first, last + 1};
  }
  return spans;
}

Agreement CountAgreement(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb,
                         int stride, const RowSpans* b_spans) {
  stride = std::max(stride, 1);
  Agreement result;
  const Eigen::Matrix2d R = T_ga_gb.rotation();
  const Eigen::Vector2d step = R.col(0) * stride;  // moving one visited cell along b's row
  const auto a_width = static_cast<unsigned>(a.width());
  const auto a_height = static_cast<unsigned>(a.height());
  const std::uint8_t* a_data = a.cells().ptr<std::uint8_t>(0);
  const std::size_t a_step = a.cells().step[0];
  const auto unknown = static_cast<std::uint8_t>(CellState::kUnknown);
  std::int64_t agree = 0, disagree = 0;
  for (int j = 0; j < b.height(); j += stride) {
    const std::uint8_t* b_row = b.cells().ptr<std::uint8_t>(j);
    int begin = 0, end = b.width();
    if (b_spans != nullptr) {
      // Round the span start up to the stride's lattice so strided results do not change.
      begin = ((*b_spans)[j].first + stride - 1) / stride * stride;
      end = (*b_spans)[j].second;
    }
    Eigen::Vector2d p_a = T_ga_gb * Eigen::Vector2d(begin + 0.5, j + 0.5);
    for (int i = begin; i < end; i += stride, p_a += step) {
      const std::uint8_t state_b = b_row[i];
      if (state_b == unknown) continue;
      const int ia = FloorToInt(p_a.x());
      const int ja = FloorToInt(p_a.y());
      // One unsigned comparison per axis also rejects negative indices.
      if (static_cast<unsigned>(ia) >= a_width || static_cast<unsigned>(ja) >= a_height) continue;
      const std::uint8_t state_a = a_data[ja * a_step + ia];
      // Without branches: whether a cell agrees is as unpredictable as the maps (perf showed
      // CountAgreement 17 % of a fleet merge).
      const int known = state_a != unknown;
      agree += known & (state_a == state_b);
      disagree += known & (state_a != state_b);
    }
  }
  result.agree = agree;
  result.disagree = disagree;
  return result;
}

}  // namespace fleetmerge
