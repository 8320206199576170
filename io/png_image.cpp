#include "io/png_image.hpp"

#include <spng.h>
#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/parallel.hpp"
#include "io/big_endian.hpp"

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

// Encoding. libspng deflates an image as one stream on one thread, and a site's 4000 x 4000
// preview is the longest step of writing its result set (docs/speed.md). So the scanlines are
// filtered and deflated here in bands of whole rows on threads, as pigz does: each band is a raw
// deflate stream that ends on a byte boundary (Z_SYNC_FLUSH; the last band Z_FINISH), so the bands
// concatenate into one zlib stream (RFC 1950: a 2-byte header, the deflate data, the Adler-32 of
// the uncompressed bytes, combined here from the bands' own). The settings are cv::imwrite's:
// zlib level 1 with the RLE strategy (its matches reach back one byte only, so a band loses
// nothing by not seeing the band before it). The bands depend on the image alone, so the bytes do
// not depend on the thread count.

// A band holds whole rows, at least this many bytes of filtered scanlines.
constexpr std::size_t kBandBytes = std::size_t{1} << 20;

// Zlib's header for a 32 KiB window and its "fastest" level, the one deflate writes at level 1
// (RFC 1950 section 2.2: (0x78 * 256 + 0x01) % 31 == 0).
constexpr char kZlibHeader[] = {0x78, 0x01};

void AppendBigEndian32(std::string& out, std::uint32_t v) {
  for (const int shift : {24, 16, 8, 0}) out += static_cast<char>((v >> shift) & 0xff);
}

// A PNG chunk (PNG specification section 5.3): length, type, data, CRC-32 of type and data.
void AppendChunk(std::string& png, const char (&type)[5], const std::string& data) {
  AppendBigEndian32(png, static_cast<std::uint32_t>(data.size()));
  const std::size_t typed = png.size();
  png.append(type, 4);
  png.append(data);
  const uLong crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(png.data() + typed),
                          static_cast<uInt>(png.size() - typed));
  AppendBigEndian32(png, static_cast<std::uint32_t>(crc));
}

struct DeflatedBand {
  std::string bytes;  // raw deflate data
  uLong adler = 1;    // Adler-32 of the band's filtered scanlines
  std::size_t length = 0;
};

// Rows [row_begin, row_end) filtered (PNG specification section 9: a filter-type byte, then the
// row; Sub subtracts the byte one pixel to the left) with 16-bit samples big-endian, deflated.
DeflatedBand DeflateRows(const cv::Mat& pixels, bool sub_filter, int row_begin, int row_end,
                         bool last) {
  const std::size_t sample_bytes = pixels.elemSize1();
  const std::size_t pixel_bytes = pixels.elemSize();
  const std::size_t row_bytes = pixel_bytes * static_cast<std::size_t>(pixels.cols);
  std::string filtered(static_cast<std::size_t>(row_end - row_begin) * (1 + row_bytes), '\0');
  auto* out = reinterpret_cast<std::uint8_t*>(filtered.data());
  for (int j = row_begin; j < row_end; ++j) {
    *out++ = sub_filter ? 1 : 0;
    if (sample_bytes == 2) {
      StoreBigEndian16(pixels.ptr<std::uint16_t>(j), row_bytes / 2, out);
    } else {
      std::copy_n(pixels.ptr<std::uint8_t>(j), row_bytes, out);
    }
    if (sub_filter) {  // from the right, so each byte still sees its raw left neighbour
      for (std::size_t k = row_bytes; k-- > pixel_bytes;) out[k] -= out[k - pixel_bytes];
    }
    out += row_bytes;
  }
  DeflatedBand band;
  band.length = filtered.size();
  band.adler = adler32(band.adler, reinterpret_cast<const Bytef*>(filtered.data()),
                       static_cast<uInt>(filtered.size()));
  z_stream z{};
  // Raw deflate (negative window bits): the zlib header and checksum are the whole image's.
  if (deflateInit2(&z, 1, Z_DEFLATED, -15, 8, Z_RLE) != Z_OK) {
    throw std::runtime_error("PNG encoding: zlib could not start a deflate stream");
  }
  const std::unique_ptr<z_stream, int (*)(z_stream*)> end_stream(&z, deflateEnd);
  // deflateBound covers Z_FINISH; a sync flush adds an empty stored block (5 bytes).
  band.bytes.resize(deflateBound(&z, static_cast<uLong>(filtered.size())) + 16);
  z.next_in = reinterpret_cast<Bytef*>(filtered.data());
  z.avail_in = static_cast<uInt>(filtered.size());
  z.next_out = reinterpret_cast<Bytef*>(band.bytes.data());
  z.avail_out = static_cast<uInt>(band.bytes.size());
  const int result = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
  if (result != (last ? Z_STREAM_END : Z_OK) || z.avail_in != 0 || z.avail_out == 0) {
    throw std::runtime_error("PNG encoding: zlib failed to deflate a band of rows");
  }
  // Held until every band is done: only its bytes, not deflateBound's room (a preview's 40 bands
  // would hold 40 MB of it).
  band.bytes.resize(band.bytes.size() - z.avail_out);
  band.bytes.shrink_to_fit();
  return band;
}

// The PNG of `pixels` (8- or 16-bit samples, continuous, in the PNG's channel order), with
// `before_image`'s chunks (PLTE, tRNS) between IHDR and the image data.
std::string Encode(const cv::Mat& pixels, std::uint8_t color_type, bool sub_filter,
                   const std::string& before_image, int threads) {
  CV_Assert(pixels.isContinuous());
  if (pixels.empty()) throw std::runtime_error("PNG encoding: an empty image (a PNG has pixels)");
  // The image's size must fit the band arithmetic's uInt lengths and the PNG's own limits.
  const std::size_t row_bytes = 1 + pixels.elemSize() * static_cast<std::size_t>(pixels.cols);
  const int rows_per_band =
      static_cast<int>(std::max<std::size_t>(1, (kBandBytes + row_bytes - 1) / row_bytes));
  if (row_bytes * static_cast<std::size_t>(rows_per_band) > (std::size_t{1} << 31)) {
    throw std::runtime_error("PNG encoding: rows of " + std::to_string(row_bytes) +
                             " bytes are too long");
  }
  const int band_count = std::max(1, (pixels.rows + rows_per_band - 1) / rows_per_band);
  std::vector<DeflatedBand> bands(static_cast<std::size_t>(band_count));
  ParallelFor(bands.size(), threads, [&](std::size_t b) {
    const int row_begin = static_cast<int>(b) * rows_per_band;
    const int row_end = std::min(pixels.rows, row_begin + rows_per_band);
    bands[b] = DeflateRows(pixels, sub_filter, row_begin, row_end, b + 1 == bands.size());
  });

  std::string header;  // IHDR (section 11.2.2): no interlacing
  AppendBigEndian32(header, static_cast<std::uint32_t>(pixels.cols));
  AppendBigEndian32(header, static_cast<std::uint32_t>(pixels.rows));
  header += static_cast<char>(pixels.depth() == CV_16U ? 16 : 8);
  header += static_cast<char>(color_type);
  header.append(3, '\0');  // deflate, adaptive filtering, no interlace
  std::size_t size = 8 + 25 + before_image.size() + 12;
  for (const DeflatedBand& band : bands) size += 12 + band.bytes.size();
  std::string png;
  png.reserve(size + 6);
  png.append("\x89PNG\r\n\x1a\n", 8);
  AppendChunk(png, "IHDR", header);
  png += before_image;
  // One IDAT a band: the zlib header opens the first, the image's Adler-32 closes the last.
  uLong adler = 1;
  for (std::size_t b = 0; b < bands.size(); ++b) {
    DeflatedBand& band = bands[b];
    adler = adler32_combine(adler, band.adler, static_cast<z_off_t>(band.length));
    if (b == 0) band.bytes.insert(0, kZlibHeader, 2);
    if (b + 1 == bands.size()) AppendBigEndian32(band.bytes, static_cast<std::uint32_t>(adler));
    AppendChunk(png, "IDAT", band.bytes);
    std::string().swap(band.bytes);
  }
  AppendChunk(png, "IEND", "");
  return png;
}

}  // namespace

std::string EncodePng(const cv::Mat& image, int threads) {
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
  // Sub: for a preview, half the bytes of no filtering.
  return Encode(rgb, type, /*sub_filter=*/true, "", threads);
}

std::string EncodeIndexedPng(const cv::Mat1b& indices, const std::vector<cv::Vec4b>& palette_rgba,
                             int threads) {
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
  std::string plte, trns;  // PLTE and tRNS chunks' data (sections 11.2.3, 11.3.2.1)
  for (const cv::Vec4b& rgba : palette_rgba) {
    plte.append(
        {static_cast<char>(rgba[0]), static_cast<char>(rgba[1]), static_cast<char>(rgba[2])});
    trns += static_cast<char>(rgba[3]);
  }
  std::string chunks;
  AppendChunk(chunks, "PLTE", plte);
  AppendChunk(chunks, "tRNS", trns);
  // No filtering: indices are no quantities to predict (the specification's encoder
  // recommendations, "Filter selection"; the 33 map images of scripts/cache_rerun_benchmark.sh
  // take 26 % fewer bytes and 42 % less time than with Sub).
  return Encode(pixels, kIndexed, /*sub_filter=*/false, chunks, threads);
}

}  // namespace fleetmerge
