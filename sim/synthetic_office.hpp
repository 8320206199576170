// A seeded generator of synthetic office floors, for demos and tests of map merging.
//
// The building fills the grid: an outer wall on the grid border, a main corridor across the full
// width at a random height, optionally a second corridor from it up to the top wall at a random
// position, and rows of rooms of random widths along both sides of the corridors. Every room has
// a door (a gap in its corridor wall) and the rooms beside the vertical corridor a second one
// into it. Tables and pillars stand inside the rooms, clear of the walls by one door width so
// they never block a door. With cut_corner the top-right room is left out and its area, walls
// included, is kUnknown "outside": the building becomes L-shaped.
//
// Random room widths, corridor positions and the missing corner make the floor plan asymmetric
// and distinctive, as map merging needs. Cells: walls and clutter kOccupied, everything else in
// the building kFree, outside kUnknown. The map frame's origin is the building's lower-left
// corner (T_map_grid = identity).
#pragma once

#include <cstdint>

#include "core/occupancy_grid.hpp"

namespace fleetmerge {

struct OfficeOptions {
  double width_m = 30.0;
  double height_m = 20.0;
  double resolution_m = 0.05;
  double corridor_width_m = 2.0;
  double wall_thickness_m = 0.10;
  int clutter_per_room = 2;  // tables and pillars per room
  double door_width_m = 0.9;
  double min_room_width_m = 2.5;  // along the corridor
  double max_room_width_m = 6.0;
  bool vertical_corridor = true;  // a second corridor from the main one to the top wall
  bool cut_corner = true;         // leave out the top-right room (L-shaped building)
};

// The floor for `seed`: the same options and seed give identical cells on every platform (the
// random numbers come from std::mt19937, whose sequence the standard fixes, mapped to ranges by
// hand because std::uniform_*_distribution's mapping differs between standard libraries).
// Throws fleetmerge::Error if an option is not a finite positive number (clutter_per_room may be
// 0), min_room_width_m > max_room_width_m, a door does not fit a room, or the building is too
// small for two rows of rooms of at least 2 m depth and two rooms per row.
OccupancyGrid GenerateOfficeFloor(const OfficeOptions& options, std::uint32_t seed);

}  // namespace fleetmerge
