#include "core/acceptance_index.hpp"

#include <algorithm>
#include <cmath>

namespace fleetmerge {
namespace {

// Positions in a's grid in 32.32 fixed point: along a row of b they advance by a constant step,
// and integer steps are exact (a double accumulated over 1000 cells drifts by ~1e-13 cells, the
// fixed-point step's rounding by ~1e-7: neither moves a cell centre across a cell border in
// practice). floor() is a shift, and the cells of a row that land inside a are found once per
// row (ClipToRange) instead of tested one by one.
constexpr int kFractionBits = 32;
constexpr double kFixedOne = 4294967296.0;  // 2^kFractionBits
// Positions beyond this many cells are clamped (no map is that large); keeps the products below
// 2^63 whatever the pose.
constexpr double kMaxCells = 1 << 26;

std::int64_t ToFixed(double cells) {
  return std::llround(std::clamp(cells, -kMaxCells, kMaxCells) * kFixedOne);
}

// Visited cells k = 0, 1, ... of a row have fixed-point coordinate v0 + k * dv; the k with
// 0 <= v < limit form one interval [*k_begin, *k_end) (intersected with the caller's).
void ClipToRange(std::int64_t v0, std::int64_t dv, std::int64_t limit, std::int64_t* k_begin,
                 std::int64_t* k_end) {
  if (dv == 0) {
    if (v0 < 0 || v0 >= limit) *k_end = *k_begin;
    return;
  }
  // Smallest k with v0 + k dv >= lo, largest with <= hi, for dv > 0 (mirrored for dv < 0).
  const auto floor_div = [](std::int64_t n, std::int64_t d) {
    const std::int64_t q = n / d;
    return q - ((n % d != 0) && ((n < 0) != (d < 0)));
  };
  const auto ceil_div = [&](std::int64_t n, std::int64_t d) { return -floor_div(-n, d); };
  std::int64_t first = 0, last = 0;  // inclusive k range
  if (dv > 0) {
    first = ceil_div(-v0, dv);
    last = floor_div(limit - 1 - v0, dv);
  } else {
    first = ceil_div(limit - 1 - v0, dv);
    last = floor_div(-v0, dv);
  }
  *k_begin = std::max(*k_begin, first);
  *k_end = std::min(*k_end, last + 1);
  if (*k_end < *k_begin) *k_end = *k_begin;
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
  const Eigen::Matrix2d R = T_ga_gb.rotation();
  const Eigen::Vector2d step = R.col(0) * stride;  // moving one visited cell along b's row
  const std::int64_t step_x = ToFixed(step.x()), step_y = ToFixed(step.y());
  const std::int64_t limit_x = std::int64_t{a.width()} << kFractionBits;
  const std::int64_t limit_y = std::int64_t{a.height()} << kFractionBits;
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
    if (begin >= end) continue;
    const Eigen::Vector2d p0 = T_ga_gb * Eigen::Vector2d(begin + 0.5, j + 0.5);
    const std::int64_t x0 = ToFixed(p0.x()), y0 = ToFixed(p0.y());
    // Only the visited cells that land inside a: the row is a line segment in a's grid.
    std::int64_t k_begin = 0, k_end = (end - begin + stride - 1) / stride;
    ClipToRange(x0, step_x, limit_x, &k_begin, &k_end);
    ClipToRange(y0, step_y, limit_y, &k_begin, &k_end);
    const std::uint8_t* b_cell = b_row + begin;
    for (std::int64_t k = k_begin; k < k_end; ++k) {
      const std::uint8_t state_b = b_cell[k * stride];
      // Non-negative after clipping, so the shift is floor().
      const std::int64_t ia = (x0 + k * step_x) >> kFractionBits;
      const std::int64_t ja = (y0 + k * step_y) >> kFractionBits;
      const std::uint8_t state_a = a_data[ja * a_step + ia];
      // Without branches: whether a cell agrees is as unpredictable as the maps (perf showed
      // CountAgreement 17 % of a fleet merge).
      const int known = (state_a != unknown) & (state_b != unknown);
      agree += known & (state_a == state_b);
      disagree += known & (state_a != state_b);
    }
  }
  Agreement result;
  result.agree = agree;
  result.disagree = disagree;
  return result;
}

}  // namespace fleetmerge
