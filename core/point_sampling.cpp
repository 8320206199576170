#include "core/point_sampling.hpp"

#include <algorithm>
#include <numeric>
#include <random>
#include <sstream>

#include "core/error.hpp"

namespace fleetmerge {

std::vector<Eigen::Vector2f> OccupiedCellCenters(const OccupancyGrid& grid) {
  return CellCenters(grid, CellState::kOccupied);
}

std::vector<Eigen::Vector2f> CellCenters(const OccupancyGrid& grid, CellState state) {
  std::vector<Eigen::Vector2f> points;
  const auto wanted = static_cast<std::uint8_t>(state);
  // Counted first: free cells run to 10^5-10^6, and growing the vector by doubling moved them
  // ~20 times.
  std::size_t count = 0;
  for (int j = 0; j < grid.height(); ++j) {
    const std::uint8_t* row = grid.cells().ptr<std::uint8_t>(j);
    for (int i = 0; i < grid.width(); ++i) count += row[i] == wanted;
  }
  // Sized once and written in place: emplace_back's capacity check and call per point were 5 %
  // of the hypothesis search.
  points.resize(count);
  Eigen::Vector2f* out = points.data();
  for (int j = 0; j < grid.height(); ++j) {
    const std::uint8_t* row = grid.cells().ptr<std::uint8_t>(j);
    for (int i = 0; i < grid.width(); ++i) {
      if (row[i] == wanted) *out++ = Eigen::Vector2f(i + 0.5f, j + 0.5f);
    }
  }
  return points;
}

void OccupiedAndFreeCellCenters(const OccupancyGrid& grid, std::vector<Eigen::Vector2f>* occupied,
                                std::vector<Eigen::Vector2f>* free) {
  const auto occupied_state = static_cast<std::uint8_t>(CellState::kOccupied);
  const auto free_state = static_cast<std::uint8_t>(CellState::kFree);
  std::size_t occupied_count = 0, free_count = 0;
  for (int j = 0; j < grid.height(); ++j) {
    const std::uint8_t* row = grid.cells().ptr<std::uint8_t>(j);
    for (int i = 0; i < grid.width(); ++i) {
      occupied_count += row[i] == occupied_state;
      free_count += row[i] == free_state;
    }
  }
  occupied->resize(occupied_count);  // written in place, as CellCenters does
  free->resize(free_count);
  Eigen::Vector2f* occupied_out = occupied->data();
  Eigen::Vector2f* free_out = free->data();
  for (int j = 0; j < grid.height(); ++j) {
    const std::uint8_t* row = grid.cells().ptr<std::uint8_t>(j);
    for (int i = 0; i < grid.width(); ++i) {
      if (row[i] == occupied_state) {
        *occupied_out++ = Eigen::Vector2f(i + 0.5f, j + 0.5f);
      } else if (row[i] == free_state) {
        *free_out++ = Eigen::Vector2f(i + 0.5f, j + 0.5f);
      }
    }
  }
}

std::vector<Eigen::Vector2f> SamplePoints(const std::vector<Eigen::Vector2f>& points,
                                          const SamplingOptions& options) {
  switch (options.mode) {
    case SamplingMode::kAll:
      return points;
    case SamplingMode::kEveryKth: {
      if (options.step < 1) {
        std::ostringstream msg;
        msg << "sampling step must be an integer >= 1, got " << options.step;
        throw Error(msg.str());
      }
      std::vector<Eigen::Vector2f> out;
      out.reserve(points.size() / options.step + 1);
      for (std::size_t k = 0; k < points.size(); k += options.step) out.push_back(points[k]);
      return out;
    }
    case SamplingMode::kRandomFraction: {
      if (!(options.fraction > 0.0 && options.fraction <= 1.0)) {
        std::ostringstream msg;
        msg << "sampling fraction must be in (0, 1], got " << options.fraction;
        throw Error(msg.str());
      }
      // Partial Fisher-Yates: an exact-size subset, then restored to scan order so that the
      // result is a subsequence like the other modes.
      const auto keep = static_cast<std::size_t>(std::max<double>(
          points.empty() ? 0.0 : 1.0, std::round(options.fraction * points.size())));
      std::vector<std::size_t> index(points.size());
      std::iota(index.begin(), index.end(), 0);
      std::mt19937 rng(options.seed);
      for (std::size_t k = 0; k < keep; ++k) {
        const std::size_t pick = k + rng() % (index.size() - k);
        std::swap(index[k], index[pick]);
      }
      index.resize(keep);
      std::sort(index.begin(), index.end());
      std::vector<Eigen::Vector2f> out;
      out.reserve(keep);
      for (std::size_t k : index) out.push_back(points[k]);
      return out;
    }
  }
  return points;
}

}  // namespace fleetmerge
