#include "sim/simulation_explore.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <string>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

constexpr int kDx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
constexpr int kDy[8] = {0, 0, 1, -1, 1, -1, 1, -1};

// Breadth-first search over the nonzero cells of `walkable` from `sources`: step counts (-1 where
// unreached) and, per cell, the flat index of the cell it was reached from (-1 for sources).
// `on_pop(index, distance)` sees cells in order of distance and returns false to stop.
template <typename OnPop>
void BreadthFirst(const cv::Mat1b& walkable, const std::vector<Eigen::Array2i>& sources,
                  std::vector<int>& distance, std::vector<int>& parent, OnPop&& on_pop) {
  const int w = walkable.cols, h = walkable.rows;
  distance.assign(static_cast<std::size_t>(w) * h, -1);
  parent.assign(distance.size(), -1);
  std::vector<int> queue;
  queue.reserve(distance.size() / 4);
  for (const auto& s : sources) {
    const int index = s.y() * w + s.x();
    if (distance[index] >= 0) continue;
    distance[index] = 0;
    queue.push_back(index);
  }
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const int index = queue[head];
    if (!on_pop(index, distance[index])) return;
    const int x = index % w, y = index / w;
    for (int n = 0; n < 8; ++n) {
      const int nx = x + kDx[n], ny = y + kDy[n];
      if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
      const int next = ny * w + nx;
      if (distance[next] >= 0 || walkable(ny, nx) == 0) continue;
      distance[next] = distance[index] + 1;
      parent[next] = index;
      queue.push_back(next);
    }
  }
}

std::vector<Eigen::Array2i> NonzeroCells(const cv::Mat1b& mask) {
  std::vector<cv::Point> points;
  cv::findNonZero(mask, points);
  std::vector<Eigen::Array2i> cells;
  cells.reserve(points.size());
  for (const auto& p : points) cells.emplace_back(p.x, p.y);
  return cells;
}

}  // namespace

cv::Mat1b TraversableCells(const OccupancyGrid& building, double clearance_m) {
  // A one-cell non-free border makes the grid's edge count as an obstacle.
  cv::Mat1b free_cells;
  cv::copyMakeBorder(building.cells() == static_cast<std::uint8_t>(CellState::kFree), free_cells, 1,
                     1, 1, 1, cv::BORDER_CONSTANT, 0);
  cv::Mat1f distance_cells;
  cv::distanceTransform(free_cells, distance_cells, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  const double r = building.geometry().resolution_m();
  cv::Mat1b clear =
      distance_cells(cv::Rect(1, 1, building.width(), building.height())) * static_cast<float>(r) >
      static_cast<float>(clearance_m);
  cv::Mat1i labels;
  cv::Mat stats, centroids;
  const int n = cv::connectedComponentsWithStats(clear, labels, stats, centroids, 8, CV_32S);
  int largest = 0;
  for (int label = 1; label < n; ++label) {
    if (largest == 0 ||
        stats.at<int>(label, cv::CC_STAT_AREA) > stats.at<int>(largest, cv::CC_STAT_AREA)) {
      largest = label;
    }
  }
  if (largest == 0) return cv::Mat1b::zeros(building.height(), building.width());
  return labels == largest;
}

std::vector<Eigen::Array2i> ChooseStarts(const cv::Mat1b& traversable, int count, bool spread_out,
                                         PortableRng& rng) {
  const std::vector<Eigen::Array2i> cells = NonzeroCells(traversable);
  if (static_cast<int>(cells.size()) < std::max(count, 1)) {
    throw Error("simulation: the building has " + std::to_string(cells.size()) +
                " free cells with the robots' clearance, too few for " + std::to_string(count) +
                " robots (lower the clearance or use another map)");
  }
  std::vector<Eigen::Array2i> starts;
  while (static_cast<int>(starts.size()) < count) {
    if (!spread_out || starts.empty()) {
      const Eigen::Array2i cell = cells[rng.UniformInt(0, static_cast<int>(cells.size()) - 1)];
      const bool taken = std::any_of(starts.begin(), starts.end(),
                                     [&](const Eigen::Array2i& s) { return (s == cell).all(); });
      if (!taken) starts.push_back(cell);
      continue;
    }
    // Straight-line distance to the nearest start so far (0 at the starts), over the grid.
    cv::Mat1b not_start(traversable.size(), 255);
    for (const auto& s : starts) not_start(s.y(), s.x()) = 0;
    cv::Mat1f distance_to_starts;
    cv::distanceTransform(not_start, distance_to_starts, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    cv::Point farthest;
    cv::minMaxLoc(distance_to_starts, nullptr, nullptr, nullptr, &farthest, traversable);
    starts.emplace_back(farthest.x, farthest.y);
  }
  return starts;
}

cv::Mat1i Territories(const cv::Mat1b& traversable, const std::vector<Eigen::Array2i>& starts) {
  cv::Mat1i label(traversable.rows, traversable.cols, -1);
  for (std::size_t k = 0; k < starts.size(); ++k) label(starts[k].y(), starts[k].x()) = int(k);
  // Cells come out in breadth-first order, so a cell's parent is labelled before it.
  std::vector<int> distance, parent;
  int* labels = label.ptr<int>(0);
  BreadthFirst(traversable, starts, distance, parent, [&](int index, int) {
    if (parent[index] >= 0) labels[index] = labels[parent[index]];
    return true;
  });
  return label;
}

std::vector<Eigen::Array2i> PathToNextGoal(const cv::Mat1b& walkable, const cv::Mat1b& seen,
                                           const Eigen::Array2i& from, int spread_cells,
                                           PortableRng& rng) {
  std::vector<int> distance, parent, candidates;
  int nearest = -1;
  BreadthFirst(walkable, {from}, distance, parent, [&](int index, int d) {
    if (nearest >= 0 && d > nearest + spread_cells) return false;
    if (d > 0 && seen(index / walkable.cols, index % walkable.cols) == 0) {
      if (nearest < 0) nearest = d;
      candidates.push_back(index);
    }
    return true;
  });
  if (candidates.empty()) return {};
  int index = candidates[rng.UniformInt(0, static_cast<int>(candidates.size()) - 1)];
  std::vector<Eigen::Array2i> path;
  for (; parent[index] >= 0; index = parent[index]) {
    path.emplace_back(index % walkable.cols, index / walkable.cols);
  }
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace fleetmerge
