// Checks a map image's header before any pixel is decoded: the format (Netpbm or PNG, by its
// magic bytes), the announced size against a cell limit, and, for binary Netpbm files, that the
// file is long enough for the pixels its header announces. OpenCV would otherwise allocate
// whatever a (possibly corrupt) header claims: a 20000 x 20000 PGM took 5 minutes and 13.5 GB to
// load; a truncated PGM made it print its own message on stderr.
#pragma once

#include <cstdint>
#include <filesystem>

namespace fleetmerge {

struct ImageHeaderSize {
  std::int64_t width = 0;
  std::int64_t height = 0;
};

// Throws fleetmerge::Error "<image_path>: ... (the image of map <yaml_path>)" when the file is
// empty, neither Netpbm (P1..P6) nor PNG, has a malformed or incomplete header, announces 0
// pixels or more than `max_cells` pixels, or (binary Netpbm) holds fewer bytes than its pixels
// need. Returns the announced size.
ImageHeaderSize CheckImageHeader(const std::filesystem::path& image_path,
                                 const std::filesystem::path& yaml_path, std::int64_t max_cells);

}  // namespace fleetmerge
