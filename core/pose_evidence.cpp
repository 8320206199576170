#include "core/pose_evidence.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/parallel.hpp"
#include "core/wall_agreement.hpp"

namespace fleetmerge {
namespace {

// What a right pose gives: omega 0.97-0.99 and wall agreement 0.83-1.00 on real maps
// (docs/method.md). The upper ends, so that disagreement weighs: a wrong translation in a
// repetitive building lands many walls on walls but far more off them than a right one.
constexpr double kRightCellAgreement = 0.99;
constexpr double kRightWallAgreement = 0.98;
// Cells of a 3 x 3 neighbourhood: one roughly independent observation.
constexpr double kCellsPerObservation = 9.0;
// The chance poses for walls: the hypothesis this many cells off along each axis of the grid
// the walls land on.
constexpr double kChanceShiftCells = 4.0;
const std::array<Eigen::Vector2d, 4> kChanceShifts = {
    Eigen::Vector2d(kChanceShiftCells, 0.0), Eigen::Vector2d(-kChanceShiftCells, 0.0),
    Eigen::Vector2d(0.0, kChanceShiftCells), Eigen::Vector2d(0.0, -kChanceShiftCells)};

// The share of `from`'s walls near `onto`'s walls at the chance poses (elements 1-4 of
// CountWallsAndShifted(onto, ..., from, T_onto_from, kChanceShifts)). The rotation search has
// already aligned the walls' directions, so walls meet walls far more often than the map's
// near-wall share says (along a corridor, always); a wrong translation in a repetitive building
// then scores walls on walls "by chance" at this rate, not at that share. Falls back to the share
// when no shifted pose lands a wall on a known cell.
double ChanceWallRate(const std::array<WallCount, 5>& counts, double onto_near_wall_share) {
  long near = 0, judged = 0;
  for (std::size_t k = 1; k < counts.size(); ++k) {
    near += counts[k].near_wall;
    judged += counts[k].on_known;
  }
  return judged < kMinWallsJudged ? onto_near_wall_share : double(near) / double(judged);
}

// ln-likelihood ratio of `hits` successes in `trials` under rate q against chance rate p. The
// chance rate is kept off 0 and 1 (a map of walls only, or of free space only) and below q, so
// that agreement is never evidence against the pose.
double LogRatio(double hits, double trials, double q, double p) {
  p = std::clamp(p, 0.01, q - 0.01);
  return hits * std::log(q / p) + (trials - hits) * std::log((1.0 - q) / (1.0 - p));
}

// The walls of each map on the other's known cells under h (sets h.wall_agreement); with
// `chance`, also under the chance poses (elements 1-4).
struct WallCounts {
  std::array<WallCount, 5> b_on_a, a_on_b;
};
WallCounts CountBothWays(const MapFeatures& a, const MapFeatures& b, CellHypothesis& h,
                         bool chance) {
  WallCounts c{};
  const Pose2 T_gb_ga = h.T_ga_gb.inverse();
  if (chance) {
    c.b_on_a =
        CountWallsAndShifted(a.grid, a.walls.near_walls, b.walls.centres, h.T_ga_gb, kChanceShifts);
    c.a_on_b =
        CountWallsAndShifted(b.grid, b.walls.near_walls, a.walls.centres, T_gb_ga, kChanceShifts);
  } else {
    c.b_on_a[0] = CountWalls(a.grid, a.walls.near_walls, b.walls.centres, h.T_ga_gb);
    c.a_on_b[0] = CountWalls(b.grid, b.walls.near_walls, a.walls.centres, T_gb_ga);
  }
  // SymmetricWallAgreement
  h.wall_agreement = std::min(c.b_on_a[0].share(), c.a_on_b[0].share());
  return c;
}

// `walls` with the chance poses' counts.
double Evidence(const MapFeatures& a, const MapFeatures& b, const CellHypothesis& h,
                const WallCounts& walls) {
  const double o_a = a.occupied_share, o_b = b.occupied_share;
  const double chance_cell_agreement = o_a * o_b + (1.0 - o_a) * (1.0 - o_b);
  const double overlap = static_cast<double>(h.overlap_cells);
  const double nats =
      LogRatio(h.omega * overlap, overlap, kRightCellAgreement, chance_cell_agreement) +
      LogRatio(walls.b_on_a[0].near_wall, walls.b_on_a[0].on_known, kRightWallAgreement,
               ChanceWallRate(walls.b_on_a, a.near_wall_share)) +
      LogRatio(walls.a_on_b[0].near_wall, walls.a_on_b[0].on_known, kRightWallAgreement,
               ChanceWallRate(walls.a_on_b, b.near_wall_share));
  return nats / kCellsPerObservation;
}

}  // namespace

double MeasureEvidence(const MapFeatures& a, const MapFeatures& b, CellHypothesis& h) {
  return Evidence(a, b, h, CountBothWays(a, b, h, /*chance=*/true));
}

RankedHypotheses RankByEvidence(const MapFeatures& a, const MapFeatures& b,
                                std::vector<CellHypothesis> sorted, std::int64_t min_overlap_cells,
                                int threads) {
  RankedHypotheses ranked;
  ranked.margin_nats = std::numeric_limits<double>::infinity();
  if (sorted.empty()) return ranked;
  // The tie: hypotheses with enough overlap within kOmegaTie of the best (SortHypotheses puts
  // those with enough overlap first, highest omega first).
  const double best_omega = sorted.front().omega;
  const auto tied_end = std::find_if(sorted.begin(), sorted.end(), [&](const CellHypothesis& h) {
    return h.overlap_cells < min_overlap_cells || h.omega < best_omega - kOmegaTie;
  });
  // Evidence decides the order of the tie and the margin to the runner-up, which is the second
  // of the tie or else the second hypothesis: only those are measured (the chance rates cost
  // four wall counts each way); every hypothesis gets its wall agreement.
  const std::size_t measured = std::max<std::size_t>(tied_end - sorted.begin(), 2);
  ParallelFor(sorted.size(), threads, [&](std::size_t k) {
    const bool measure = k < measured;
    const WallCounts walls = CountBothWays(a, b, sorted[k], /*chance=*/measure);
    sorted[k].evidence_nats =
        measure ? Evidence(a, b, sorted[k], walls) : std::numeric_limits<double>::quiet_NaN();
  });
  std::stable_sort(sorted.begin(), tied_end, [](const CellHypothesis& l, const CellHypothesis& r) {
    return l.evidence_nats > r.evidence_nats;
  });
  if (sorted.size() >= 2) {
    ranked.margin_nats = sorted[0].evidence_nats - sorted[1].evidence_nats;
    ranked.ambiguous = tied_end - sorted.begin() >= 2 && ranked.margin_nats < kAmbiguousMarginNats;
  }
  ranked.hypotheses = std::move(sorted);
  return ranked;
}

}  // namespace fleetmerge
