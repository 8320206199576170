#include "refine/wall_distance_field.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "core/image_filters.hpp"
#include "core/image_masks.hpp"
#include "core/point_sampling.hpp"

namespace fleetmerge {

WallDistanceField::WallDistanceField(const OccupancyGrid& grid, double truncation_cells)
    : WallDistanceField(OccupiedCellCenters(grid), truncation_cells) {}

WallDistanceField::WallDistanceField(const std::vector<Eigen::Vector2f>& walls,
                                     double truncation_cells)
    : truncation_cells_(truncation_cells) {
  // Only a margin of `truncation` around the walls differs from the truncation value, so the
  // field covers the walls' bounding box plus that margin, not the whole grid (re-framed maps
  // are mostly unknown). The box from the centres (cell i's is i + 0.5): no pass over the grid.
  cv::Rect box;
  if (!walls.empty()) {
    int i0 = int(walls.front().x()), i1 = i0, j0 = int(walls.front().y()), j1 = j0;
    for (const auto& w : walls) {
      i0 = std::min(i0, int(w.x())), i1 = std::max(i1, int(w.x()));
      j0 = std::min(j0, int(w.y())), j1 = std::max(j1, int(w.y()));
    }
    box = cv::Rect(i0, j0, i1 - i0 + 1, j1 - j0 + 1);
  }
  const int radius = static_cast<int>(std::ceil(truncation_cells));
  const int margin = radius + 2;
  offset_ = Eigen::Array2i(box.x - margin, box.y - margin);
  distances_ = cv::Mat1f(box.height + 2 * margin, box.width + 2 * margin,
                         static_cast<float>(truncation_cells));
  // Why not cv::distanceTransform: it visits every pixel of the box (about 30 ms for a
  // 1300 x 1250 re-framed map here), while the truncated field only needs a disc of radius
  // `truncation` stamped around each wall cell: exact distances at a fraction of the cost.
  std::vector<std::pair<cv::Point, float>> disc;
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      const float d = std::hypot(float(dx), float(dy));
      if (d < truncation_cells) disc.push_back({cv::Point(dx, dy), d});
    }
  }
  for (const auto& w : walls) {
    const cv::Point c(int(w.x()) - offset_.x(), int(w.y()) - offset_.y());
    for (const auto& [delta, d] : disc) {
      float& cell = distances_(c.y + delta.y, c.x + delta.x);
      cell = std::min(cell, d);
    }
  }
  // Stencil rows floor(r) - 1 .. floor(r) + 2 (and columns): a 4 x 4 dilation anchored at
  // (1, 1) of the cells below the truncation value, the border replicated as the grid does.
  const cv::Mat1b near = CompareMask(distances_, cv::CMP_LT, static_cast<float>(truncation_cells));
  flat_ = CompareMask(MaxFilter<1, 2>(near), cv::CMP_EQ, 0);
  grid_ = std::make_unique<Grid>(Grid{distances_.ptr<float>(), distances_.rows, distances_.cols});
  interpolator_ = std::make_unique<Interpolator>(*grid_);
}

WallDistanceField::WallDistanceField(double truncation_cells, const Eigen::Array2i& offset_cells,
                                     const cv::Mat1f& distances, const cv::Mat1b& flat)
    : truncation_cells_(truncation_cells),
      offset_(offset_cells),
      distances_(distances.isContinuous() ? distances : distances.clone()),
      flat_(flat) {
  if (distances.empty() || distances.size() != flat.size()) {
    throw Error("wall distance field: distances and flat mask must be one non-empty size");
  }
  grid_ = std::make_unique<Grid>(Grid{distances_.ptr<float>(), distances_.rows, distances_.cols});
  interpolator_ = std::make_unique<Interpolator>(*grid_);
}

}  // namespace fleetmerge
