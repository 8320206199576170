// Wall agreement of two maps under a candidate pose: of b's occupied cells that land on cells
// a knows (free or occupied), the share within one cell of an occupied cell of a.
//
// Why beside omega (Eq. 1): omega counts free cells too, and free space dominates a map, so a
// wrong alignment of one building's parts, or of two buildings, still scores 0.90-0.965 when
// free regions happen to overlap. Walls landing on walls is far more selective: measured on cut
// real maps, 0.98-1.00 for correct alignments and 0.06-0.63 for wrong ones (docs/method.md).
#pragma once

#include <Eigen/Core>
#include <array>
#include <opencv2/core.hpp>
#include <vector>

#include "core/acceptance_index.hpp"
#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"

namespace fleetmerge {

// Fewer walls of b on a's known cells than this cannot judge a pose: a sliver of overlap
// holding one or two wall cells would score 1.0 (seen on simulated fleets once the translation
// search found such slivers, with omega 1.0 too).
constexpr long kMinWallsJudged = 30;

// T_ga_gb in cell units (as CountAgreement). Returns 0 when fewer than kMinWallsJudged walls of b
// land on a's known cells.
double WallAgreement(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb);

// 255 where a cell is within one cell (8-neighbourhood) of an occupied cell of `grid`: the
// tolerance of WallAgreement (resampling a re-framed map moves walls by up to a cell).
cv::Mat1b NearWallMask(const OccupancyGrid& grid);

// WallAgreement with a's NearWallMask computed beforehand (once per map in a fleet).
double WallAgreement(const OccupancyGrid& a, const cv::Mat1b& a_near_walls, const OccupancyGrid& b,
                     const Pose2& T_ga_gb);

// b's walls that land on a's known cells, and of those the ones near a's walls.
struct WallCount {
  long on_known = 0;
  long near_wall = 0;
  // The agreement: 0 when fewer than kMinWallsJudged walls are judged.
  double share() const {
    return on_known < kMinWallsJudged ? 0.0 : double(near_wall) / double(on_known);
  }
};
WallCount CountWalls(const OccupancyGrid& a, const cv::Mat1b& a_near_walls,
                     const std::vector<Eigen::Vector2f>& b_wall_centres, const Pose2& T_ga_gb);

// CountWalls at T_ga_gb and at T_ga_gb translated along a's axes by each of shifts_cells, in one
// pass over b's walls: element 0 is CountWalls(..., T_ga_gb), element k >= 1 is CountWalls(...,
// Pose2(shifts_cells[k - 1], 0) * T_ga_gb), the same counts (each wall is rotated once, and
// each pose's translation added as Pose2's composition computes it).
std::array<WallCount, 5> CountWallsAndShifted(const OccupancyGrid& a, const cv::Mat1b& a_near_walls,
                                              const std::vector<Eigen::Vector2f>& b_wall_centres,
                                              const Pose2& T_ga_gb,
                                              const std::array<Eigen::Vector2d, 4>& shifts_cells);

// WallAgreement with b given by its occupied cell centres (OccupiedCellCenters(b), any order):
// the same count without scanning all of b's cells for its few walls on every call.
double WallAgreement(const OccupancyGrid& a, const cv::Mat1b& a_near_walls,
                     const std::vector<Eigen::Vector2f>& b_wall_centres, const Pose2& T_ga_gb);

// min(WallAgreement(a, b, T), WallAgreement(b, a, T^-1)): both maps' walls must agree.
double SymmetricWallAgreement(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb);

// One map's side of the wall agreement, computed once per map where it is judged in many pairs,
// with its known cells' row spans: the overlap counted before the walls are judged
// (CountAgreement's fast path, the same counts).
struct MapWalls {
  explicit MapWalls(const OccupancyGrid& grid);  // keeps a reference to `grid`
  // From parts already made for `grid` (core/map_features.hpp computes the same three).
  MapWalls(const OccupancyGrid& grid, std::vector<Eigen::Vector2f> centres, cv::Mat1b near_walls,
           RowSpans known_spans);
  const OccupancyGrid& grid;
  std::vector<Eigen::Vector2f> centres;  // OccupiedCellCenters(grid)
  cv::Mat1b near_walls;                  // NearWallMask(grid)
  RowSpans known_spans;                  // KnownRowSpans(grid)
};

// SymmetricWallAgreement of two maps' precomputed walls: the same value.
double SymmetricWallAgreement(const MapWalls& a, const MapWalls& b, const Pose2& T_ga_gb);

}  // namespace fleetmerge
