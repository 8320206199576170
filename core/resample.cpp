#include "core/resample.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

// Cell counts are computed from metric ratios such as 0.5 / 0.1 = 5.000000000000001; this slack
// stops such a ratio from rounding up to an extra, empty cell (or a spurious extra source cell).
constexpr double kIndexSlack = 1e-9;

int CeilCount(double cells) { return static_cast<int>(std::ceil(cells - kIndexSlack)); }

// Half-open source index range [begin, end) overlapped by each of `new_count` new cells of size
// `ratio` source cells, clipped to the `old_count` source cells.
std::vector<std::pair<int, int>> OverlappedRanges(int new_count, double ratio, int old_count) {
  std::vector<std::pair<int, int>> ranges(new_count);
  for (int n = 0; n < new_count; ++n) {
    const int begin = static_cast<int>(std::floor(n * ratio + kIndexSlack));
    const int end = CeilCount((n + 1) * ratio);
    ranges[n] = {std::clamp(begin, 0, old_count), std::clamp(end, 0, old_count)};
  }
  return ranges;
}

// Source index containing the centre of each new cell, or -1 outside the source grid.
std::vector<int> CentreIndices(int new_count, double ratio, int old_count) {
  std::vector<int> indices(new_count);
  for (int n = 0; n < new_count; ++n) {
    const int index = static_cast<int>(std::floor((n + 0.5) * ratio));
    indices[n] = index < old_count ? index : -1;
  }
  return indices;
}

void Coarsen(const cv::Mat1b& source, double ratio, cv::Mat1b& target) {
  const auto cols = OverlappedRanges(target.cols, ratio, source.cols);
  const auto rows = OverlappedRanges(target.rows, ratio, source.rows);
  for (int tj = 0; tj < target.rows; ++tj) {
    for (int ti = 0; ti < target.cols; ++ti) {
      std::uint8_t strongest = static_cast<std::uint8_t>(CellState::kUnknown);
      for (int j = rows[tj].first; j < rows[tj].second; ++j) {
        const std::uint8_t* row = source.ptr<std::uint8_t>(j);
        for (int i = cols[ti].first; i < cols[ti].second; ++i)
          strongest = std::max(strongest, row[i]);
      }
      target(tj, ti) = strongest;  // max == occupied > free > unknown (see the header)
    }
  }
}

void Refine(const cv::Mat1b& source, double ratio, cv::Mat1b& target) {
  const std::vector<int> cols = CentreIndices(target.cols, ratio, source.cols);
  const std::vector<int> rows = CentreIndices(target.rows, ratio, source.rows);
  for (int tj = 0; tj < target.rows; ++tj) {
    if (rows[tj] < 0) continue;  // target starts all kUnknown
    const std::uint8_t* row = source.ptr<std::uint8_t>(rows[tj]);
    for (int ti = 0; ti < target.cols; ++ti) {
      if (cols[ti] >= 0) target(tj, ti) = row[cols[ti]];
    }
  }
}

}  // namespace

OccupancyGrid ResampleToResolution(const OccupancyGrid& grid, double resolution_m) {
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m)) {
    std::ostringstream msg;
    msg << "resample: target resolution must be a finite number > 0 m, got " << resolution_m;
    throw Error(msg.str());
  }
  const GridGeometry& old_geometry = grid.geometry();
  // Target cell size in source cells: > 1 coarsens, < 1 refines.
  const double ratio = resolution_m / old_geometry.resolution_m();
  if (HasResolution(old_geometry, resolution_m)) {
    return OccupancyGrid(old_geometry, grid.cells().clone());
  }

  const Eigen::Array2i new_size(CeilCount(old_geometry.width() / ratio),
                                CeilCount(old_geometry.height() / ratio));
  OccupancyGrid out(GridGeometry(resolution_m, new_size, old_geometry.T_map_grid()));
  if (ratio > 1.0) {
    Coarsen(grid.cells(), ratio, out.mutable_cells());
  } else {
    Refine(grid.cells(), ratio, out.mutable_cells());
  }
  return out;
}

bool HasResolution(const GridGeometry& geometry, double resolution_m) {
  return std::abs(resolution_m / geometry.resolution_m() - 1.0) <= kIndexSlack;
}

}  // namespace fleetmerge
