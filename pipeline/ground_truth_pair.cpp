#include "pipeline/ground_truth_pair.hpp"

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

  // b's frame in a's (= the building's) frame, and b's grid: axis-aligned in b's frame, covering
  // the rotated part, with its corner at a random offset (map_server origins are arbitrary).
  const double r = building.geometry().resolution_m();
  const Pose2 T_a_b((unit(rng) * 2 - 1) * options.max_offset_m,
                    (unit(rng) * 2 - 1) * options.max_offset_m, yaw_rad);
  const GridGeometry& gp = b_part.geometry();
  Eigen::Vector2d lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const Eigen::Vector2d corner_grid :
       {Eigen::Vector2d(0, 0), Eigen::Vector2d(gp.width() * r, 0),
        Eigen::Vector2d(0, gp.height() * r), Eigen::Vector2d(gp.width() * r, gp.height() * r)}) {
    const Eigen::Vector2d p_b = T_a_b.inverse() * (gp.T_map_grid() * corner_grid);
    lo = lo.cwiseMin(p_b);
    hi = hi.cwiseMax(p_b);
  }
  const Eigen::Array2i size = ((hi - lo) / r).array().ceil().cast<int>() + 1;
  const GridGeometry gb(r, size, Pose2(lo - Eigen::Vector2d::Constant(0.5 * r), 0.0));
  OccupancyGrid b(gb);
  for (int j = 0; j < gb.height(); ++j) {
    for (int i = 0; i < gb.width(); ++i) {
      const Eigen::Array2i cell(i, j);
      b.set(cell, b_part.StateOrUnknown(gp.CellOf(T_a_b * gb.CellCenter(cell))));
    }
  }
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
