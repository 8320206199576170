// Every parameter of a fleet-merging job, with the defaults a user should not need to change.
// Filled from a job YAML by io/job_file.hpp (validated there) or from the command line.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "job/fusion_mode.hpp"
#include "job/pair_options.hpp"
#include "octree/octree_options.hpp"
#include "refine/pose_graph.hpp"

namespace fleetmerge {

// 1 GiB: a pair's entry (~330 bytes) takes a 4 KiB filesystem block, so about 260,000 pairs
// (720 maps' worth; configs/README.md).
inline constexpr std::int64_t kDefaultCacheMaxMb = 1024;
inline constexpr std::int64_t kLargestCacheMaxMb = std::int64_t(1) << 40;  // bytes fit an int64

struct FleetOptions {
  double resolution_m = 0.0;  // 0: the finest resolution among the job's maps
  PairOptions pair;           // Hough, sampling, hypotheses per pair, translation, refinement
  // A pair becomes a pose-graph edge when its best hypothesis has omega >= omega_threshold, at
  // least min_overlap_cells cells known in both maps, and a symmetric wall agreement
  // (core/wall_agreement.hpp) >= min_wall_agreement. Defaults from the measurements in
  // docs/method.md.
  double omega_threshold = 0.9;
  int min_overlap_cells = 5000;
  double min_wall_agreement = 0.8;
  // An edge that is the only link between two groups of maps of a component of three or more
  // (a bridge: no cycle checks it) needs wall agreement >= min_bridge_wall_agreement: chance
  // matches of a look-alike building pass the thresholds above (pipeline/weak_bridges.hpp).
  double min_bridge_wall_agreement = 0.89;
  // A pair with a fixed map (a site map) is searched with this translation free_penalty
  // (core/translation_search.hpp) instead of pair.hypotheses.translation's. Between two robots
  // the penalty lets a small true overlap beat a large wrong one; a robot inside a site map
  // overlaps it wholly, so there the penalty only costs the true pose the cells where the two
  // maps disagree: the Willow Garage map's grey, porous walls put the truth below wrong poses at
  // 2.0. The pairs of 700 robots simulated in 14 real buildings with the building's map
  // (scripts/fixed_base_penalty.sh; docs/accuracy.md, "Fixed base maps"): 699 right at 0.25 and
  // at 0, 691 at 0.5 (MIT building 31), 632 at 2.0 (Willow, MIT building 31).
  double fixed_map_free_penalty = 0.25;
  PoseGraphOptions pose_graph;
  FusionMode fusion = FusionMode::kLogOdds;
  int threads = 0;       // 0: all cores
  OctreeOptions octree;  // floor plans of the job's octrees (.bt, .ot maps)
  // A map image announcing more cells is refused before decoding (see kDefaultMaxMapCells).
  std::int64_t max_map_cells = kDefaultMaxMapCells;
  // Re-runs reuse earlier work (pipeline/pair_cache.hpp): the pairs' hypotheses are kept in this
  // folder (empty: no cache), which holds at most cache_max_mb MiB (least recently used entries
  // are evicted beyond).
  std::filesystem::path cache_dir;
  std::int64_t cache_max_mb = kDefaultCacheMaxMb;
  // Colour each merged map's preview while compositing (FleetComponent::preview): a job that
  // writes its results asks for them.
  bool previews = false;
  // The maps' names, in job order, for notes and errors (pipeline/map_label.hpp); empty: maps
  // are named by their number.
  std::vector<std::string> map_names;
};

}  // namespace fleetmerge
