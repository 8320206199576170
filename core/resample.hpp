// Resampling an occupancy grid to another cell size, keeping its map frame and grid origin.
//
// The new grid has the same T_map_grid and size ceil(old extent / new resolution) per axis, so
// it covers at least the old extent (the extra sliver, if any, is kUnknown).
//
// Coarsening (larger cells): a new cell takes the "strongest" state among the source cells it
// overlaps, in the order occupied > free > unknown. Occupied-wins keeps walls one source cell
// thick from vanishing (a majority rule would erase them, and the merger needs walls to align);
// free-beats-unknown keeps the explored area from shrinking. Because the CellState values are
// ordered kUnknown = 0 < kFree = 1 < kOccupied = 2, this rule is simply the maximum.
//
// Refining (smaller cells): a new cell takes the state of the source cell containing its centre
// (nearest-neighbour, no invented detail).
#pragma once

#include "core/occupancy_grid.hpp"

namespace fleetmerge {

// Returns a copy when resolution_m equals the grid's (HasResolution). Throws fleetmerge::Error
// unless resolution_m is a finite number > 0.
OccupancyGrid ResampleToResolution(const OccupancyGrid& grid, double resolution_m);

// Whether the grid's cells are resolution_m wide, to 1e-9 relative: ResampleToResolution would
// return its cells unchanged.
bool HasResolution(const GridGeometry& geometry, double resolution_m);

}  // namespace fleetmerge
