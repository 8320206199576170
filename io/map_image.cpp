#include "io/map_image.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <opencv2/core.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "core/error.hpp"
#include "core/image_masks.hpp"
#include "io/image_header.hpp"
#include "io/png_image.hpp"
#include "io/pnm_header.hpp"
#include "io/pnm_image.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

constexpr std::uint8_t kOccupiedPixel = 0;
constexpr std::uint8_t kUnknownPixel = 205;
constexpr std::uint8_t kFreePixel = 254;

[[noreturn]] void FailImage(const fs::path& image_path, const fs::path& yaml_path,
                            const std::string& what) {
  throw Error(image_path.string() + ": " + what + " (the image of map " + yaml_path.string() + ")");
}

// Factor that brings samples onto 0..255. DecodePnm already rescales 8-bit Netpbm samples but
// returns 16-bit samples raw (0..maxval), so a 16-bit Netpbm file is scaled by its maxval; 16-bit
// PNG samples span 0..65535 (v / 257).
double SampleScale(const cv::Mat& raw, const std::optional<PnmHeader>& pnm) {
  if (raw.depth() == CV_8U) return 1.0;
  if (pnm && pnm->maxval > 255) return 255.0 / pnm->maxval;
  return 255.0 / 65535.0;
}

MapImage Normalise(const cv::Mat& raw, double scale) {
  cv::Mat scaled;
  raw.convertTo(scaled, CV_64F, scale);
  std::vector<cv::Mat> channels;
  cv::split(scaled, channels);
  // Channel layouts: grey, grey+alpha, colour, colour+alpha (the mean makes the order moot).
  const bool has_alpha = channels.size() == 2 || channels.size() == 4;
  const int colour_channels = static_cast<int>(channels.size()) - (has_alpha ? 1 : 0);
  MapImage image;
  image.value = channels[0].clone();
  for (int c = 1; c < colour_channels; ++c) image.value += channels[c];
  image.value /= colour_channels;  // map_server: mean of the colour channels
  image.opaque = cv::Mat1b(raw.size(), 1);
  if (has_alpha) image.opaque.setTo(0, CompareMask(channels.back(), cv::CMP_EQ, 0));
  return image;
}

CellState Threshold(double occupancy, const MapMetadata& metadata) {
  if (occupancy > metadata.occupied_thresh) return CellState::kOccupied;
  if (occupancy < metadata.free_thresh) return CellState::kFree;
  return CellState::kUnknown;
}

// map_server / Nav2 map_io: grey value v -> occupancy probability -> three states.
CellState Classify(double value, bool opaque, const MapMetadata& metadata) {
  if (metadata.mode == MapMode::kRaw) {
    const double percent = std::round(value);  // raw pixels are occupancy percentages
    return percent > 100.0 ? CellState::kUnknown : Threshold(percent / 100.0, metadata);
  }
  if (!opaque) return CellState::kUnknown;
  const double occupancy = metadata.negate ? value / 255.0 : (255.0 - value) / 255.0;
  return Threshold(occupancy, metadata);
}

// One read of the file's size, not a stream grown 8 KiB at a time: that copied each map about
// three times over, and a job's maps are loaded into untouched memory, where every copied page
// is a page fault first.
std::string ReadWholeFile(const fs::path& path, const fs::path& yaml_path) {
  std::ifstream in(path, std::ios::binary);
  std::error_code error;
  const std::uintmax_t size = fs::file_size(path, error);
  std::string bytes;
  if (in && !error) {
    bytes.resize(static_cast<std::size_t>(size));
    in.read(bytes.data(), static_cast<std::streamsize>(size));
    bytes.resize(static_cast<std::size_t>(in.gcount()));  // shorter if the file shrank since
  }
  if (in) {  // whatever the file grew by since its size was taken
    std::ostringstream rest;
    rest << in.rdbuf();
    bytes += rest.str();
  }
  if (!in.is_open() || in.bad() || bytes.empty()) FailImage(path, yaml_path, "cannot be read");
  return bytes;
}

std::string LowerExtension(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

}  // namespace

MapImage ReadMapImage(const fs::path& image_path, const fs::path& yaml_path,
                      std::int64_t max_cells) {
  CheckImageHeader(image_path, yaml_path, max_cells);  // before anything is allocated
  const std::string bytes = ReadWholeFile(image_path, yaml_path);
  const bool is_pnm = bytes.size() >= 2 && bytes[0] == 'P';  // else PNG (CheckImageHeader)
  const std::optional<PnmHeader> pnm =
      is_pnm ? ReadPnmHeader(image_path) : std::optional<PnmHeader>();
  if (is_pnm && !pnm) {  // the file changed since CheckImageHeader read it
    FailImage(image_path, yaml_path, "has a malformed or incomplete Netpbm (PGM) header");
  }
  cv::Mat raw;
  try {
    raw = is_pnm ? DecodePnm(bytes, *pnm) : DecodePng(bytes);
  } catch (const std::runtime_error& e) {
    FailImage(image_path, yaml_path,
              std::string("is not a readable PGM/PNG image (") + e.what() + ")");
  } catch (const cv::Exception& e) {  // allocation of the announced size failed
    FailImage(image_path, yaml_path, "is not a readable PGM/PNG image (" + e.msg + ")");
  }
  if (raw.type() == CV_8UC1) return MapImage{{}, {}, raw};
  return Normalise(raw, SampleScale(raw, pnm));
}

cv::Mat1b PixelsToCells(const MapImage& image, const MapMetadata& metadata) {
  if (!image.grey8.empty()) {
    // The same rule as below, evaluated once per grey level.
    cv::Mat1b table(1, 256);
    for (int v = 0; v < 256; ++v) table(0, v) = std::uint8_t(Classify(v, true, metadata));
    cv::Mat1b cells;
    cv::LUT(image.grey8, table, cells);
    cv::flip(cells, cells, 0);  // image row 0 is the top of the map; grid row 0 the bottom
    return cells;
  }
  const int rows = image.value.rows;
  cv::Mat1b cells(rows, image.value.cols);
  for (int r = 0; r < rows; ++r) {
    // Image row 0 is the top of the map; grid row 0 is the bottom (+y up): flip.
    std::uint8_t* cell_row = cells[rows - 1 - r];
    const double* value_row = image.value[r];
    const std::uint8_t* opaque_row = image.opaque[r];
    for (int c = 0; c < image.value.cols; ++c) {
      const CellState state = Classify(value_row[c], opaque_row[c] != 0, metadata);
      cell_row[c] = static_cast<std::uint8_t>(state);
    }
  }
  return cells;
}

cv::Mat1b CellsToPixels(const OccupancyGrid& grid, const fs::path& path_for_errors) {
  const cv::Mat1b& cells = grid.cells();
  cv::Mat1b pixels(cells.rows, cells.cols);
  for (int j = 0; j < cells.rows; ++j) {
    const std::uint8_t* cell_row = cells[j];
    std::uint8_t* pixel_row = pixels[cells.rows - 1 - j];  // grid row 0 is the image's bottom
    for (int i = 0; i < cells.cols; ++i) {
      switch (static_cast<CellState>(cell_row[i])) {
        case CellState::kOccupied:
          pixel_row[i] = kOccupiedPixel;
          break;
        case CellState::kFree:
          pixel_row[i] = kFreePixel;
          break;
        case CellState::kUnknown:
          pixel_row[i] = kUnknownPixel;
          break;
        default:
          throw Error(path_for_errors.string() + ": cell (" + std::to_string(i) + ", " +
                      std::to_string(j) + ") holds " + std::to_string(cell_row[i]) +
                      ", expected a CellState (0 unknown, 1 free, 2 occupied)");
      }
    }
  }
  return pixels;
}

std::string EncodeImage(const cv::Mat& image, const fs::path& path, int threads) {
  const std::string extension = LowerExtension(path);
  const auto fail = [&path](const std::string& what) { throw Error(path.string() + ": " + what); };
  if (extension != ".png" && extension != ".pgm") {
    fail("unsupported image extension '" + path.extension().string() + "', expected .png or .pgm");
  }
  if (image.empty()) fail("cannot save an empty image");
  if (image.depth() != CV_8U && image.depth() != CV_16U) fail("expected 8- or 16-bit samples");
  const int channels = image.channels();
  if (extension == ".pgm" && channels != 1) {
    fail("a PGM holds 1 channel, got " + std::to_string(channels));
  }
  if (channels != 1 && channels != 3 && channels != 4) {
    fail("a PNG holds 1, 3 or 4 channels, got " + std::to_string(channels));
  }
  return extension == ".pgm" ? EncodePgm(image) : EncodePng(image, threads);
}

}  // namespace fleetmerge
