// PNG pixels decoded with libspng (Debian's libspng0: zlib only; OpenCV's imgcodecs, which did
// this before, loads ~110 shared libraries at every start-up) and encoded with zlib in bands of
// rows on threads (png_image.cpp says why).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace fleetmerge {

// The pixels of the PNG file whose whole content is `bytes`. An 8-bit grey PNG without a tRNS
// chunk gives a CV_8UC1 Mat; every other PNG gives 4 channels R, G, B, A (tRNS applied as
// alpha, palettes expanded, grey copied to R, G and B), CV_16U when the PNG has 16-bit samples
// and CV_8U otherwise (1-, 2- and 4-bit samples scaled to 0..255). No gamma correction: the
// samples are the file's. Throws std::runtime_error with libspng's reason (no file name).
cv::Mat DecodePng(const std::string& bytes);

// PNG of an 8- or 16-bit image with 1 (grey), 3 (BGR, OpenCV's order) or 4 (BGRA) channels,
// written like cv::imwrite's default (zlib level 1, RLE strategy, "sub" filter: fast, and
// maps compress well anyway), on `threads` threads (<= 0: all cores; the bytes are the same for
// any count).
std::string EncodePng(const cv::Mat& image, int threads = 1);

// Palette PNG (PLTE and tRNS chunks) of 8-bit `indices` into `palette_rgba` (R, G, B, A; 1 to
// 256 colours): decoded, the RGBA image of the palette's colours. One byte a pixel to filter and
// compress where RGBA takes four. Throws std::runtime_error for an index beyond the palette.
// `threads` as for EncodePng.
std::string EncodeIndexedPng(const cv::Mat1b& indices, const std::vector<cv::Vec4b>& palette_rgba,
                             int threads = 1);

}  // namespace fleetmerge
