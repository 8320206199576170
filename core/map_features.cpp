#include "core/map_features.hpp"

#include <algorithm>
#include <cstdint>
#include <opencv2/core.hpp>

#include "core/hough_spectrum.hpp"
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
  // The known, occupied and near-wall known cells, counted in one pass: masks of a site's 16 M
  // cells to count them would take fresh pages, which cost more than the counting.
  std::int64_t known = 0, occupied = 0, near_wall_known = 0;
  const auto unknown = static_cast<std::uint8_t>(CellState::kUnknown);
  const auto wall = static_cast<std::uint8_t>(CellState::kOccupied);
  for (int j = 0; j < grid.height(); ++j) {
    const std::uint8_t* cells = grid.cells().ptr<std::uint8_t>(j);
    const std::uint8_t* near = walls.near_walls.ptr<std::uint8_t>(j);
    for (int i = 0; i < grid.width(); ++i) {
      const int is_known = cells[i] != unknown;
      known += is_known;
      occupied += cells[i] == wall;
      near_wall_known += is_known & (near[i] != 0);
    }
  }
  if (known > 0) {
    near_wall_share = static_cast<double>(near_wall_known) / static_cast<double>(known);
    occupied_share = static_cast<double>(occupied) / static_cast<double>(known);
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
