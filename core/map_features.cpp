#include "core/map_features.hpp"

#include <algorithm>
#include <opencv2/core.hpp>

#include "core/hough_spectrum.hpp"
#include "core/image_masks.hpp"
#include "core/point_sampling.hpp"
#include "core/wall_agreement.hpp"

namespace fleetmerge {

MapFeatures::MapFeatures(const OccupancyGrid& grid, const HypothesisOptions& options)
    : grid(grid), known_spans(KnownRowSpans(grid)), near_walls(NearWallMask(grid)) {
  if (options.translation.method == TranslationMethod::kCorrelation2D) {
    OccupiedAndFreeCellCenters(grid, &occupied, &free);  // the search also needs open space
  } else {
    occupied = OccupiedCellCenters(grid);
  }
  const double known = cv::countNonZero(grid.cells());  // kUnknown is 0
  if (known > 0) {
    near_wall_share =
        cv::countNonZero(MaskAnd(near_walls, CompareMask(grid.cells(), cv::CMP_NE, 0))) / known;
    occupied_share = grid.Count(CellState::kOccupied) / known;
  }
  spectra_points = SamplePoints(occupied, options.spectra_sampling);
  if (!occupied.empty()) {
    hough_spectrum = HoughSpectrum(
        ComputeHoughTransform(SamplePoints(occupied, options.hough_sampling), options.hough));
  }
}

}  // namespace fleetmerge
