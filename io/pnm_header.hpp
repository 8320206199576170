// Reads the header of a Netpbm file (PBM/PGM/PPM, ASCII or binary). io/pnm_image.hpp decodes the
// pixels after it; the loader also needs maxval to scale 16-bit samples (DecodePnm rescales 8-bit
// samples to 0..255 but returns 16-bit samples raw: a PGM with maxval 1023 gives 0..1023).
#pragma once

#include <filesystem>
#include <optional>

namespace fleetmerge {

struct PnmHeader {
  char kind = '5';  // the digit after 'P': 1..6
  int width = 0;
  int height = 0;
  int maxval = 1;  // 1 for bitmaps (P1, P4)
  // Bytes before the pixel data (the header and the one whitespace character that ends it);
  // -1 when the file ends inside the header.
  long long data_offset = 0;
};

// The header, or nullopt when the file does not start with a complete Netpbm header.
std::optional<PnmHeader> ReadPnmHeader(const std::filesystem::path& path);

}  // namespace fleetmerge
