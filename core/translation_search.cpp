#include "core/translation_search.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>

#include "core/error.hpp"
#include "core/image_filters.hpp"
#include "core/image_masks.hpp"

namespace fleetmerge {
namespace {

// The coarse pixel must stay small enough to resolve the smaller map. The extent that sets it is
// the larger map's (which keeps the transforms near coarse_max_side) but at most twice the
// smaller map's, and at least a quarter of the larger's (which bounds the transforms at about
// 4 coarse_max_side however small the smaller map). Maps of similar size, as a fleet's robots,
// get the larger extent as before. A robot's map searched against a 4000 x 4000 site: at the
// site's pooling (30 cells) a robot of a 50 m path was 89 deg off
// (FixedBase.SmallRobotsAreFoundInASiteOfFourBuildings); at twice the robot's extent (8-10
// cells) all 60 robots of scripts/large_site_benchmark.sh (50 and 100 m) were right.
int PoolingFor(double a_extent_cells, double b_extent_cells, int coarse_max_side) {
  const double larger = std::max(a_extent_cells, b_extent_cells);
  const double smaller = std::min(a_extent_cells, b_extent_cells);
  const double side = std::max(std::min(larger, 2.0 * smaller), larger / 4.0);
  return std::max(1, static_cast<int>(std::ceil(side / std::max(coarse_max_side, 8))));
}

// A map on the coarse grid: pixels holding a wall cell, and open space: pixels whose known cells
// are all free and that do not touch a wall pixel (so a wall off by a pixel, from pooling or a
// rotation error of a fraction of a degree, is not penalised).
struct CoarseLayers {
  cv::Mat1f walls;
  cv::Mat1f open;
};

CoarseLayers OpenSpaceAround(cv::Mat1f walls, cv::Mat1f free) {
  free.setTo(0.f, CompareMask(MaxFilter<1, 1>(walls), cv::CMP_GT, 0.0));
  return {walls, free};
}

CoarseLayers CoarseGridLayers(const OccupancyGrid& a, int pooling) {
  const int w = (a.width() + pooling - 1) / pooling, h = (a.height() + pooling - 1) / pooling;
  cv::Mat1f walls(h, w, 0.f), free(h, w, 0.f);
  // Pixel by pixel (a block of `pooling` cells of a row at a time), not cell by cell with two
  // divisions each.
  for (int j = 0; j < a.height(); ++j) {
    const std::uint8_t* row = a.cells().ptr<std::uint8_t>(j);
    float* walls_row = walls.ptr<float>(j / pooling);
    float* free_row = free.ptr<float>(j / pooling);
    for (int u = 0; u < w; ++u) {
      const int end = std::min(a.width(), (u + 1) * pooling);
      bool wall = false, open = false;
      for (int i = u * pooling; i < end; ++i) {
        wall |= row[i] == std::uint8_t(CellState::kOccupied);
        open |= row[i] == std::uint8_t(CellState::kFree);
      }
      if (wall) walls_row[u] = 1.f;
      if (open) free_row[u] = 1.f;
    }
  }
  return OpenSpaceAround(walls, free);
}

// The fixed layers of a: the score of a pixel for a wall of b, and a's walls, cropped to a's
// known cells plus a margin the blur and the dilation cannot cross (everything beyond is zero in
// both layers, so the crop changes no correlation value; re-framed maps are mostly unknown and
// the transforms' cost grows with the area). *offset_px: the crop's first pixel.
std::vector<cv::Mat1f> FixedLayers(const OccupancyGrid& a, int pooling, double free_penalty,
                                   cv::Point* offset_px) {
  const CoarseLayers layers = CoarseGridLayers(a, pooling);
  cv::Rect known = NonZeroBox(MaskOr(CompareMask(layers.walls, cv::CMP_GT, 0.0),
                                     CompareMask(layers.open, cv::CMP_GT, 0.0)));
  *offset_px = cv::Point(0, 0);
  if (known.area() > 0) {
    constexpr int kMargin = 3;  // the 5 x 5 blur reaches 2 pixels, the wall dilation 1
    known = cv::Rect(known.x - kMargin, known.y - kMargin, known.width + 2 * kMargin,
                     known.height + 2 * kMargin) &
            cv::Rect(0, 0, layers.walls.cols, layers.walls.rows);
    *offset_px = known.tl();
  } else {
    known = cv::Rect(0, 0, layers.walls.cols, layers.walls.rows);
  }
  // The blur widens the peak so a rotation off by a fraction of a degree still correlates.
  const cv::Mat1f wall_score = GaussianBlur5x5(layers.walls, 1.0);
  // score = wall_score - free_penalty * open, fused as cv::scaleAdd does it (whose object file
  // would bring OpenCV's PCA and LAPACK into the executable: core/image_masks.hpp).
  cv::Mat1f score(wall_score.size());
  const float minus_penalty = static_cast<float>(-free_penalty);
  for (int j = 0; j < score.rows; ++j) {
    const float* open_row = layers.open.ptr<float>(j);
    const float* wall_row = wall_score.ptr<float>(j);
    float* score_row = score.ptr<float>(j);
    for (int i = 0; i < score.cols; ++i) {
      score_row[i] = std::fma(open_row[i], minus_penalty, wall_row[i]);
    }
  }
  return {score(known).clone(), layers.walls(known).clone()};
}

using PointBox = CorrelationTranslation::PointBox;

// The rotated b points' bounding box, over every point the search rasterizes.
PointBox BoundingBox(const std::vector<Eigen::Vector2f>& scored_walls,
                     const std::vector<Eigen::Vector2f>& walls,
                     const std::vector<Eigen::Vector2f>& free) {
  // Four independent running boxes, merged at the end: one would make every point wait for
  // the previous point's min and max (the same box: min and max do not depend on the order).
  constexpr std::size_t kLanes = 4;
  std::array<PointBox, kLanes> lanes;
  lanes.fill(PointBox{walls.front(), walls.front()});
  for (const auto* points : {&scored_walls, &walls, &free}) {
    const Eigen::Vector2f* q = points->data();
    const std::size_t n = points->size();
    std::size_t k = 0;
    for (; k + kLanes <= n; k += kLanes) {
      for (std::size_t lane = 0; lane < kLanes; ++lane) {
        lanes[lane].min = lanes[lane].min.cwiseMin(q[k + lane]);
        lanes[lane].max = lanes[lane].max.cwiseMax(q[k + lane]);
      }
    }
    for (; k < n; ++k) {
      lanes[0].min = lanes[0].min.cwiseMin(q[k]);
      lanes[0].max = lanes[0].max.cwiseMax(q[k]);
    }
  }
  PointBox box = lanes[0];
  for (std::size_t lane = 1; lane < kLanes; ++lane) {
    box.min = box.min.cwiseMin(lanes[lane].min);
    box.max = box.max.cwiseMax(lanes[lane].max);
  }
  return box;
}

// Local maxima of a 2-D surface (5x5 neighbourhood, border rows and columns excluded), largest
// first, with sub-pixel parabolas. Only a pixel above the count-th best maximum found so far can
// still be one of the results, so almost every pixel costs one comparison (a 5x5 dilation of the
// whole surface was 6 % of the hypothesis search).
std::vector<TranslationCandidate> SurfacePeaks(const cv::Mat1f& surface, int count) {
  std::vector<TranslationCandidate> peaks;
  if (count <= 0) return peaks;
  std::vector<float> best;  // the count best maxima so far, descending
  const auto is_local_maximum = [&](int r, int c, float v) {
    for (int y = std::max(r - 2, 0); y <= std::min(r + 2, surface.rows - 1); ++y) {
      const float* row = surface.ptr<float>(y);
      for (int x = std::max(c - 2, 0); x <= std::min(c + 2, surface.cols - 1); ++x) {
        if (row[x] > v) return false;
      }
    }
    return true;
  };
  for (int r = 1; r + 1 < surface.rows; ++r) {
    const float* row = surface.ptr<float>(r);
    for (int c = 1; c + 1 < surface.cols; ++c) {
      const float v = row[c];
      if (v <= 0.f) continue;
      if (static_cast<int>(best.size()) == count && v < best.back()) continue;
      if (!is_local_maximum(r, c, v)) continue;
      const auto vertex = [](float m, float z, float p) {
        const float curvature = m - 2.f * z + p;
        return curvature < 0.f ? 0.5f * (m - p) / curvature : 0.f;
      };
      const double dx = c + vertex(row[c - 1], v, row[c + 1]);
      const double dy = r + vertex(surface(r - 1, c), v, surface(r + 1, c));
      peaks.push_back({Eigen::Vector2d(dx, dy), v});
      best.insert(std::upper_bound(best.begin(), best.end(), v, std::greater<float>()), v);
      if (static_cast<int>(best.size()) > count) best.pop_back();
    }
  }
  std::sort(peaks.begin(), peaks.end(),
            [](const auto& l, const auto& r) { return l.score > r.score; });
  if (static_cast<int>(peaks.size()) > count) peaks.resize(count);
  return peaks;
}

}  // namespace

double FixedExtentCells(const OccupancyGrid& a) {
  return std::max(double(a.width()), double(a.height()));
}

double RotatedExtentCells(const OccupancyGrid& b) {
  return std::hypot(double(b.width()), double(b.height()));
}

int CorrelationPooling(const OccupancyGrid& a, const OccupancyGrid& b,
                       const TranslationOptions& options) {
  return PoolingFor(FixedExtentCells(a), RotatedExtentCells(b), options.coarse_max_side);
}

CorrelationTranslation::PointBox CorrelationTranslation::Bounds(
    const std::vector<Eigen::Vector2f>& scored_walls, const std::vector<Eigen::Vector2f>& walls,
    const std::vector<Eigen::Vector2f>& free) {
  if (walls.empty()) throw Error("CorrelationTranslation::Bounds: no walls");
  return BoundingBox(scored_walls, walls, free);
}

cv::Size CorrelationTranslation::RasterSize(const PointBox& box, int pooling) {
  return cv::Size(int((box.max.x() - box.min.x()) / pooling) + 1,
                  int((box.max.y() - box.min.y()) / pooling) + 1);
}

CorrelationTranslation::CorrelationTranslation(const OccupancyGrid& a, int pooling,
                                               cv::Size max_b_pixels,
                                               const TranslationOptions& options)
    : options_(options),
      pooling_(std::max(pooling, 1)),
      max_b_size_(max_b_pixels),
      correlator_(FixedLayers(a, pooling_, options.free_penalty, &a_offset_px_), max_b_size_) {}

CorrelationTranslation CorrelationTranslation::WithOwnBuffers() const {
  CorrelationTranslation copy(*this);
  copy.correlator_ = correlator_.WithOwnBuffers();
  return copy;
}

CorrelationTranslation::BLayers CorrelationTranslation::RasterizeB(
    const std::vector<Eigen::Vector2f>& scored_walls, const std::vector<Eigen::Vector2f>& walls,
    const std::vector<Eigen::Vector2f>& free, const PointBox& box) const {
  const Eigen::Vector2f q_min = box.min;
  const cv::Size size = RasterSize(box, pooling_);
  const int w = std::min(max_b_size_.width, size.width);
  const int h = std::min(max_b_size_.height, size.height);
  const float pooling = static_cast<float>(pooling_);
  const auto rasterize = [&](const std::vector<Eigen::Vector2f>& points) {
    cv::Mat1f image(h, w, 0.f);
    float* pixels = image.ptr<float>(0);  // a new matrix is continuous
    // Pixel indices for a chunk of points (a loop the compiler vectorises), then the stores.
    constexpr std::size_t kChunk = 1024;
    std::array<int, kChunk> index;
    for (std::size_t start = 0; start < points.size(); start += kChunk) {
      const std::size_t count = std::min(kChunk, points.size() - start);
      const Eigen::Vector2f* q = points.data() + start;
      for (std::size_t n = 0; n < count; ++n) {
        const int u = std::min(w - 1, static_cast<int>((q[n].x() - q_min.x()) / pooling));
        const int v = std::min(h - 1, static_cast<int>((q[n].y() - q_min.y()) / pooling));
        index[n] = v * w + u;
      }
      for (std::size_t n = 0; n < count; ++n) pixels[index[n]] = 1.f;
    }
    return image;
  };
  const CoarseLayers b_layers = OpenSpaceAround(rasterize(walls), rasterize(free));
  // b's scored walls against a's score layer, minus a's walls on b's open space.
  cv::Mat1f penalised_open;
  b_layers.open.convertTo(penalised_open, CV_32F, -options_.free_penalty);
  return {{&scored_walls == &walls ? b_layers.walls : rasterize(scored_walls), penalised_open},
          q_min};
}

void CorrelationTranslation::ToTranslations(cv::Size b_pixels, const Eigen::Vector2d& anchor,
                                            std::vector<TranslationCandidate>& peaks) const {
  // b pixel u covers q - anchor in [p u, p u + p); shifted by d it meets a pixel u + d, which
  // covers a cells [p (u + d), ...): so q + t lies in a with t = p d - anchor. The surface's
  // element (row, col) is the shift (col - (w - 1), row - (h - 1)) from a's crop.
  for (auto& c : peaks) {
    const Eigen::Vector2d d(c.t_cells.x() - (b_pixels.width - 1) + a_offset_px_.x,
                            c.t_cells.y() - (b_pixels.height - 1) + a_offset_px_.y);
    c.t_cells = pooling_ * d - anchor;
  }
}

std::array<std::vector<TranslationCandidate>, 2> CorrelationTranslation::FindWithHalfTurn(
    const std::vector<Eigen::Vector2f>& scored_walls, const std::vector<Eigen::Vector2f>& walls,
    const std::vector<Eigen::Vector2f>& free, const PointBox* box) {
  if (scored_walls.empty() || walls.empty()) return {};
  const BLayers b =
      RasterizeB(scored_walls, walls, free, box ? *box : BoundingBox(scored_walls, walls, free));
  cv::Mat1f surface, surface_half_turn;
  correlator_.CorrelateSumAndHalfTurn(b.layers, &surface, &surface_half_turn);
  const int w = b.layers.front().cols, h = b.layers.front().rows;
  std::array<std::vector<TranslationCandidate>, 2> out = {
      SurfacePeaks(surface, options_.candidates),
      SurfacePeaks(surface_half_turn, options_.candidates)};
  ToTranslations(cv::Size(w, h), b.q_min.cast<double>(), out[0]);
  // The flipped image's pixel u' = w - 1 - u holds the turned points -q with q in b's pixel u:
  // -q lies in (A + p u', A + p u' + p] with A = -q_min - p (w, h), the flipped image's anchor.
  const Eigen::Vector2d anchor = -b.q_min.cast<double>() - pooling_ * Eigen::Vector2d(w, h);
  ToTranslations(cv::Size(w, h), anchor, out[1]);
  return out;
}

}  // namespace fleetmerge
