// Maps of different resolutions are merged at the finest (or a given) resolution, so each is
// resampled first (core/resample.hpp). A map whose resampled grid would exceed the cell limit
// (one at 1e-300 m per cell beside one at 0.05 m) is refused here, before any work, naming
// both files, instead of failing deep inside with an overflowed grid size.
#pragma once

#include <cstdint>
#include <vector>

#include "io/map_io.hpp"

namespace fleetmerge {

// resolution_m 0: the finest of the maps. Throws fleetmerge::Error.
void CheckResampledSizes(const std::vector<const LoadedMap*>& maps, double resolution_m,
                         std::int64_t max_cells);

// How errors name a loaded map: its YAML, or "<bag> topic <topic>".
std::string MapLabel(const LoadedMap& map);

}  // namespace fleetmerge
