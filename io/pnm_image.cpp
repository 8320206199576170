#include "io/pnm_image.hpp"

#include <array>
#include <cctype>
#include <cstdint>
#include <stdexcept>

#include "io/big_endian.hpp"

namespace fleetmerge {
namespace {

int ChannelsOf(char kind) { return kind == '3' || kind == '6' ? 3 : 1; }

// Reads the ASCII raster: whitespace-separated decimal samples ('#' comments allowed, as in the
// header); in P1 every '0' or '1' character is a sample, separated or not (Netpbm's rule).
class AsciiSamples {
 public:
  AsciiSamples(const std::string& bytes, std::size_t at, bool bits)
      : bytes_(bytes), at_(at), bits_(bits) {}

  // The next sample clamped to `maxval`; throws when the raster ends or holds something else.
  int Next(int maxval, std::int64_t index, std::int64_t count) {
    SkipSpaceAndComments();
    if (at_ >= bytes_.size()) {
      throw std::runtime_error("its ASCII pixel data ends after " + std::to_string(index) +
                               " of the " + std::to_string(count) +
                               " samples its header announces");
    }
    const char first = bytes_[at_];
    if (std::isdigit(static_cast<unsigned char>(first)) == 0) {
      throw std::runtime_error("ASCII sample " + std::to_string(index + 1) + " of " +
                               std::to_string(count) + " is '" + Printable(first) +
                               "', expected a decimal number");
    }
    if (bits_) {
      ++at_;
      return first == '0' ? 0 : (first == '1' ? 1 : maxval);
    }
    long long value = 0;
    while (at_ < bytes_.size() && std::isdigit(static_cast<unsigned char>(bytes_[at_])) != 0) {
      value = std::min<long long>(value * 10 + (bytes_[at_] - '0'), 1LL << 40);
      ++at_;
    }
    if (at_ < bytes_.size() && !IsSeparator(bytes_[at_])) {
      throw std::runtime_error("ASCII sample " + std::to_string(index + 1) + " of " +
                               std::to_string(count) + " runs into '" + Printable(bytes_[at_]) +
                               "', expected a decimal number");
    }
    return static_cast<int>(std::min<long long>(value, maxval));
  }

 private:
  static bool IsSeparator(char c) {
    return std::isspace(static_cast<unsigned char>(c)) != 0 || c == '#';
  }
  static std::string Printable(char c) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isprint(u) != 0) return std::string(1, c);
    std::array<char, 8> hex{};
    std::snprintf(hex.data(), hex.size(), "\\x%02x", u);
    return hex.data();
  }
  void SkipSpaceAndComments() {
    while (at_ < bytes_.size()) {
      const char c = bytes_[at_];
      if (c == '#') {
        while (at_ < bytes_.size() && bytes_[at_] != '\n' && bytes_[at_] != '\r') ++at_;
      } else if (std::isspace(static_cast<unsigned char>(c)) != 0) {
        ++at_;
      } else {
        return;
      }
    }
  }

  const std::string& bytes_;
  std::size_t at_;
  bool bits_;
};

// Sample -> 8-bit value: round-down(v * 255 / maxval), PBM inverted (1 is black).
std::array<std::uint8_t, 256> EightBitTable(const PnmHeader& header) {
  std::array<std::uint8_t, 256> table{};
  const bool bitmap = header.kind == '1' || header.kind == '4';
  for (int v = 0; v < 256; ++v) {
    const int clamped = std::min(v, header.maxval);
    const int value = clamped * 255 / header.maxval;
    table[v] = static_cast<std::uint8_t>(bitmap ? 255 - value : value);
  }
  return table;
}

void DecodeBinary(const std::string& bytes, std::size_t at, const PnmHeader& header,
                  cv::Mat& image) {
  const std::size_t row_samples = static_cast<std::size_t>(image.cols) * image.channels();
  if (header.kind == '4') {  // rows of packed bits, most significant first, padded to bytes
    const std::size_t row_bytes = (static_cast<std::size_t>(image.cols) + 7) / 8;
    for (int r = 0; r < image.rows; ++r) {
      const auto* in = reinterpret_cast<const unsigned char*>(bytes.data() + at + r * row_bytes);
      std::uint8_t* out = image.ptr<std::uint8_t>(r);
      for (int c = 0; c < image.cols; ++c) out[c] = (in[c / 8] >> (7 - c % 8)) & 1 ? 0 : 255;
    }
    return;
  }
  if (image.depth() == CV_8U) {
    const std::array<std::uint8_t, 256> table = EightBitTable(header);
    for (int r = 0; r < image.rows; ++r) {
      const auto* in = reinterpret_cast<const unsigned char*>(bytes.data() + at + r * row_samples);
      std::uint8_t* out = image.ptr<std::uint8_t>(r);
      for (std::size_t i = 0; i < row_samples; ++i) out[i] = table[in[i]];
    }
    return;
  }
  for (int r = 0; r < image.rows; ++r) {  // 16-bit samples are big-endian
    const auto* in =
        reinterpret_cast<const unsigned char*>(bytes.data() + at + 2 * r * row_samples);
    std::uint16_t* out = image.ptr<std::uint16_t>(r);
    for (std::size_t i = 0; i < row_samples; ++i) {
      const int value = in[2 * i] << 8 | in[2 * i + 1];
      out[i] = static_cast<std::uint16_t>(std::min(value, header.maxval));
    }
  }
}

void DecodeAscii(const std::string& bytes, std::size_t at, const PnmHeader& header,
                 cv::Mat& image) {
  AsciiSamples samples(bytes, at, header.kind == '1');
  const std::int64_t row_samples = static_cast<std::int64_t>(image.cols) * image.channels();
  const std::int64_t count = row_samples * image.rows;
  const std::array<std::uint8_t, 256> table = EightBitTable(header);
  for (int r = 0; r < image.rows; ++r) {
    for (std::int64_t i = 0; i < row_samples; ++i) {
      const int value = samples.Next(header.maxval, r * row_samples + i, count);
      if (image.depth() == CV_8U) {
        image.ptr<std::uint8_t>(r)[i] = table[value];
      } else {
        image.ptr<std::uint16_t>(r)[i] = static_cast<std::uint16_t>(value);
      }
    }
  }
}

}  // namespace

cv::Mat DecodePnm(const std::string& bytes, const PnmHeader& header) {
  if (header.data_offset < 0 || header.width <= 0 || header.height <= 0 || header.maxval < 1 ||
      header.maxval > 65535) {
    throw std::runtime_error("its Netpbm header is incomplete or invalid");
  }
  const int depth = header.maxval > 255 ? CV_16U : CV_8U;
  cv::Mat image(header.height, header.width, CV_MAKETYPE(depth, ChannelsOf(header.kind)));
  const auto at = static_cast<std::size_t>(header.data_offset);
  if (header.kind >= '4') {
    const std::size_t row_bytes = header.kind == '4'
                                      ? (static_cast<std::size_t>(header.width) + 7) / 8
                                      : image.cols * image.elemSize();
    const std::size_t need = row_bytes * static_cast<std::size_t>(header.height);
    if (at > bytes.size() || bytes.size() - at < need) {
      throw std::runtime_error("its binary pixel data holds " +
                               std::to_string(at > bytes.size() ? 0 : bytes.size() - at) +
                               " bytes, its header announces " + std::to_string(need));
    }
    DecodeBinary(bytes, at, header, image);
  } else {
    DecodeAscii(bytes, at, header, image);
  }
  return image;
}

std::string EncodePgm(const cv::Mat& image) {
  CV_Assert(image.channels() == 1 && (image.depth() == CV_8U || image.depth() == CV_16U));
  const bool deep = image.depth() == CV_16U;
  std::string out = "P5\n" + std::to_string(image.cols) + " " + std::to_string(image.rows) + "\n" +
                    (deep ? "65535" : "255") + "\n";
  const std::size_t header_bytes = out.size();
  const std::size_t row_bytes = static_cast<std::size_t>(image.cols) * (deep ? 2 : 1);
  out.resize(header_bytes + row_bytes * image.rows);
  for (int r = 0; r < image.rows; ++r) {
    char* dst = &out[header_bytes + r * row_bytes];
    if (!deep) {
      std::copy_n(image.ptr<char>(r), row_bytes, dst);
      continue;
    }
    StoreBigEndian16(image.ptr<std::uint16_t>(r), static_cast<std::size_t>(image.cols),
                     reinterpret_cast<std::uint8_t*>(dst));
  }
  return out;
}

}  // namespace fleetmerge
