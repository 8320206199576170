// Occupancy grid maps on disk in ROS map_server / Nav2 map_io form: a YAML file naming an image
// (PGM or PNG) plus resolution, origin and thresholds. Loading follows map_server's pixel
// semantics (see LoadMap); saving writes a trinary PGM and its YAML, each atomically.
#pragma once

#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/occupancy_grid.hpp"
#include "core/pose2.hpp"
#include "io/atomic_file.hpp"

namespace fleetmerge {

// How pixel values become occupancy (map_server's `mode` key).
enum class MapMode { kTrinary, kScale, kRaw };

// The YAML file's contents, with `image` resolved to a path.
struct MapMetadata {
  std::filesystem::path yaml_path;
  std::filesystem::path image_path;  // relative `image` values are relative to the YAML's folder
  double resolution_m = 0.0;
  Pose2 origin;  // pose of the lower-left corner of cell (0, 0) in the map frame: [x, y, yaw]
  bool negate = false;
  double occupied_thresh = 0.65;
  double free_thresh = 0.196;
  MapMode mode = MapMode::kTrinary;
};

// Where a map read from a bag came from (io/bag_maps.hpp); reported in report.json.
struct BagMapInfo {
  std::filesystem::path bag;
  std::string topic, type, frame_id;  // frame_id: the message's header.frame_id
  std::int64_t log_time_ns = 0;       // when the recorder received the message
  std::int64_t stamp_ns = 0;          // its header.stamp
};

struct LoadedMap {
  OccupancyGrid grid;  // cells hold CellState values only
  MapMetadata metadata;
  std::optional<BagMapInfo> bag;  // set for a map read from a bag (metadata.yaml_path: the bag)
};

// Loads a map_server YAML and its image. Pixel value v in 0..255 (16-bit images are scaled to
// it, colour images use the mean of the colour channels):
//   trinary, scale: p = negate ? v / 255 : (255 - v) / 255; p > occupied_thresh -> occupied,
//                   p < free_thresh -> free, else unknown; a pixel with alpha 0 is unknown.
//   raw:            v is an occupancy percentage; v > 100 -> unknown, else p = v / 100 as above.
// Image row 0 is the top of the map, so grid row j is image row (height - 1 - j). The origin's
// yaw is honoured (it becomes the geometry's T_map_grid). Throws fleetmerge::Error whose message
// starts with the file's path and names the key or line and what was expected. An image whose
// header announces more than `max_cells` pixels is refused before anything is decoded.
LoadedMap LoadMap(const std::filesystem::path& yaml_path,
                  std::int64_t max_cells = kDefaultMaxMapCells);

// Writes `<stem>.pgm` (binary, trinary: occupied 0, unknown 205, free 254) beside `yaml_path`,
// then the YAML (mode trinary, negate 0, occupied_thresh 0.65, free_thresh 0.196), each through
// WriteFileAtomically: the image comes first, so no reader sees a YAML naming a missing image.
// Refuses to overwrite any of `protected_inputs` (both files are checked before either is
// written). `mode`: WriteFileAtomically's.
void SaveMap(const OccupancyGrid& grid, const std::filesystem::path& yaml_path,
             const std::vector<std::filesystem::path>& protected_inputs = {},
             AtomicWrite mode = AtomicWrite::kDurable);

// Writes an 8- or 16-bit image atomically, as PNG (.png: 1, 3 or 4 channels) or binary PGM
// (.pgm: 1 channel), chosen by the extension, a PNG encoded on `threads` threads. For previews
// and debugging output.
void SaveImage(const cv::Mat& image, const std::filesystem::path& path,
               const std::vector<std::filesystem::path>& protected_inputs = {},
               AtomicWrite mode = AtomicWrite::kDurable, int threads = 1);

}  // namespace fleetmerge
