// Scoring a fleet merge against the ground truth (`fleetmerge eval`, /work contract
// "eval semantics"): for every pair of maps that truly overlap, directly or through other maps
// of their building, whether the merge put them in one component and how far their relative
// pose is from the truth; maps of different buildings put together (false merges); maps left
// out of every component with the maps they overlap (missed).
#pragma once

#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "io/report_file.hpp"
#include "io/truth_file.hpp"

namespace fleetmerge {

struct EvalOptions {
  // Pairs of one building observing at least this many common cells are overlap edges; maps
  // connected through them truly overlap (merge's min_overlap_cells default).
  long long min_overlap_cells = 2000;
  // Success tolerances: yaw error and mean displacement of the second map's occupied cells.
  double coarse_yaw_deg = 1.0, coarse_cells = 3.0;
  double fine_yaw_deg = 0.25, fine_cells = 1.0;
};

struct EvalPair {
  std::string a, b;  // map names, a listed before b in the truth
  std::string building;
  long long overlap_cells = 0;  // direct overlap (0 when the truth lists none)
  bool scored = false;          // truly overlapping (connected by overlap edges)
  bool merged = false;          // in one component of the report
  // T_a_b of the report against the truth (merged pairs only): yaw error, translation error,
  // mean displacement of b's occupied cells in b's cells (ComparePoses).
  double yaw_error_deg = 0.0;
  double translation_error_m = 0.0;
  double displacement_cells = 0.0;
  bool coarse = false, fine = false;  // merged and within the tolerances
};

struct EvalFalseMerge {
  std::string a, b;  // maps of different buildings in one component
  int component = 0;
};

struct EvalSummary {
  int maps = 0, components = 0;
  int scored_pairs = 0, merged_pairs = 0, coarse_pairs = 0, fine_pairs = 0;
  double coarse_rate = 0.0, fine_rate = 0.0;  // of the scored pairs; 1 when there are none
  int false_merges = 0;
  std::vector<std::string> missed_maps;
  // Over the merged scored pairs (0 when there are none).
  double median_yaw_error_deg = 0.0, max_yaw_error_deg = 0.0;
  double median_displacement_cells = 0.0, max_displacement_cells = 0.0;
};

struct Evaluation {
  std::vector<EvalPair> pairs;  // scored pairs, then listed overlaps that are not scored
  std::vector<EvalFalseMerge> false_merges;
  EvalSummary summary;
};

// `maps[i]` is truth.maps[i] loaded (its occupied cells measure the displacement). Maps are
// matched by name; a map of the report missing from the truth, or the reverse, throws
// fleetmerge::Error naming the map and both files (`report_name`, `truth_name`).
Evaluation Evaluate(const MergeReport& report, const GroundTruth& truth,
                    const std::vector<const OccupancyGrid*>& maps, const EvalOptions& options,
                    const std::string& report_name, const std::string& truth_name);

}  // namespace fleetmerge
