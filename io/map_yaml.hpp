// The YAML half of a map_server map: parsing and validating its keys, and writing them back.
#pragma once

#include <filesystem>
#include <string>

#include "core/grid_geometry.hpp"
#include "io/map_io.hpp"

namespace fleetmerge {

// Reads and validates a map YAML (keys as in LoadMap; unknown keys are ignored, a repeated key
// is an error). `image_path` is resolved against the YAML's folder and must exist. Throws
// fleetmerge::Error "<yaml_path>: line L: key 'k': expected ..., got ...".
MapMetadata ReadMapYaml(const std::filesystem::path& yaml_path);

// The YAML text for a trinary map whose image is `image_name` (relative to the YAML's folder).
// Numbers use the shortest form that reads back to the same double.
std::string FormatMapYaml(const GridGeometry& geometry, const std::string& image_name);

}  // namespace fleetmerge
