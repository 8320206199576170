// One map of a pair search with the work that depends on it alone done once: its hypothesis
// features (core/map_features.hpp) and its alignment targets (refine/: wall distance fields of
// the map and of its coarser copies). In a fleet of N maps each map is in N - 1 pairs; the
// 8-robot ACES case rebuilt these 7 times per map (perf: cell centres, Hough transforms,
// resampling and distance fields together ~12 % of a merge).
#pragma once

#include <map>
#include <memory>
#include <mutex>

#include "core/map_features.hpp"
#include "core/occupancy_grid.hpp"
#include "job/pair_options.hpp"
#include "refine/local_alignment.hpp"

namespace fleetmerge {

class PreparedMap {
 public:
  // Keeps a reference to `grid`, which must outlive this object.
  PreparedMap(const OccupancyGrid& grid, const PairOptions& options);
  PreparedMap(const PreparedMap&) = delete;
  PreparedMap& operator=(const PreparedMap&) = delete;

  const OccupancyGrid& grid() const { return features_.grid; }
  const MapFeatures& features() const { return features_; }

  // The alignment target of the map resampled `scale` times coarser (1: the map itself), with
  // PairOptions::refine_truncation_cells. Made on first use; safe to call from several threads.
  const AlignmentTarget& Target(int scale) const;

  // The map's walls for the judging of solved pairs (core/wall_agreement.hpp), moved out of its
  // features (MapFeatures::walls): for the map's last pair to hand on (pipeline/all_pairs.hpp).
  // The features must not be used afterwards.
  MapWalls TakeWalls();

 private:
  MapFeatures features_;
  double truncation_cells_;
  mutable std::mutex mutex_;
  mutable std::map<int, std::unique_ptr<const AlignmentTarget>> targets_;  // by scale
};

}  // namespace fleetmerge
