#include "core/wall_agreement.hpp"

#include <algorithm>
#include <utility>

#include "core/image_filters.hpp"
#include "core/image_masks.hpp"
#include "core/point_sampling.hpp"  // OccupiedCellCenters

namespace fleetmerge {

cv::Mat1b NearWallMask(const OccupancyGrid& grid) {
  return MaxFilter<1, 1>(
      CompareMask(grid.cells(), cv::CMP_EQ, static_cast<int>(CellState::kOccupied)));
}

double WallAgreement(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb) {
  return WallAgreement(a, NearWallMask(a), b, T_ga_gb);
}

namespace {

// Counts b's walls (cell centres p_b, in b's grid frame) that land on a's known cells, and of
// those the ones near a's walls, under K poses that share the rotation R and have the
// translations t[k]: p = t[k] + R p_b.
template <std::size_t K, typename ForEachWall>
std::array<WallCount, K> CountWallsOnWalls(const OccupancyGrid& a, const cv::Mat1b& near_wall,
                                           const Eigen::Matrix2d& R,
                                           const std::array<Eigen::Vector2d, K>& t,
                                           const ForEachWall& for_each_wall) {
  const auto unknown = static_cast<std::uint8_t>(CellState::kUnknown);
  const CellOfPoint cell_in_a(a);
  std::array<WallCount, K> count{};
  for_each_wall([&](const Eigen::Vector2d& p_b) {
    const Eigen::Vector2d R_p_b = R * p_b;
    for (std::size_t k = 0; k < K; ++k) {
      int ia = 0, ja = 0;
      if (!cell_in_a(t[k] + R_p_b, &ia, &ja)) continue;
      if (a.cells()(ja, ia) == unknown) continue;
      ++count[k].on_known;
      count[k].near_wall += near_wall(ja, ia) != 0;
    }
  });
  return count;
}

// One pose. Pose2 * point takes a sine and a cosine each time: once here, not once per wall cell
// (they were a fifth of a pair's time). The same arithmetic as Pose2's, so the same cells.
template <typename ForEachWall>
WallCount CountWallsOnWalls(const OccupancyGrid& a, const cv::Mat1b& near_wall,
                            const Pose2& T_ga_gb, const ForEachWall& for_each_wall) {
  return CountWallsOnWalls<1>(a, near_wall, T_ga_gb.rotation(), {T_ga_gb.translation_m()},
                              for_each_wall)[0];
}

}  // namespace

double WallAgreement(const OccupancyGrid& a, const cv::Mat1b& near_wall, const OccupancyGrid& b,
                     const Pose2& T_ga_gb) {
  const auto occupied = static_cast<std::uint8_t>(CellState::kOccupied);
  return CountWallsOnWalls(a, near_wall, T_ga_gb,
                           [&](const auto& visit) {
                             for (int j = 0; j < b.height(); ++j) {
                               const std::uint8_t* row = b.cells().ptr<std::uint8_t>(j);
                               for (int i = 0; i < b.width(); ++i) {
                                 if (row[i] == occupied) visit(Eigen::Vector2d(i + 0.5, j + 0.5));
                               }
                             }
                           })
      .share();
}

WallCount CountWalls(const OccupancyGrid& a, const cv::Mat1b& near_wall,
                     const std::vector<Eigen::Vector2f>& b_wall_centres, const Pose2& T_ga_gb) {
  // Centres i + 0.5 are exact in float (cells < 2^23), so the cast gives WallAgreement's points.
  return CountWallsOnWalls(a, near_wall, T_ga_gb, [&](const auto& visit) {
    for (const Eigen::Vector2f& c : b_wall_centres) visit(c.cast<double>());
  });
}

std::array<WallCount, 5> CountWallsAndShifted(const OccupancyGrid& a, const cv::Mat1b& near_wall,
                                              const std::vector<Eigen::Vector2f>& b_wall_centres,
                                              const Pose2& T_ga_gb,
                                              const std::array<Eigen::Vector2d, 4>& shifts_cells) {
  // Pose2(shift, 0) * T has T's yaw and the translation shift + I t, which is shift + t exactly
  // (the identity's products are t's coordinates and signed zeros).
  std::array<Eigen::Vector2d, 5> t;
  t[0] = T_ga_gb.translation_m();
  for (std::size_t k = 0; k < shifts_cells.size(); ++k) {
    t[k + 1] = (Pose2(shifts_cells[k], 0.0) * T_ga_gb).translation_m();
  }
  return CountWallsOnWalls<5>(a, near_wall, T_ga_gb.rotation(), t, [&](const auto& visit) {
    for (const Eigen::Vector2f& c : b_wall_centres) visit(c.cast<double>());
  });
}

double WallAgreement(const OccupancyGrid& a, const cv::Mat1b& near_wall,
                     const std::vector<Eigen::Vector2f>& b_wall_centres, const Pose2& T_ga_gb) {
  return CountWalls(a, near_wall, b_wall_centres, T_ga_gb).share();
}

double SymmetricWallAgreement(const OccupancyGrid& a, const OccupancyGrid& b,
                              const Pose2& T_ga_gb) {
  return std::min(WallAgreement(a, b, T_ga_gb), WallAgreement(b, a, T_ga_gb.inverse()));
}

MapWalls::MapWalls(const OccupancyGrid& grid)
    : grid(grid),
      centres(OccupiedCellCenters(grid)),
      near_walls(NearWallMask(grid)),
      known_spans(KnownRowSpans(grid)) {}

MapWalls::MapWalls(const OccupancyGrid& grid, std::vector<Eigen::Vector2f> centres,
                   cv::Mat1b near_walls, RowSpans known_spans)
    : grid(grid),
      centres(std::move(centres)),
      near_walls(std::move(near_walls)),
      known_spans(std::move(known_spans)) {}

double SymmetricWallAgreement(const MapWalls& a, const MapWalls& b, const Pose2& T_ga_gb) {
  return std::min(WallAgreement(a.grid, a.near_walls, b.centres, T_ga_gb),
                  WallAgreement(b.grid, b.near_walls, a.centres, T_ga_gb.inverse()));
}

}  // namespace fleetmerge
