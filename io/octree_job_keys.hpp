// The `octree` mapping of a job file (configs/README.md): the height band of the floor plans cut
// from the job's octrees. Internal to io/ (yaml-cpp types).
#pragma once

#include "io/yaml_fields.hpp"
#include "octree/octree_options.hpp"

namespace fleetmerge {

// Reads `octree: {band_min_m, band_max_m}` (metres above the floor, band_min_m < band_max_m,
// each in [-10, 10]) over the defaults in `options`.
void ReadOctreeOptions(const YamlField& field, OctreeOptions& options, const YamlErrors& errors);

}  // namespace fleetmerge
