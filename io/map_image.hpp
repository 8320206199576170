// The image half of a map_server map: decoding PGM/PNG pixels into CellState values (and back),
// and encoding images for atomic writes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

#include "core/occupancy_grid.hpp"
#include "io/map_io.hpp"

namespace fleetmerge {

// A decoded map image reduced to what map_server looks at: the grey value of each pixel on a
// 0..255 scale (mean of the colour channels, 16-bit samples scaled down) and whether it is
// opaque (no alpha channel, or alpha > 0). Rows are image rows: row 0 is the top of the map.
struct MapImage {
  cv::Mat1d value;
  cv::Mat1b opaque;  // 1 where opaque, 0 where alpha == 0
  // For 8-bit single-channel images (most maps) only this is set, and value/opaque are empty:
  // a 256-entry table then classifies the pixels with no full-size intermediate images, whose
  // fresh allocations (page faults) cost ~25 ms for a 600 x 600 map here.
  cv::Mat1b grey8;
  cv::Size size() const { return grey8.empty() ? value.size() : grey8.size(); }
};

// Decodes `image_path` (Netpbm P1..P6 by io/pnm_image.hpp, PNG by io/png_image.hpp: grey,
// grey+alpha, RGB, RGBA; 8- or 16-bit). Throws fleetmerge::Error "<image_path>: ..."
// (mentioning `yaml_path`, the file that named it) when the file is empty, not an image, larger
// than `max_cells` pixels or truncated (checked from its header before decoding: see
// io/image_header.hpp), or of an unsupported depth/channel count.
MapImage ReadMapImage(const std::filesystem::path& image_path,
                      const std::filesystem::path& yaml_path, std::int64_t max_cells);

// map_server's pixel -> occupancy rule (see LoadMap) applied to every pixel; the result has
// grid rows, i.e. row j is image row (height - 1 - j).
cv::Mat1b PixelsToCells(const MapImage& image, const MapMetadata& metadata);

// The trinary PGM pixels of a grid (occupied 0, unknown 205, free 254), image row 0 at the top.
// Throws fleetmerge::Error "<path_for_errors>: ..." if a cell holds a value that is not a
// CellState.
cv::Mat1b CellsToPixels(const OccupancyGrid& grid, const std::filesystem::path& path_for_errors);

// Encodes an 8- or 16-bit image as PNG or binary PGM, chosen by `path`'s extension (.png: 1, 3
// or 4 channels; .pgm: 1 channel). Throws fleetmerge::Error "<path>: ..." otherwise. A PNG is
// encoded on `threads` threads (EncodePng).
std::string EncodeImage(const cv::Mat& image, const std::filesystem::path& path, int threads = 1);

}  // namespace fleetmerge
