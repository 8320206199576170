// Algorithm 1 (ComputeHypothesis): ranked rigid transformations that overlay map b on map a.
//
//   1. Hough spectra HS_a, HS_b of the occupied cells (Section III-A), optionally sampled (III-D).
//   2. Circular cross-correlation C of the spectra; its n largest local maxima psi_1..psi_n; each
//      also gives psi_i + pi (the spectrum's period is pi, so the two are indistinguishable).
//   3. For every rotation: rotate b's occupied cells, find translation candidates (X/Y spectra
//      as in the paper, or 2-D correlation), and score each with omega (Eq. 1).
//   4. Drop near-duplicates and return the best, highest omega first.
// All poses here are T_ga_gb: b's grid frame in a's grid frame, in CELL units.
#pragma once

#include <cstdint>
#include <vector>

#include "core/hough_spectrum.hpp"
#include "core/occupancy_grid.hpp"
#include "core/point_sampling.hpp"
#include "core/pose2.hpp"
#include "core/translation_search.hpp"

namespace fleetmerge {

struct HypothesisOptions {
  HoughOptions hough;
  SamplingOptions hough_sampling;  // points used for the Hough transform (Section III-D)
  // Points used for the X/Y spectra (Section III-D). Seed 1: every front end seeds the Hough
  // transform with its seed and the spectra with seed + 1, and their default seed is 0.
  SamplingOptions spectra_sampling{SamplingMode::kAll, 1.0, 1, 1};
  int rotation_peaks = 4;  // the paper's n: local maxima of C taken
  TranslationOptions translation;
  int max_hypotheses = 4;  // returned, best first
  // Candidates closer than this are one hypothesis (the better omega is kept).
  double duplicate_yaw_rad = 2.0 * M_PI / 180.0;
  double duplicate_translation_cells = 3.0;
  // A hypothesis whose overlap (cells known in both maps) is below this ranks below every one
  // that reaches it. Omega (Eq. 1) only counts the overlap, so a transform that barely touches
  // the other map scores ~1 however wrong it is; seen on simulated robots whose maps overlap by
  // 90000 cells, where such slivers outranked the true pose.
  std::int64_t min_overlap_cells = 2000;
};

struct CellHypothesis {
  Pose2 T_ga_gb;  // cell units
  double omega = 0.0;
  std::int64_t overlap_cells = 0;  // agr + dis of Eq. (1): cells known in both maps under T
  double wall_agreement = 0.0;     // core/wall_agreement.hpp; set by RankByEvidence
  double evidence_nats = 0.0;      // core/pose_evidence.hpp; set by RankByEvidence (NaN
                                   // where it ranks nothing)
};

// Best first: hypotheses reaching `min_overlap_cells` before the others, then by omega (stable).
void SortHypotheses(std::vector<CellHypothesis>& hypotheses, std::int64_t min_overlap_cells);

// Throws fleetmerge::Error if the grids' resolutions differ (resample first). Returns an empty
// list when either map has no occupied cell.
std::vector<CellHypothesis> GenerateHypotheses(const OccupancyGrid& a, const OccupancyGrid& b,
                                               const HypothesisOptions& options);

// Drops hypotheses within the duplicate tolerances of a better one; keeps order (best first).
std::vector<CellHypothesis> RemoveDuplicates(std::vector<CellHypothesis> sorted,
                                             const HypothesisOptions& options);

// T_a_b in metres from T_ga_gb in cells: T_a_b = T_a_ga * scale(T_ga_gb) * T_gb_b.
Pose2 MapPoseFromCellPose(const GridGeometry& a, const GridGeometry& b, const Pose2& T_ga_gb);
Pose2 CellPoseFromMapPose(const GridGeometry& a, const GridGeometry& b, const Pose2& T_a_b);

}  // namespace fleetmerge
