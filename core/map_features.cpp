#include "core/map_features.hpp"

#include <algorithm>
#include <opencv2/core.hpp>

#include "core/hough_spectrum.hpp"
#include "core/image_masks.hpp"
#include "core/point_sampling.hpp"
#include "core/wall_agreement.hpp"

namespace fleetmerge {

namespace {

// The occupied cell centres; with the correlation search the free ones too, into `free`, in the
// same pass (the search also needs open space).
std::vector<Eigen::Vector2f> OccupiedCentres(const OccupancyGrid& grid,
                                             const HypothesisOptions& options,
                                             std::vector<Eigen::Vector2f>* free) {
  std::vector<Eigen::Vector2f> occupied;
  if (options.translation.method == TranslationMethod::kCorrelation2D) {
    OccupiedAndFreeCellCenters(grid, &occupied, free);
  } else {
    occupied = OccupiedCellCenters(grid);
  }
  return occupied;
}

}  // namespace

MapFeatures::MapFeatures(const OccupancyGrid& grid, const HypothesisOptions& options,
                         const std::vector<double>* cached_hough_spectrum)
    : grid(grid),  // `free` (declared before `walls`) is made before it is filled here
      walls(grid, OccupiedCentres(grid, options, &free), NearWallMask(grid), KnownRowSpans(grid)) {
  const double known = cv::countNonZero(grid.cells());  // kUnknown is 0
  if (known > 0) {
    near_wall_share =
        cv::countNonZero(MaskAnd(walls.near_walls, CompareMask(grid.cells(), cv::CMP_NE, 0))) /
        known;
    occupied_share = grid.Count(CellState::kOccupied) / known;
  }
  spectra_points = SamplePoints(walls.centres, options.spectra_sampling);
  // A spectrum of another length is no spectrum of this map with these options: made anew.
  const std::size_t spectrum_size =
      walls.centres.empty() ? 0 : static_cast<std::size_t>(options.hough.n_theta);
  if (cached_hough_spectrum != nullptr && cached_hough_spectrum->size() == spectrum_size) {
    hough_spectrum = *cached_hough_spectrum;
  } else if (!walls.centres.empty()) {
    hough_spectrum = HoughSpectrum(
        ComputeHoughTransform(SamplePoints(walls.centres, options.hough_sampling), options.hough));
  }
}

}  // namespace fleetmerge
