#include "io/image_header.hpp"

#include <array>
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "core/error.hpp"
#include "io/pnm_header.hpp"

namespace fleetmerge {
namespace fs = std::filesystem;
namespace {

constexpr std::array<unsigned char, 8> kPngSignature = {0x89, 'P',  'N',  'G',
                                                        '\r', '\n', 0x1a, '\n'};

[[noreturn]] void Fail(const fs::path& image_path, const fs::path& yaml_path,
                       const std::string& what) {
  throw Error(image_path.string() + ": " + what + " (the image of map " + yaml_path.string() + ")");
}

std::string HexBytes(const std::string& bytes) {
  std::string out;
  for (std::size_t i = 0; i < bytes.size() && i < 8; ++i) {
    std::array<char, 4> hex{};
    std::snprintf(hex.data(), hex.size(), "%02x", static_cast<unsigned char>(bytes[i]));
    out += (i > 0 ? " " : "") + std::string(hex.data());
  }
  return out;
}

std::uint32_t BigEndian32(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t i = 0; i < 4; ++i)
    value = value << 8 | static_cast<unsigned char>(bytes[at + i]);
  return value;
}

// PNG: the signature, then the IHDR chunk (length 13, "IHDR", width, height: big-endian).
ImageHeaderSize PngSize(const std::string& head, const fs::path& image_path,
                        const fs::path& yaml_path) {
  if (head.size() < 24 || head.compare(12, 4, "IHDR") != 0) {
    Fail(image_path, yaml_path, "is a truncated or corrupt PNG (no IHDR header chunk)");
  }
  return {BigEndian32(head, 16), BigEndian32(head, 20)};
}

// Binary Netpbm: bytes of pixel data the header announces.
std::optional<std::int64_t> PixelBytes(const PnmHeader& header) {
  const std::int64_t w = header.width, h = header.height;
  const std::int64_t sample_bytes = header.maxval > 255 ? 2 : 1;
  switch (header.kind) {
    case '4':
      return (w + 7) / 8 * h;
    case '5':
      return w * h * sample_bytes;
    case '6':
      return w * h * 3 * sample_bytes;
    default:
      return std::nullopt;  // ASCII: no fixed size
  }
}

// Reads a Netpbm header; `pixel_bytes` and `data_offset` are set for binary files.
ImageHeaderSize PnmSize(const fs::path& image_path, const fs::path& yaml_path,
                        std::optional<std::int64_t>& pixel_bytes, std::int64_t& data_offset) {
  const std::optional<PnmHeader> header = ReadPnmHeader(image_path);
  if (!header) Fail(image_path, yaml_path, "has a malformed or incomplete Netpbm (PGM) header");
  if (header->maxval < 1 || header->maxval > 65535) {
    Fail(image_path, yaml_path,
         "has maxval " + std::to_string(header->maxval) + ", expected 1..65535");
  }
  pixel_bytes = PixelBytes(*header);
  data_offset = header->data_offset;
  return {header->width, header->height};
}

}  // namespace

ImageHeaderSize CheckImageHeader(const fs::path& image_path, const fs::path& yaml_path,
                                 std::int64_t max_cells) {
  std::error_code ec;
  const std::uintmax_t file_bytes = fs::file_size(image_path, ec);
  if (ec) Fail(image_path, yaml_path, "cannot be read: " + ec.message());
  if (file_bytes == 0)
    Fail(image_path, yaml_path, "is empty (0 bytes), expected a PGM or PNG image");
  std::ifstream in(image_path, std::ios::binary);
  std::string head(24, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  ImageHeaderSize size;
  std::optional<std::int64_t> pixel_bytes;  // binary Netpbm only
  std::int64_t data_offset = 0;
  if (head.size() >= 8 &&
      std::equal(kPngSignature.begin(), kPngSignature.end(), head.begin(),
                 [](unsigned char a, char b) { return a == static_cast<unsigned char>(b); })) {
    size = PngSize(head, image_path, yaml_path);
  } else if (head.size() >= 2 && head[0] == 'P' && head[1] >= '1' && head[1] <= '6') {
    size = PnmSize(image_path, yaml_path, pixel_bytes, data_offset);
  } else {
    Fail(image_path, yaml_path,
         "is not a PGM or PNG image (it starts with bytes " + HexBytes(head) + ")");
  }
  if (size.width == 0 || size.height == 0) {
    Fail(image_path, yaml_path,
         "is an empty image (" + std::to_string(size.width) + " x " + std::to_string(size.height) +
             " pixels)");
  }
  // PNG sizes reach 2^32 - 1 a side: the product fits in 64 unsigned bits, not in int64.
  const auto cells =
      static_cast<unsigned long long>(size.width) * static_cast<unsigned long long>(size.height);
  if (max_cells < 0 || cells > static_cast<unsigned long long>(max_cells)) {
    Fail(image_path, yaml_path,
         "is " + std::to_string(size.width) + " x " + std::to_string(size.height) + " = " +
             std::to_string(cells) + " cells, more than the limit of " + std::to_string(max_cells) +
             " cells (raise it with --max-map-cells or the job key max_map_cells)");
  }
  if (pixel_bytes) {  // OpenCV would report a short file on stderr only
    const std::int64_t present =
        data_offset < 0 ? 0 : static_cast<std::int64_t>(file_bytes) - data_offset;
    if (present < *pixel_bytes) {
      Fail(image_path, yaml_path,
           "is truncated: its header announces " + std::to_string(size.width) + " x " +
               std::to_string(size.height) + " pixels (" + std::to_string(*pixel_bytes) +
               " bytes of pixel data) but only " + std::to_string(present) + " bytes follow it");
    }
  }
  return size;
}

}  // namespace fleetmerge
