// What the hypothesis search (Algorithm 1) needs of ONE map, whichever map it is paired with:
// its occupied and free cell centres, its Hough spectrum (Section III-A, sampled as in III-D),
// the points of its X/Y spectra, its known row spans (omega, Eq. 1) and its near-wall mask (wall
// agreement). In a fleet of N maps every map is in N - 1 pairs; computing these once per map
// instead of once per pair gives the same numbers at a fraction of the cost.
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "core/acceptance_index.hpp"
#include "core/hypothesis_generator.hpp"
#include "core/occupancy_grid.hpp"
#include "core/wall_agreement.hpp"

namespace fleetmerge {

struct MapFeatures {
  // Keeps a reference to `grid`, which must outlive the features. `cached_hough_spectrum`, when
  // given, is the map's hough_spectrum made before with the same options (a cache's,
  // pipeline/pair_cache.hpp): taken as it is instead of computed again (the Hough transform is
  // the features' dearest part).
  MapFeatures(const OccupancyGrid& grid, const HypothesisOptions& options,
              const std::vector<double>* cached_hough_spectrum = nullptr);

  const OccupancyGrid& grid;
  std::vector<Eigen::Vector2f> free;  // CellCenters(grid, kFree): correlation search
  // Its occupied cell centres (walls.centres), known row spans and near-wall mask: MapWalls(grid),
  // which a fleet's judging of solved pairs takes over (pipeline/prepared_map.hpp).
  MapWalls walls;
  std::vector<Eigen::Vector2f> spectra_points;  // walls.centres, sampled by spectra_sampling
  std::vector<double> hough_spectrum;           // of walls.centres sampled by hough_sampling;
                                                // empty when the map has no occupied cell
  // Chance rates of core/pose_evidence.hpp, as shares of the known cells (0 for an empty map).
  double near_wall_share = 0.0;
  double occupied_share = 0.0;
};

// GenerateHypotheses (core/hypothesis_generator.hpp) on precomputed features: the same result.
// Both feature sets must have been made with the same `options`. The rotation candidates are
// searched on `threads` threads (<= 0: all cores; one pair alone, as `fleetmerge pair` runs;
// a fleet runs its pairs in parallel instead): the same hypotheses for any count.
std::vector<CellHypothesis> GenerateHypotheses(const MapFeatures& a, const MapFeatures& b,
                                               const HypothesisOptions& options, int threads = 1);

}  // namespace fleetmerge
