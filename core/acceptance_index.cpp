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
  RowSpans spans;
  spans.row_begin.reserve(grid.height() + 1);
  const auto unknown = static_cast<std::uint8_t>(CellState::kUnknown);
  for (int j = 0; j < grid.height(); ++j) {
    spans.row_begin.push_back(static_cast<int>(spans.runs.size()));
    const std::uint8_t* row = grid.cells().ptr<std::uint8_t>(j);
    for (int i = 0; i < grid.width();) {
      if (row[i] == unknown) {
        ++i;
        continue;
      }
      const int first = i;
      while (i < grid.width() && row[i] != unknown) ++i;
      spans.runs.emplace_back(first, i);
    }
  }
  spans.row_begin.push_back(static_cast<int>(spans.runs.size()));
  return spans;
}

Agreement CountAgreement(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb,
                         int stride, const RowSpans* b_spans) {
  stride = std::max(stride, 1);
  // Pose2 * point takes a sine and a cosine each time: once here, with Pose2's arithmetic (the
  // same cells), not once per row.
  const Eigen::Matrix2d R = T_ga_gb.rotation();
  const Eigen::Vector2d& t = T_ga_gb.translation_m();
  const Eigen::Vector2d step = R.col(0) * stride;  // moving one visited cell along b's row
  const std::int64_t step_x = ToFixed(step.x()), step_y = ToFixed(step.y());
  const std::int64_t limit_x = std::int64_t{a.width()} << kFractionBits;
  const std::int64_t limit_y = std::int64_t{a.height()} << kFractionBits;
  const std::uint8_t* a_data = a.cells().ptr<std::uint8_t>(0);
  const std::size_t a_step = a.cells().step[0];
  const auto unknown = static_cast<std::uint8_t>(CellState::kUnknown);
  const std::pair<int, int> whole_row(0, b.width());
  std::int64_t agree = 0, disagree = 0;
  for (int j = 0; j < b.height(); j += stride) {
    const std::uint8_t* b_row = b.cells().ptr<std::uint8_t>(j);
    // The row's runs of known cells, or the whole row.
    const std::pair<int, int>* run_first = &whole_row;
    const std::pair<int, int>* run_last = &whole_row + 1;
    if (b_spans != nullptr) {
      run_first = b_spans->runs.data() + b_spans->row_begin[j];
      run_last = b_spans->runs.data() + b_spans->row_begin[j + 1];
    }
    if (run_first == run_last) continue;
    // Visited cells are begin + k stride, k = 0, 1, ...: from the row's first known cell,
    // rounded up to the stride's lattice so that strided results do not change.
    const int begin = (run_first->first + stride - 1) / stride * stride;
    const int end = (run_last - 1)->second;
    if (begin >= end) continue;
    const Eigen::Vector2d p0 = t + R * Eigen::Vector2d(begin + 0.5, j + 0.5);  // T_ga_gb * cell
    const std::int64_t x0 = ToFixed(p0.x()), y0 = ToFixed(p0.y());
    // Only the visited cells that land inside a: the row is a line segment in a's grid.
    std::int64_t k_begin = 0, k_end = (end - begin + stride - 1) / stride;
    ClipToRange(x0, step_x, limit_x, &k_begin, &k_end);
    ClipToRange(y0, step_y, limit_y, &k_begin, &k_end);
    if (k_begin >= k_end) continue;
    const std::uint8_t* b_cell = b_row + begin;
    for (const std::pair<int, int>* run = run_first; run != run_last; ++run) {
      // The visited k inside this run (positions are the row's, so they do not depend on the
      // runs: the same cells land on the same cells of a).
      const std::int64_t first =
          run->first <= begin ? 0 : (run->first - begin + stride - 1) / stride;
      const std::int64_t last =
          run->second <= begin ? 0 : (run->second - begin + stride - 1) / stride;
      const std::int64_t k_from = std::max(k_begin, first), k_to = std::min(k_end, last);
      for (std::int64_t k = k_from; k < k_to; ++k) {
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
  }
  Agreement result;
  result.agree = agree;
  result.disagree = disagree;
  return result;
}

std::optional<Eigen::Vector2d> OverlapCentre(const OccupancyGrid& a, const OccupancyGrid& b,
                                             const Pose2& T_ga_gb, int stride) {
  stride = std::max(stride, 1);
  const auto unknown = static_cast<std::uint8_t>(CellState::kUnknown);
  // Once, not per cell (Pose2 * point takes a sine and a cosine: a fleet's anchors spent ~40 ms
  // of CPU on them at 33 robots); Pose2's arithmetic, so the same cells.
  const Eigen::Matrix2d R = T_ga_gb.rotation();
  const Eigen::Vector2d& t = T_ga_gb.translation_m();
  const CellOfPoint cell_in_a(a);
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  std::int64_t count = 0;
  for (int j = 0; j < b.height(); j += stride) {
    const std::uint8_t* b_row = b.cells().ptr<std::uint8_t>(j);
    for (int i = 0; i < b.width(); i += stride) {
      if (b_row[i] == unknown) continue;
      const Eigen::Vector2d centre(i + 0.5, j + 0.5);
      int ia = 0, ja = 0;
      if (!cell_in_a(t + R * centre, &ia, &ja)) continue;
      if (a.cells().ptr<std::uint8_t>(ja)[ia] == unknown) continue;
      sum += centre;
      ++count;
    }
  }
  if (count == 0) return std::nullopt;
  return sum / static_cast<double>(count);
}

}  // namespace fleetmerge
