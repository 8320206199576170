#include "sim/ground_truth_pair.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace fleetmerge {
namespace {

// Bounding box (in cells) of the known cells.
cv::Rect KnownBox(const OccupancyGrid& grid) {
  cv::Mat1b known = grid.cells() != static_cast<std::uint8_t>(CellState::kUnknown);
  return cv::boundingRect(known);
}

OccupancyGrid Crop(const OccupancyGrid& grid, const cv::Rect& box) {
  const GridGeometry& g = grid.geometry();
  const Pose2 T_map_crop =
      g.T_map_grid() * Pose2(box.x * g.resolution_m(), box.y * g.resolution_m(), 0.0);
  return OccupancyGrid(GridGeometry(g.resolution_m(), {box.width, box.height}, T_map_crop),
                       grid.cells()(box).clone());
}

}  // namespace

OccupancyGrid Reframe(const OccupancyGrid& part, const Pose2& T_map_new) {
  // The new grid is axis-aligned in the new frame and covers the rotated part.
  const double r = part.geometry().resolution_m();
  const GridGeometry& gp = part.geometry();
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const Eigen::Vector2d& corner_grid :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(gp.width() * r, 0),
        Eigen::Vector2d(0, gp.height() * r), Eigen::Vector2d(gp.width() * r, gp.height() * r)}) {
    const Eigen::Vector2d p_new = T_map_new.inverse() * (gp.T_map_grid() * corner_grid);
    lo = lo.cwiseMin(p_new);
    hi = hi.cwiseMax(p_new);
  }
  const Eigen::Array2i size = ((hi - lo) / r).array().ceil().cast<int>() + 1;
  const GridGeometry g_new(r, size, Pose2(lo - Eigen::Vector2d::Constant(0.5 * r), 0.0));
  OccupancyGrid out(g_new);
  for (int j = 0; j < g_new.height(); ++j) {
    for (int i = 0; i < g_new.width(); ++i) {
      const Eigen::Array2i cell(i, j);
      out.set(cell, part.StateOrUnknown(gp.CellOf(T_map_new * g_new.CellCenter(cell))));
    }
  }
  return out;
}

GroundTruthFleet CutFleet(const OccupancyGrid& building, int robots, std::mt19937& rng,
                          const CutFleetOptions& options) {
  // Tiles of a cols x rows grid over the known box, each grown by `overlap` of a tile on every
  // side, so that neighbouring robots share a band and diagonal ones may not.
  const cv::Rect box = KnownBox(building);
  const int cols = static_cast<int>(std::ceil(std::sqrt(double(robots))));
  const int rows = (robots + cols - 1) / cols;
  const double tile_w = double(box.width) / cols, tile_h = double(box.height) / rows;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  GroundTruthFleet fleet;
  for (int k = 0; k < robots; ++k) {
    const int c = k % cols, r = k / cols;
    const int x0 = std::max(box.x, int(box.x + (c - options.overlap) * tile_w));
    const int y0 = std::max(box.y, int(box.y + (r - options.overlap) * tile_h));
    const int x1 = std::min(box.x + box.width, int(box.x + (c + 1 + options.overlap) * tile_w));
    const int y1 = std::min(box.y + box.height, int(box.y + (r + 1 + options.overlap) * tile_h));
    const OccupancyGrid part = Crop(building, cv::Rect(x0, y0, x1 - x0, y1 - y0));
    const Pose2 T_building_map((unit(rng) * 2 - 1) * options.max_offset_m,
                               (unit(rng) * 2 - 1) * options.max_offset_m,
                               (unit(rng) * 2 - 1) * M_PI);
    fleet.maps.push_back(Reframe(part, T_building_map));
    fleet.T_building_map.push_back(T_building_map);
  }
  return fleet;
}

GroundTruthPair CutPair(const OccupancyGrid& building, double yaw_rad, std::mt19937& rng,
                        const CutPairOptions& options) {
  const cv::Rect box = KnownBox(building);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const bool split_x = unit(rng) < 0.5;
  const double overlap =
      options.min_overlap + unit(rng) * (options.max_overlap - options.min_overlap);
  const int length = split_x ? box.width : box.height;
  const int a_end = static_cast<int>(length * (0.5 + overlap / 2));
  const int b_begin = static_cast<int>(length * (0.5 - overlap / 2));
  cv::Rect a_box = box, b_box = box;
  if (split_x) {
    a_box.width = a_end;
    b_box.x += b_begin;
    b_box.width -= b_begin;
  } else {
    a_box.height = a_end;
    b_box.y += b_begin;
    b_box.height -= b_begin;
  }
  const OccupancyGrid a = Crop(building, a_box);
  const OccupancyGrid b_part = Crop(building, b_box);

  // b's frame in a's (= the building's) frame, at a random offset and the given yaw.
  const Pose2 T_a_b((unit(rng) * 2 - 1) * options.max_offset_m,
                    (unit(rng) * 2 - 1) * options.max_offset_m, yaw_rad);
  const OccupancyGrid b = Reframe(b_part, T_a_b);
  return {a, b, T_a_b};
}

PoseError ComparePoses(const OccupancyGrid& b, const Pose2& T_a_b_estimate,
                       const Pose2& T_a_b_true) {
  PoseError error;
  error.yaw_deg =
      std::abs(WrapAngle(T_a_b_estimate.yaw_rad() - T_a_b_true.yaw_rad())) * 180.0 / M_PI;
  double sum = 0.0;
  const auto occupied = b.CellsIn(CellState::kOccupied);
  for (const auto& cell : occupied) {
    const Eigen::Vector2d p_b = b.geometry().CellCenter(cell);
    sum += (T_a_b_estimate * p_b - T_a_b_true * p_b).norm();
  }
  if (!occupied.empty()) {
    error.mean_displacement_cells = sum / occupied.size() / b.geometry().resolution_m();
  }
  return error;
}

}  // namespace fleetmerge
