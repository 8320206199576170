// One map of a pair search with the work that depends on it alone done once: its hypothesis
// features (core/map_features.hpp) and its alignment targets (refine/: wall distance fields of
// the map and of its coarser copies). In a fleet of N maps each map is in N - 1 pairs; the
// 8-robot ACES case rebuilt these 7 times per map (perf: cell centres, Hough transforms,
// resampling and distance fields together ~12 % of a merge).
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "core/map_features.hpp"
#include "core/occupancy_grid.hpp"
#include "job/pair_options.hpp"
#include "refine/local_alignment.hpp"

namespace fleetmerge {

// What a cache keeps of a prepared map (pipeline/pair_cache.hpp): its dearest parts, the Hough
// spectrum and the alignment targets by scale. The rest (cell lists, known spans, near-wall mask)
// is made again from the cells in less time than its bytes would take to read back.
struct KeptTarget {
  // The target's field (WallDistanceField's offset(), distances() and flat()).
  Eigen::Array2i offset_cells = Eigen::Array2i::Zero();
  cv::Mat1f distances;
  cv::Mat1b flat;
  // Its wall cell centres; none at scale 1, whose are the map's own (MapFeatures::walls.centres).
  std::vector<Eigen::Vector2f> wall_centres;
};
struct KeptPreparation {
  std::vector<double> hough_spectrum;  // MapFeatures::hough_spectrum
  std::map<int, KeptTarget> targets;   // by scale
};

class PreparedMap {
 public:
  // Keeps a reference to `grid`, which must outlive this object.
  PreparedMap(const OccupancyGrid& grid, const PairOptions& options);
  // With the parts a cache kept of this map's preparation with these options: the same prepared
  // map, its Hough spectrum and targets taken instead of made.
  PreparedMap(const OccupancyGrid& grid, const PairOptions& options, KeptPreparation kept);
  PreparedMap(const PreparedMap&) = delete;
  PreparedMap& operator=(const PreparedMap&) = delete;

  const OccupancyGrid& grid() const { return features_.grid; }
  const MapFeatures& features() const { return features_; }

  // The alignment target of the map resampled `scale` times coarser (1: the map itself), with
  // PairOptions::refine_truncation_cells. Made on first use; safe to call from several threads.
  const AlignmentTarget& Target(int scale) const;
  // The scales whose targets are made (or were kept), and how many of them were made here, not
  // kept: what a cache stores, and whether it must store it again.
  std::map<int, const AlignmentTarget*> Targets() const;
  int targets_made() const;

  // The map's walls for the judging of solved pairs (core/wall_agreement.hpp), moved out of its
  // features (MapFeatures::walls): for the map's last pair to hand on (pipeline/all_pairs.hpp).
  // The features must not be used afterwards.
  MapWalls TakeWalls();

 private:
  MapFeatures features_;
  double truncation_cells_;
  mutable std::mutex mutex_;
  mutable std::map<int, std::unique_ptr<const AlignmentTarget>> targets_;  // by scale
  mutable int targets_made_ = 0;
};

}  // namespace fleetmerge
