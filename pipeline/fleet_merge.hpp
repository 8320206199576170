// The fleet-merging job on in-memory maps (the product's main job): every pair of maps gets
// Hough hypotheses (pipeline/all_pairs.hpp); pairs with a high best omega and enough overlap
// become omega-weighted pose-graph edges, solved per connected component with cycle checks
// (pipeline/fleet_graph.hpp); each component of two or more maps is composited into one map, and
// a fixed map that no map joined, or a map that its prior places alone (the only map with one), is
// its component's merged map as it is, at its pose in the site frame.
// A map that overlaps no other (and has no fixed pose or prior) stays unmerged: never forced in,
// never dropped.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "job/fleet_options.hpp"
#include "pipeline/all_pairs.hpp"
#include "pipeline/fleet_graph.hpp"

namespace fleetmerge {

struct FleetComponent {
  std::vector<int> maps;  // map indices, in job order
  int reference = 0;      // the map whose frame is the component's merged frame
  // Components of two or more maps, a one-map job's, and a fixed map's that no map joined.
  std::optional<OccupancyGrid> merged;
  // ColourPreview of `merged` from the inputs at the compared resolution, made while compositing
  // when FleetOptions::previews asks (empty otherwise, or when the merged cells are not the
  // compared ones: the preview then samples other inputs than compositing did).
  cv::Mat3b preview;
};

struct FleetTiming {
  double pairs_ms = 0.0, refine_ms = 0.0, composite_ms = 0.0;
};

struct FleetResult {
  double resolution_m = 0.0;           // the maps were compared and composited at this
  std::vector<OccupancyGrid> maps;     // the inputs at resolution_m (sharing their cells)
  std::vector<int> component_of;       // per map
  std::vector<Pose2> T_component_map;  // per map: its map frame in its component's frame
  std::vector<PlacedBy> placed_by;     // per map: what put it there (pipeline/fleet_graph.hpp)
  std::vector<FleetComponent> components;
  std::vector<PairOutcome> pairs;  // every pair a < b
  FleetTiming timing;
};

// `reference` indexes `maps`. Throws fleetmerge::Error for an empty list or a bad reference.
// `cache` (pipeline/pair_cache.hpp), when given, supplies the pairs it holds and keeps the others
// (the same result as without it), and is closed (trimmed, unlocked) once the pairs are done.
// options.cache_dir is not looked at here (RunLoadedJob opens it).
FleetResult MergeFleet(const std::vector<const OccupancyGrid*>& maps, int reference,
                       const FleetOptions& options, const ProgressFn& progress = {},
                       PairCache* cache = nullptr);

// With fixed (base) maps: `fixed` holds, per map, its given pose T_merged_map or nullopt for a
// map that moves (empty: none is fixed). Fixed maps never move; the merged frame is theirs;
// `reference` must be the first of them, whose cell lattice (moved by its pose) the merged map
// keeps; every cell a fixed map knows comes out unchanged, and the other maps fill only the cells
// no fixed map knows (pipeline/composite.hpp). Throws fleetmerge::Error for a non-finite pose, a
// `fixed` list of another length, or a reference that is not the first fixed map.
FleetResult MergeFleet(const std::vector<const OccupancyGrid*>& maps, int reference,
                       const FixedPoses& fixed, const FleetOptions& options,
                       const ProgressFn& progress = {}, PairCache* cache = nullptr);

// With known start poses too: `priors` holds, per map, its prior (job/pose_prior.hpp) or nullopt
// (empty: none has one). Hypotheses that contradict two maps' known poses are dropped and a pair
// left with none is refused (pipeline/pose_priors.hpp); the priors join the pose graph, so a map
// with a prior that overlaps no other is placed at it (pipeline/fleet_graph.hpp), and the
// component holding the priors has their site frame. Throws fleetmerge::Error as above, and for
// a prior list of another length, a non-finite prior, a sigma <= 0 or a prior on a fixed map.
FleetResult MergeFleet(const std::vector<const OccupancyGrid*>& maps, int reference,
                       const FixedPoses& fixed, const PosePriors& priors,
                       const FleetOptions& options, const ProgressFn& progress = {},
                       PairCache* cache = nullptr);

}  // namespace fleetmerge
