// A grid whose cells are drawn uniformly from unknown, free and occupied, row by row: tests that
// compare a function with its definition read literally, cell by cell.
#pragma once

#include <random>

#include "core/occupancy_grid.hpp"

namespace fleetmerge::testing {

inline OccupancyGrid RandomGrid(int width, int height, std::mt19937& rng) {
  OccupancyGrid grid(GridGeometry(0.05, {width, height}));
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) grid.set({i, j}, static_cast<CellState>(rng() % 3));
  }
  return grid;
}

}  // namespace fleetmerge::testing
