#include "pipeline/prepared_map.hpp"

#include <utility>

#include "core/resample.hpp"

namespace fleetmerge {

PreparedMap::PreparedMap(const OccupancyGrid& grid, const PairOptions& options)
    : features_(grid, options.hypotheses), truncation_cells_(options.refine_truncation_cells) {}

PreparedMap::PreparedMap(const OccupancyGrid& grid, const PairOptions& options,
                         KeptPreparation kept)
    : features_(grid, options.hypotheses, &kept.hough_spectrum),
      truncation_cells_(options.refine_truncation_cells) {
  for (const auto& [scale, t] : kept.targets) {
    targets_[scale] = std::make_unique<const AlignmentTarget>(
        scale == 1 ? features_.walls.centres : t.wall_centres, truncation_cells_, t.offset_cells,
        t.distances, t.flat);
  }
}

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
    ++targets_made_;
  }
  return *target;
}

std::map<int, const AlignmentTarget*> PreparedMap::Targets() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::map<int, const AlignmentTarget*> out;
  for (const auto& [scale, target] : targets_) {
    if (target) out[scale] = target.get();
  }
  return out;
}

int PreparedMap::targets_made() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return targets_made_;
}

MapWalls PreparedMap::TakeWalls() { return std::move(features_.walls); }

}  // namespace fleetmerge
