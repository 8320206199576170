// Netpbm pixels (PBM/PGM/PPM, ASCII P1..P3 and binary P4..P6) decoded and encoded here, so the
// map loader needs no image library (OpenCV's imgcodecs pulled ~110 shared libraries, ~60 ms of
// every start-up, in for these two formats and PNG). The header comes from io/pnm_header.hpp.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "io/pnm_header.hpp"

namespace fleetmerge {

// The pixels of a Netpbm file whose whole content is `bytes` and whose header is `header`
// (ReadPnmHeader of the same file). Returns a Mat of 1 channel (PBM, PGM) or 3 (PPM, in file
// order R, G, B) and depth CV_8U (maxval <= 255) or CV_16U (maxval > 255), the conventions of
// cv::imread(IMREAD_UNCHANGED) on these files:
// - 8-bit samples are rescaled to 0..255 as round-down(v * 255 / maxval); 16-bit samples are
//   returned raw (0..maxval) and the caller scales them;
// - PBM bits are 1 = black: 1 -> 0 and 0 -> 255;
// - a sample above maxval counts as maxval.
// Throws std::runtime_error with what is wrong (a non-number in an ASCII raster, fewer samples
// than the header announces) and no file name: the caller adds it.
cv::Mat DecodePnm(const std::string& bytes, const PnmHeader& header);

// Binary PGM (P5) of a 1-channel 8-bit (maxval 255) or 16-bit (maxval 65535, big-endian
// samples) image.
std::string EncodePgm(const cv::Mat& image);

}  // namespace fleetmerge
