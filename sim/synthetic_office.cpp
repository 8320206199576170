#include "sim/synthetic_office.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "sim/portable_rng.hpp"

namespace fleetmerge {
namespace {

constexpr double kMinRoomDepthM = 2.0;

using Rng = PortableRng;

// The options converted to whole cells once, so all drawing is exact integer geometry.
struct Dimensions {
  int width = 0;
  int height = 0;
  int wall = 0;
  int corridor = 0;
  int door = 0;
  int min_room = 0;
  int max_room = 0;
  double resolution_m = 0.0;
  int Cells(double length_m) const {
    return std::max(1, static_cast<int>(std::lround(length_m / resolution_m)));
  }
};

// Free interior of a room, half-open cell ranges [x0, x1) x [y0, y1).
struct Room {
  int x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  bool door_above = false;    // door in the wall above (rooms below the main corridor)
  int side_door_wall_x = -1;  // first column of a wall shared with the vertical corridor
};

struct Corridors {
  int main_y0 = 0;       // main corridor rows [main_y0, main_y0 + corridor)
  int vertical_x0 = -1;  // vertical corridor columns [x0, x0 + corridor), -1 if none
};

void FillRect(cv::Mat1b& cells, int x0, int y0, int x1, int y1, CellState state) {
  if (x1 <= x0 || y1 <= y0) return;
  // Rows of `cells` count from the bottom, so cv::Rect's y is the grid row: no flip needed.
  cv::rectangle(cells, cv::Rect(x0, y0, x1 - x0, y1 - y0), cv::Scalar(static_cast<double>(state)),
                cv::FILLED);
}

void Require(bool condition, const std::string& what) {
  if (!condition) throw Error("office generator: " + what);
}

void ValidateOptions(const OfficeOptions& o) {
  const std::pair<const char*, double> lengths[] = {{"width_m", o.width_m},
                                                    {"height_m", o.height_m},
                                                    {"resolution_m", o.resolution_m},
                                                    {"corridor_width_m", o.corridor_width_m},
                                                    {"wall_thickness_m", o.wall_thickness_m},
                                                    {"door_width_m", o.door_width_m},
                                                    {"min_room_width_m", o.min_room_width_m},
                                                    {"max_room_width_m", o.max_room_width_m}};
  for (const auto& [name, value] : lengths) {
    Require(value > 0.0 && std::isfinite(value),
            std::string(name) + " must be a finite number > 0, got " + std::to_string(value));
  }
  Require(o.clutter_per_room >= 0, "clutter_per_room must be >= 0");
  Require(o.min_room_width_m <= o.max_room_width_m, "min_room_width_m > max_room_width_m");
  Require(o.door_width_m + 2.0 * o.wall_thickness_m <= o.min_room_width_m,
          "door_width_m + 2 wall thicknesses must fit in min_room_width_m");
  std::ostringstream msg;
  msg << "building " << o.width_m << " x " << o.height_m << " m is too small: needs height >= "
      << "corridor + 2 x " << kMinRoomDepthM << " m rooms + 4 walls and width >= 2 rooms + 3 walls";
  Require(o.height_m >= o.corridor_width_m + 2.0 * kMinRoomDepthM + 4.0 * o.wall_thickness_m &&
              o.width_m >= 2.0 * o.min_room_width_m + 3.0 * o.wall_thickness_m,
          msg.str());
}

Dimensions ToCells(const OfficeOptions& o) {
  Dimensions d;
  d.resolution_m = o.resolution_m;
  d.width = d.Cells(o.width_m);
  d.height = d.Cells(o.height_m);
  d.wall = d.Cells(o.wall_thickness_m);
  d.corridor = d.Cells(o.corridor_width_m);
  d.door = d.Cells(o.door_width_m);
  d.min_room = d.Cells(o.min_room_width_m);
  d.max_room = d.Cells(o.max_room_width_m);
  return d;
}

void DrawOuterWall(cv::Mat1b& cells, const Dimensions& d) {
  const CellState wall = CellState::kOccupied;
  FillRect(cells, 0, 0, d.width, d.wall, wall);
  FillRect(cells, 0, d.height - d.wall, d.width, d.height, wall);
  FillRect(cells, 0, 0, d.wall, d.height, wall);
  FillRect(cells, d.width - d.wall, 0, d.width, d.height, wall);
}

// The main corridor somewhere between 30 % and 50 % of the height (never centred, so the two
// rows of rooms differ in depth), and the optional vertical one between 30 % and 60 % of the
// width, both with their walls; the vertical corridor opens into the main one.
Corridors DrawCorridors(cv::Mat1b& cells, const Dimensions& d, bool vertical, Rng& rng) {
  const CellState wall = CellState::kOccupied;
  const int min_depth = static_cast<int>(std::ceil(kMinRoomDepthM / d.resolution_m));
  const int lo_y = 2 * d.wall + min_depth;                          // room row below fits
  const int hi_y = d.height - d.corridor - 2 * d.wall - min_depth;  // room row above fits
  Corridors c;
  const int drawn_y = static_cast<int>(d.height * rng.Uniform(0.30, 0.50));
  c.main_y0 = std::max(lo_y, std::min(drawn_y, hi_y));  // not std::clamp: rounding may give hi < lo
  const int top_y = c.main_y0 + d.corridor;             // first row above the main corridor
  FillRect(cells, 0, c.main_y0 - d.wall, d.width, c.main_y0, wall);
  FillRect(cells, 0, top_y, d.width, top_y + d.wall, wall);

  // Both room blocks beside the vertical corridor must hold at least one minimal room.
  const int lo_x = std::max(2 * d.wall + d.min_room, static_cast<int>(0.3 * d.width));
  const int hi_x =
      std::min(d.width - d.corridor - 2 * d.wall - d.min_room, static_cast<int>(0.6 * d.width));
  if (!vertical || lo_x > hi_x) return c;
  c.vertical_x0 = rng.UniformInt(lo_x, hi_x);
  const int x1 = c.vertical_x0 + d.corridor;
  FillRect(cells, c.vertical_x0 - d.wall, top_y, c.vertical_x0, d.height, wall);
  FillRect(cells, x1, top_y, x1 + d.wall, d.height, wall);
  FillRect(cells, c.vertical_x0, top_y, x1, top_y + d.wall, CellState::kFree);  // junction
  return c;
}

// Splits the columns [x0, x1) of one row of rooms into rooms of random widths separated by
// walls. A remainder too narrow for another room widens the last one, adding more variety.
void SplitIntoRooms(cv::Mat1b& cells, const Dimensions& d, Room row, Rng& rng,
                    std::vector<Room>& rooms) {
  const int x_end = row.x1;
  int start = row.x0;
  while (start < x_end) {
    int end = start + rng.UniformInt(d.min_room, d.max_room);
    if (x_end - end < d.wall + d.min_room) end = x_end;
    FillRect(cells, end, row.y0, end + d.wall, row.y1, CellState::kOccupied);
    row.x0 = start;
    row.x1 = end;
    rooms.push_back(row);
    start = end + d.wall;
  }
}

std::vector<Room> LayOutRooms(cv::Mat1b& cells, const Dimensions& d, const Corridors& c, Rng& rng) {
  std::vector<Room> rooms;
  const int top_y0 = c.main_y0 + d.corridor + d.wall;
  SplitIntoRooms(cells, d, {d.wall, d.width - d.wall, d.wall, c.main_y0 - d.wall, true}, rng,
                 rooms);
  if (c.vertical_x0 < 0) {
    SplitIntoRooms(cells, d, {d.wall, d.width - d.wall, top_y0, d.height - d.wall}, rng, rooms);
    return rooms;
  }
  const int left_x1 = c.vertical_x0 - d.wall;
  const int right_x0 = c.vertical_x0 + d.corridor + d.wall;
  SplitIntoRooms(cells, d, {d.wall, left_x1, top_y0, d.height - d.wall}, rng, rooms);
  rooms.back().side_door_wall_x = left_x1;  // its right wall is the corridor's left wall
  const std::size_t first_right = rooms.size();
  SplitIntoRooms(cells, d, {right_x0, d.width - d.wall, top_y0, d.height - d.wall}, rng, rooms);
  rooms[first_right].side_door_wall_x = right_x0 - d.wall;
  return rooms;
}

void DrawDoors(cv::Mat1b& cells, const Dimensions& d, const Room& room, Rng& rng) {
  const CellState open = CellState::kFree;
  const int door_x = rng.UniformInt(room.x0, std::max(room.x0, room.x1 - d.door));
  const int wall_y0 = room.door_above ? room.y1 : room.y0 - d.wall;
  FillRect(cells, door_x, wall_y0, std::min(door_x + d.door, room.x1), wall_y0 + d.wall, open);
  if (room.side_door_wall_x < 0) return;
  const int door_y = rng.UniformInt(room.y0, std::max(room.y0, room.y1 - d.door));
  FillRect(cells, room.side_door_wall_x, door_y, room.side_door_wall_x + d.wall,
           std::min(door_y + d.door, room.y1), open);
}

// Tables (0.6..1.6 x 0.6..1.0 m, either way round) and pillars (0.3..0.5 m square), kept one
// door width from the walls: the walkway around the room keeps every door and corner reachable.
void DrawClutter(cv::Mat1b& cells, const Dimensions& d, const Room& room, int count, Rng& rng) {
  const int room_w = room.x1 - room.x0 - 2 * d.door;
  const int room_h = room.y1 - room.y0 - 2 * d.door;
  if (room_w <= 0 || room_h <= 0) return;
  for (int k = 0; k < count; ++k) {
    int w = 0, h = 0;
    if (rng.Uniform(0.0, 1.0) < 0.3) {
      w = h = d.Cells(rng.Uniform(0.3, 0.5));
    } else {
      w = d.Cells(rng.Uniform(0.6, 1.6));
      h = d.Cells(rng.Uniform(0.6, 1.0));
      if (rng.Uniform(0.0, 1.0) < 0.5) std::swap(w, h);
    }
    w = std::min(w, room_w);
    h = std::min(h, room_h);
    const int x = room.x0 + d.door + rng.UniformInt(0, room_w - w);
    const int y = room.y0 + d.door + rng.UniformInt(0, room_h - h);
    FillRect(cells, x, y, x + w, y + h, CellState::kOccupied);
  }
}

}  // namespace

OccupancyGrid GenerateOfficeFloor(const OfficeOptions& options, std::uint32_t seed) {
  ValidateOptions(options);
  const Dimensions d = ToCells(options);
  Rng rng(seed);
  cv::Mat1b cells(d.height, d.width, static_cast<std::uint8_t>(CellState::kFree));
  DrawOuterWall(cells, d);
  const Corridors corridors = DrawCorridors(cells, d, options.vertical_corridor, rng);
  const std::vector<Room> rooms = LayOutRooms(cells, d, corridors, rng);
  // With cut_corner the last room (the top-right one) gets no door and no clutter.
  const std::size_t furnished = rooms.size() - (options.cut_corner ? 1 : 0);
  for (std::size_t k = 0; k < furnished; ++k) {
    DrawDoors(cells, d, rooms[k], rng);
    DrawClutter(cells, d, rooms[k], options.clutter_per_room, rng);
  }
  if (options.cut_corner) {
    // Its left and bottom walls become outer walls; its top and right walls are outside.
    const Room& corner = rooms.back();
    FillRect(cells, corner.x0, corner.y0, d.width, d.height, CellState::kUnknown);
  }
  return OccupancyGrid(GridGeometry(options.resolution_m, {d.width, d.height}), cells);
}

}  // namespace fleetmerge
