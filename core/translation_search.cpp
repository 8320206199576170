#include "core/translation_search.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace fleetmerge {
namespace {

int PoolingFor(const OccupancyGrid& a, double b_extent_cells, int coarse_max_side) {
  const double side = std::max({double(a.width()), double(a.height()), b_extent_cells});
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
  cv::Mat1f near_walls;
  cv::dilate(walls, near_walls, cv::Mat());
  free.setTo(0.f, near_walls > 0.f);
  return {walls, free};
}

CoarseLayers CoarseGridLayers(const OccupancyGrid& a, int pooling) {
  const int w = (a.width() + pooling - 1) / pooling, h = (a.height() + pooling - 1) / pooling;
  cv::Mat1f walls = cv::Mat1f::zeros(h, w), free = cv::Mat1f::zeros(h, w);
  for (int j = 0; j < a.height(); ++j) {
    const std::uint8_t* row = a.cells().ptr<std::uint8_t>(j);
    for (int i = 0; i < a.width(); ++i) {
      if (row[i] == std::uint8_t(CellState::kOccupied)) walls(j / pooling, i / pooling) = 1.f;
      if (row[i] == std::uint8_t(CellState::kFree)) free(j / pooling, i / pooling) = 1.f;
    }
  }
  return OpenSpaceAround(walls, free);
}

// The fixed layers of a: the score of a pixel for a wall of b, and a's walls.
std::vector<cv::Mat1f> FixedLayers(const OccupancyGrid& a, int pooling, double free_penalty) {
  const CoarseLayers layers = CoarseGridLayers(a, pooling);
  cv::Mat1f wall_score;
  // The blur widens the peak so a rotation off by a fraction of a degree still correlates.
  cv::GaussianBlur(layers.walls, wall_score, cv::Size(5, 5), 1.0);
  return {wall_score - free_penalty * layers.open, layers.walls};
}

// Local maxima of a 2-D surface (5x5 neighbourhood), largest first, with sub-pixel parabolas.
std::vector<TranslationCandidate> SurfacePeaks(const cv::Mat1f& surface, int count) {
  cv::Mat1f dilated;
  cv::dilate(surface, dilated, cv::Mat(), cv::Point(-1, -1), 2);
  std::vector<TranslationCandidate> peaks;
  for (int r = 1; r + 1 < surface.rows; ++r) {
    for (int c = 1; c + 1 < surface.cols; ++c) {
      const float v = surface(r, c);
      if (v <= 0.f || v < dilated(r, c)) continue;
      const auto vertex = [](float m, float z, float p) {
        const float curvature = m - 2.f * z + p;
        return curvature < 0.f ? 0.5f * (m - p) / curvature : 0.f;
      };
      const double dx = c + vertex(surface(r, c - 1), v, surface(r, c + 1));
      const double dy = r + vertex(surface(r - 1, c), v, surface(r + 1, c));
      peaks.push_back({Eigen::Vector2d(dx, dy), v});
    }
  }
  std::sort(peaks.begin(), peaks.end(),
            [](const auto& l, const auto& r) { return l.score > r.score; });
  if (static_cast<int>(peaks.size()) > count) peaks.resize(count);
  return peaks;
}

}  // namespace

int CorrelationPooling(const OccupancyGrid& a, const OccupancyGrid& b,
                       const TranslationOptions& options) {
  return PoolingFor(a, std::hypot(double(b.width()), double(b.height())), options.coarse_max_side);
}

CorrelationTranslation::CorrelationTranslation(const OccupancyGrid& a, double b_extent_cells,
                                               const TranslationOptions& options)
    : options_(options),
      pooling_(PoolingFor(a, b_extent_cells, options.coarse_max_side)),
      max_b_size_(static_cast<int>(std::ceil(b_extent_cells / pooling_)) + 2,
                  static_cast<int>(std::ceil(b_extent_cells / pooling_)) + 2),
      correlator_(FixedLayers(a, pooling_, options.free_penalty), max_b_size_) {}

std::vector<TranslationCandidate> CorrelationTranslation::Find(
    const std::vector<Eigen::Vector2f>& scored_walls, const std::vector<Eigen::Vector2f>& walls,
    const std::vector<Eigen::Vector2f>& free) {
  if (scored_walls.empty() || walls.empty()) return {};
  Eigen::Vector2f q_min = walls.front(), q_max = walls.front();
  for (const auto* points : {&scored_walls, &walls, &free}) {
    for (const auto& q : *points) {
      q_min = q_min.cwiseMin(q);
      q_max = q_max.cwiseMax(q);
    }
  }
  const int w = std::min(max_b_size_.width, int((q_max.x() - q_min.x()) / pooling_) + 1);
  const int h = std::min(max_b_size_.height, int((q_max.y() - q_min.y()) / pooling_) + 1);
  const auto rasterize = [&](const std::vector<Eigen::Vector2f>& points) {
    cv::Mat1f image = cv::Mat1f::zeros(h, w);
    for (const auto& q : points) {
      const int u = std::min(w - 1, int((q.x() - q_min.x()) / pooling_));
      const int v = std::min(h - 1, int((q.y() - q_min.y()) / pooling_));
      image(v, u) = 1.f;
    }
    return image;
  };
  const CoarseLayers b_layers = OpenSpaceAround(rasterize(walls), rasterize(free));
  // b's scored walls against a's score layer, minus a's walls on b's open space.
  const cv::Mat1f surface = correlator_.CorrelateSum(
      {rasterize(scored_walls), static_cast<cv::Mat1f>(-options_.free_penalty * b_layers.open)});
  // b pixel u covers q - q_min in [p u, p u + p); shifted by d it meets a pixel u + d, which
  // covers a cells [p (u + d), ...): so q + t lies in a with t = p d - q_min.
  std::vector<TranslationCandidate> out = SurfacePeaks(surface, options_.candidates);
  for (auto& c : out) {
    const Eigen::Vector2d d(c.t_cells.x() - (w - 1), c.t_cells.y() - (h - 1));
    c.t_cells = pooling_ * d - q_min.cast<double>();
  }
  return out;
}

}  // namespace fleetmerge
