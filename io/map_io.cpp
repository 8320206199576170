#include "io/map_io.hpp"

#include <string>
#include <utility>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "io/map_image.hpp"
#include "io/map_yaml.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;

LoadedMap LoadMap(const fs::path& yaml_path, std::int64_t max_cells) {
  MapMetadata metadata = ReadMapYaml(yaml_path);
  const MapImage image = ReadMapImage(metadata.image_path, yaml_path, max_cells);
  const GridGeometry geometry(metadata.resolution_m, {image.size().width, image.size().height},
                              metadata.origin);
  OccupancyGrid grid(geometry, PixelsToCells(image, metadata));
  return LoadedMap{std::move(grid), std::move(metadata), std::nullopt};
}

void SaveMap(const OccupancyGrid& grid, const fs::path& yaml_path,
             const std::vector<fs::path>& protected_inputs, AtomicWrite mode) {
  if (!yaml_path.has_filename()) throw Error(yaml_path.string() + ": not a file name");
  fs::path image_path = yaml_path;
  image_path.replace_extension(".pgm");
  if (image_path == yaml_path) {
    throw Error(yaml_path.string() + ": a map YAML cannot end in .pgm (its image is " +
                image_path.filename().string() + ")");
  }
  if (grid.width() == 0 || grid.height() == 0) {
    throw Error(yaml_path.string() + ": cannot save an empty map (" + std::to_string(grid.width()) +
                " x " + std::to_string(grid.height()) + " cells)");
  }
  // Check both targets before writing either, so a refusal leaves nothing half-saved.
  CheckNotAnInput(image_path, protected_inputs);
  CheckNotAnInput(yaml_path, protected_inputs);
  const std::string image_bytes = EncodeImage(CellsToPixels(grid, yaml_path), image_path);
  const std::string yaml_text = FormatMapYaml(grid.geometry(), image_path.filename().string());
  WriteFileAtomically(image_path, image_bytes, protected_inputs, mode);
  WriteFileAtomically(yaml_path, yaml_text, protected_inputs, mode);
}

void SaveImage(const cv::Mat& image, const fs::path& path,
               const std::vector<fs::path>& protected_inputs, AtomicWrite mode, int threads) {
  CheckNotAnInput(path, protected_inputs);
  WriteFileAtomically(path, EncodeImage(image, path, threads), protected_inputs, mode);
}

}  // namespace fleetmerge
