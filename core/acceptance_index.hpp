// The acceptance index omega (Eq. 1) of two maps under a candidate transformation.
//
//   agr = #cells where both maps are free or both occupied
//   dis = #cells where one map is free and the other occupied
//   omega = agr / (agr + dis)  if agr != 0, else 0                          (Eq. 1)
// Unknown cells count for neither. omega(M, M) = 1.
//
// Instead of materialising T M_b (a rotated copy of the whole map) we walk b's known cells and
// look each one up in a: a rigid map of a regular grid is affine, so the position in a advances
// by a constant step along each row of b and costs two additions per cell.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"

namespace fleetmerge {

struct Agreement {
  std::int64_t agree = 0;
  std::int64_t disagree = 0;
  double omega() const {
    return agree == 0 ? 0.0 : double(agree) / double(agree + disagree);  // Eq. (1)
  }
};

// Per row of a grid, its runs of consecutive known cells, each a half-open column range
// [first, last + 1). Maps re-framed by a rotation are mostly unknown around a tilted footprint,
// and inside it a robot's map knows only the corridors and rooms it saw (27-46 % of each row's
// extent in the simulated ACES fleet): walking only the runs makes omega several times cheaper.
// Computed once per map.
struct RowSpans {
  std::vector<int> row_begin;             // row j's runs: runs[row_begin[j] .. row_begin[j + 1])
  std::vector<std::pair<int, int>> runs;  // rows bottom to top, each row's runs left to right
};
RowSpans KnownRowSpans(const OccupancyGrid& grid);

// Counts agreement of `a` with `b` placed by T_ga_gb, the pose of b's grid frame in a's grid
// frame in CELL units (both grids must share one resolution). Each b cell is compared with the
// a cell containing its centre. `stride` > 1 visits every stride-th row and column of b (a
// cheap estimate for ranking many candidates).
// `b_spans` (KnownRowSpans(b)) may be given to skip b's unknown margins.
Agreement CountAgreement(const OccupancyGrid& a, const OccupancyGrid& b, const Pose2& T_ga_gb,
                         int stride = 1, const RowSpans* b_spans = nullptr);

// The centre (mean) of b's known cells that land on a's known cells under T_ga_gb (as
// CountAgreement), in b's GRID frame in cell units; nullopt when none does. Visits every
// stride-th row and column of b.
std::optional<Eigen::Vector2d> OverlapCentre(const OccupancyGrid& a, const OccupancyGrid& b,
                                             const Pose2& T_ga_gb, int stride = 1);

}  // namespace fleetmerge
