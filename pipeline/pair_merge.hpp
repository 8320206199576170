// The two-map job behind `fleetmerge pair`: Carpin's hypotheses (core/), each refined locally
// with Ceres (refine/), re-scored by omega (Eq. 1) and re-ranked, as poses of b's map frame in a's
// map frame in metres and radians.
#pragma once

#include <vector>

#include "core/hypothesis_generator.hpp"
#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "core/pose_evidence.hpp"
#include "job/pair_options.hpp"
#include "pipeline/prepared_map.hpp"

namespace fleetmerge {

struct PairHypothesis {
  Pose2 T_a_b;  // pose of b's map frame in a's map frame (metres, radians)
  double omega = 0.0;
  std::int64_t overlap_cells = 0;  // cells known in both maps (agr + dis of Eq. 1)
  double wall_agreement = 0.0;     // core/wall_agreement.hpp
  double evidence_nats = 0.0;      // core/pose_evidence.hpp
};

struct PairResult {
  std::vector<PairHypothesis> hypotheses;  // best first (core/pose_evidence.hpp)
  double margin_nats = 0.0;   // evidence of the best minus the runner-up's; +inf without one
  bool ambiguous = false;     // the runner-up, a different pose, is as good: a coin toss
  double resolution_m = 0.0;  // the resolution the maps were compared at
  bool resampled = false;     // one map was resampled to the other's (finer) cells
};

// Maps of different resolutions are compared at the finer one (the coarser map is resampled;
// its map frame is unchanged, so the poses stay valid for the original files).
// `threads` (<= 0: all cores) share the work of this one pair: the two maps' preparation, the
// rotation candidates' searches and the candidates' refinements. The hypotheses are the same
// for any count. A fleet runs its pairs in parallel instead (pipeline/all_pairs.hpp).
PairResult MergePair(const OccupancyGrid& a, const OccupancyGrid& b, const PairOptions& options,
                     int threads = 1);

// A hypothesis of cell-unit pose as a map-frame one.
PairHypothesis ToPairHypothesis(const OccupancyGrid& a, const OccupancyGrid& b,
                                const CellHypothesis& h);

// The hypotheses of two maps that already share a resolution, best first, in cell units.
RankedHypotheses RankedCellHypotheses(const OccupancyGrid& a, const OccupancyGrid& b,
                                      const PairOptions& options, int threads = 1);
// The same on maps prepared once (pipeline/prepared_map.hpp) with the same options: what a fleet
// uses, so that each map's own work is shared by all its pairs.
RankedHypotheses RankedCellHypotheses(const PreparedMap& a, const PreparedMap& b,
                                      const PairOptions& options, int threads = 1);

}  // namespace fleetmerge
