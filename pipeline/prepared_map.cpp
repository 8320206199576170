#include "pipeline/prepared_map.hpp"

#include <utility>

#include "core/resample.hpp"

namespace fleetmerge {

PreparedMap::PreparedMap(const OccupancyGrid& grid, const PairOptions& options)
    : features_(grid, options.hypotheses), truncation_cells_(options.refine_truncation_cells) {}

const AlignmentTarget& PreparedMap::Target(int scale) const {
  // One lock per map: threads asking for another map's target do not wait; two asking for the
  // same one would have built it twice.
  const std::lock_guard<std::mutex> lock(mutex_);
  std::unique_ptr<const AlignmentTarget>& target = targets_[scale];
  if (!target) {
    const OccupancyGrid& grid = features_.grid;
    target = scale == 1 ? std::make_unique<const AlignmentTarget>(features_.walls.centres,
                                                                  truncation_cells_)
                        : std::make_unique<const AlignmentTarget>(
                              ResampleToResolution(grid, grid.geometry().resolution_m() * scale),
                              truncation_cells_);
  }
  return *target;
}

MapWalls PreparedMap::TakeWalls() { return std::move(features_.walls); }

}  // namespace fleetmerge
