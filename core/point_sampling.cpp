#include "core/point_sampling.hpp"

#include <algorithm>
#include <array>
#include <numeric>
#include <random>
#include <sstream>

#include "core/error.hpp"

namespace fleetmerge {

std::vector<Eigen::Vector2f> OccupiedCellCenters(const OccupancyGrid& grid) {
  return CellCenters(grid, CellState::kOccupied);
}

namespace {

// The centres of the cells of each state asked for (lists[state]; nullptr: not wanted), row by
// row: counted in one pass, then written in place into lists sized once (emplace_back's call
// and capacity check per point were 5 % of the hypothesis search; free cells run to 10^5-10^6).
void CentresByState(const OccupancyGrid& grid,
                    const std::array<std::vector<Eigen::Vector2f>*, 3>& lists) {
  constexpr auto kFree = static_cast<std::uint8_t>(CellState::kFree);
  constexpr auto kOccupied = static_cast<std::uint8_t>(CellState::kOccupied);
  std::array<std::size_t, 3> counts{};
  for (int j = 0; j < grid.height(); ++j) {
    const std::uint8_t* row = grid.cells().ptr<std::uint8_t>(j);
    for (int i = 0; i < grid.width(); ++i) {
      counts[kFree] += row[i] == kFree;
      counts[kOccupied] += row[i] == kOccupied;
    }
  }
  // The rest is unknown (at most: each list is cut to what was written below).
  counts[static_cast<std::uint8_t>(CellState::kUnknown)] =
      grid.cells().total() - counts[kFree] - counts[kOccupied];
  std::array<Eigen::Vector2f*, 3> out{};
  for (std::size_t state = 0; state < 3; ++state) {
    if (lists[state] == nullptr) continue;
    lists[state]->resize(counts[state]);
    out[state] = lists[state]->data();
  }
  for (int j = 0; j < grid.height(); ++j) {
    const std::uint8_t* row = grid.cells().ptr<std::uint8_t>(j);
    for (int i = 0; i < grid.width(); ++i) {
      if (row[i] < 3 && out[row[i]] != nullptr)
        *out[row[i]]++ = Eigen::Vector2f(i + 0.5f, j + 0.5f);
    }
  }
  for (std::size_t state = 0; state < 3; ++state) {
    if (lists[state] != nullptr) lists[state]->resize(out[state] - lists[state]->data());
  }
}

}  // namespace

std::vector<Eigen::Vector2f> CellCenters(const OccupancyGrid& grid, CellState state) {
  std::vector<Eigen::Vector2f> points;
  std::array<std::vector<Eigen::Vector2f>*, 3> lists{};
  lists[static_cast<std::uint8_t>(state)] = &points;
  CentresByState(grid, lists);
  return points;
}

void OccupiedAndFreeCellCenters(const OccupancyGrid& grid, std::vector<Eigen::Vector2f>* occupied,
                                std::vector<Eigen::Vector2f>* free) {
  std::array<std::vector<Eigen::Vector2f>*, 3> lists{};
  lists[static_cast<std::uint8_t>(CellState::kOccupied)] = occupied;
  lists[static_cast<std::uint8_t>(CellState::kFree)] = free;
  CentresByState(grid, lists);
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
