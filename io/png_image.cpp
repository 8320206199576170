#include "io/png_image.hpp"

#include <spng.h>
#include <zlib.h>

#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace fleetmerge {
namespace {

using Context = std::unique_ptr<spng_ctx, decltype(&spng_ctx_free)>;

void Check(int error, const char* step) {
  if (error != 0) throw std::runtime_error(std::string(step) + ": " + spng_strerror(error));
}

constexpr std::uint8_t kGrey = 0;
constexpr std::uint8_t kRgb = 2;
constexpr std::uint8_t kIndexed = 3;
constexpr std::uint8_t kRgba = 6;

}  // namespace

cv::Mat DecodePng(const std::string& bytes) {
  Context ctx(spng_ctx_new(0), spng_ctx_free);
  if (!ctx) throw std::runtime_error("libspng could not create a decoder");
  Check(spng_set_png_buffer(ctx.get(), bytes.data(), bytes.size()), "PNG");
  spng_ihdr ihdr{};
  Check(spng_get_ihdr(ctx.get(), &ihdr), "PNG header");
  spng_trns trns{};
  const bool has_trns = spng_get_trns(ctx.get(), &trns) == 0;
  int format = SPNG_FMT_RGBA8;
  int type = CV_8UC4;
  if (ihdr.color_type == kGrey && ihdr.bit_depth == 8 && !has_trns) {
    format = SPNG_FMT_G8;  // most maps: one byte per cell, no conversion
    type = CV_8UC1;
  } else if (ihdr.bit_depth == 16) {
    format = SPNG_FMT_RGBA16;  // host-endian
    type = CV_16UC4;
  }
  std::size_t size = 0;
  Check(spng_decoded_image_size(ctx.get(), format, &size), "PNG");
  cv::Mat image(static_cast<int>(ihdr.height), static_cast<int>(ihdr.width), type);
  if (size != image.total() * image.elemSize()) {
    throw std::runtime_error("PNG: unexpected decoded size");
  }
  Check(spng_decode_image(ctx.get(), image.data, size, format, SPNG_DECODE_TRNS), "PNG data");
  return image;
}

namespace {

// The encoder's settings (cv::imwrite's defaults, but for palette images' filters) and its
// output, for `pixels` in the PNG's own layout (SPNG_FMT_PNG: 16-bit samples host-endian).
// `before_image` may add chunks. `filters`: SPNG_FILTER_CHOICE_SUB for colour and grey images
// (half the bytes of no filtering for a preview); SPNG_DISABLE_FILTERING for palette images,
// whose indices are no quantities to predict (the PNG specification's encoder recommendations,
// "Filter selection": filter type None is usually the most effective for them; the 33 map images
// of scripts/cache_rerun_benchmark.sh take 26 % fewer bytes and 42 % less time than with Sub).
template <typename AddChunks>
std::string Encode(const cv::Mat& pixels, std::uint8_t color_type, int filters,
                   const AddChunks& before_image) {
  CV_Assert(pixels.isContinuous());
  Context ctx(spng_ctx_new(SPNG_CTX_ENCODER), spng_ctx_free);
  if (!ctx) throw std::runtime_error("libspng could not create an encoder");
  Check(spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1), "PNG encoder");
  Check(spng_set_option(ctx.get(), SPNG_IMG_COMPRESSION_LEVEL, 1), "PNG encoder");
  Check(spng_set_option(ctx.get(), SPNG_IMG_COMPRESSION_STRATEGY, Z_RLE), "PNG encoder");
  Check(spng_set_option(ctx.get(), SPNG_FILTER_CHOICE, filters), "PNG encoder");
  spng_ihdr ihdr{};
  ihdr.width = static_cast<std::uint32_t>(pixels.cols);
  ihdr.height = static_cast<std::uint32_t>(pixels.rows);
  ihdr.bit_depth = pixels.depth() == CV_16U ? 16 : 8;
  ihdr.color_type = color_type;
  Check(spng_set_ihdr(ctx.get(), &ihdr), "PNG header");
  before_image(ctx.get());
  Check(spng_encode_image(ctx.get(), pixels.data, pixels.total() * pixels.elemSize(), SPNG_FMT_PNG,
                          SPNG_ENCODE_FINALIZE),
        "PNG encoding");
  std::size_t length = 0;
  int error = 0;
  void* buffer = spng_get_png_buffer(ctx.get(), &length, &error);
  Check(error, "PNG encoding");
  std::string out(static_cast<const char*>(buffer), length);
  std::free(buffer);
  return out;
}

}  // namespace

std::string EncodePng(const cv::Mat& image) {
  CV_Assert(image.depth() == CV_8U || image.depth() == CV_16U);
  CV_Assert(image.channels() == 1 || image.channels() == 3 || image.channels() == 4);
  cv::Mat rgb;  // PNG stores R, G, B; OpenCV images are B, G, R
  if (image.channels() == 1) {
    rgb = image.isContinuous() ? image : image.clone();
  } else {
    // B and R swapped, alpha kept: cv::cvtColor's BGR2RGB / BGRA2RGBA with core alone.
    rgb.create(image.size(), image.type());
    const int from_to[] = {0, 2, 1, 1, 2, 0, 3, 3};
    cv::mixChannels(&image, 1, &rgb, 1, from_to, static_cast<std::size_t>(image.channels()));
  }
  const std::uint8_t type = rgb.channels() == 1 ? kGrey : (rgb.channels() == 3 ? kRgb : kRgba);
  return Encode(rgb, type, SPNG_FILTER_CHOICE_SUB, [](spng_ctx*) {});
}

std::string EncodeIndexedPng(const cv::Mat1b& indices, const std::vector<cv::Vec4b>& palette_rgba) {
  if (palette_rgba.empty() || palette_rgba.size() > 256) {
    throw std::runtime_error("PNG palette: 1 to 256 colours, got " +
                             std::to_string(palette_rgba.size()));
  }
  double max_index = 0.0;
  if (!indices.empty()) cv::minMaxLoc(indices, nullptr, &max_index);
  if (max_index >= static_cast<double>(palette_rgba.size())) {
    throw std::runtime_error("PNG palette: index " + std::to_string(int(max_index)) +
                             " beyond its " + std::to_string(palette_rgba.size()) + " colours");
  }
  const cv::Mat1b pixels = indices.isContinuous() ? indices : indices.clone();
  return Encode(pixels, kIndexed, SPNG_DISABLE_FILTERING, [&](spng_ctx* ctx) {
    spng_plte plte{};
    spng_trns trns{};
    plte.n_entries = static_cast<std::uint32_t>(palette_rgba.size());
    trns.n_type3_entries = plte.n_entries;
    for (std::size_t k = 0; k < palette_rgba.size(); ++k) {
      plte.entries[k] = {palette_rgba[k][0], palette_rgba[k][1], palette_rgba[k][2], 0};
      trns.type3_alpha[k] = palette_rgba[k][3];
    }
    Check(spng_set_plte(ctx, &plte), "PNG palette");
    Check(spng_set_trns(ctx, &trns), "PNG transparency");
  });
}

}  // namespace fleetmerge
