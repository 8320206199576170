// The parameters of one pair's search (pipeline/pair_merge.hpp): Carpin's hypotheses (core/) and
// their local refinement (refine/). Part of every job (job/fleet_options.hpp), read from job files
// by io/job_file.hpp, so it lives below both io/ and pipeline/.
#pragma once

#include "core/hypothesis_generator.hpp"
#include "refine/local_alignment.hpp"

namespace fleetmerge {

struct PairOptions {
  HypothesisOptions hypotheses;
  bool refine = true;
  double refine_truncation_cells = 6.0;  // basin of the local alignment, in its grid's cells
  // The quick stage runs on grids coarse enough that its basin bridges the translation search's
  // error: this many of that search's pooled pixels (CorrelationPooling).
  double quick_basin_pixels = 1.5;
  // Candidates refined per hypothesis returned: a near miss can rank below a wrong hypothesis
  // before refinement and above all of them after.
  int candidates_per_hypothesis = 2;
  // Every candidate is refined cheaply (few wall points); the best few again with more, where a
  // wall half a cell off is already an outlier (Cauchy scale 0.5 cells; with 1.0 and the coarser
  // translation search below, the held-out set lost 2 fine pairs).
  // The final stage converges ten times tighter than Ceres' default 1e-6, where TinySolver's
  // steps stopped ~0.007 cells short of the minimum against 0.002 (local_alignment_test) and one
  // pair of the seeds 51-68 set crossed the 3-cell line; it refines one candidate per pair.
  LocalAlignmentOptions quick_refine{300, 15, 1.0, 1e-6};
  LocalAlignmentOptions final_refine{1500, 25, 0.5, 1e-7};
  int final_refine_count = 1;
};

}  // namespace fleetmerge
