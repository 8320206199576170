// Occupied-cell point sets and the sampling variants of Section III-D.
//
// The Hough transform costs O(m n_theta) and the X/Y spectra O(m) for m occupied cells; the paper
// speeds both up by using only a subset of the points: a random fraction ("probabilistic Hough
// transform", Kiryati et al.) or every k-th point (the "incremental" approach).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/occupancy_grid.hpp"

namespace fleetmerge {

enum class SamplingMode { kAll, kRandomFraction, kEveryKth };

struct SamplingOptions {
  SamplingMode mode = SamplingMode::kAll;
  double fraction = 1.0;   // kRandomFraction: share of the points kept, in (0, 1]
  int step = 1;            // kEveryKth: keep points m_1, m_(1+k), m_(1+2k), ...
  std::uint32_t seed = 0;  // kRandomFraction: the same seed picks the same subset
};

// Centres of the occupied cells in the grid frame, in CELL units (cell (i, j) -> (i+.5, j+.5)),
// row by row from the bottom.
std::vector<Eigen::Vector2f> OccupiedCellCenters(const OccupancyGrid& grid);
// The same for the cells in `state`.
std::vector<Eigen::Vector2f> CellCenters(const OccupancyGrid& grid, CellState state);

// CellCenters for kOccupied and kFree from one pass over the grid's cells (counting) and one
// more (filling), instead of two each: the same two lists.
void OccupiedAndFreeCellCenters(const OccupancyGrid& grid, std::vector<Eigen::Vector2f>* occupied,
                                std::vector<Eigen::Vector2f>* free);

// The subset of `points` chosen by `options` (order preserved). Throws fleetmerge::Error for a
// fraction outside (0, 1] or a step < 1.
std::vector<Eigen::Vector2f> SamplePoints(const std::vector<Eigen::Vector2f>& points,
                                          const SamplingOptions& options);

}  // namespace fleetmerge
