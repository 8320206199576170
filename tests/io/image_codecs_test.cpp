// io/pnm_image and io/png_image against an independent decoder and encoder: OpenCV's imgcodecs
// (which the loader used before; tests only). Seeded random images of every Netpbm kind and
// maxval class and every PNG layout imwrite makes must decode to the same samples, and what we
// encode must decode (by OpenCV) to what we encoded.
#include <gtest/gtest.h>

#include <cstring>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <string>

#include "io/png_image.hpp"
#include "io/pnm_header.hpp"
#include "io/pnm_image.hpp"
#include "tests/io/io_test_util.hpp"
#include "tests/support/shared_data.hpp"

namespace fleetmerge {
namespace {

namespace fs = std::filesystem;
namespace ft = fleetmerge::testing;

// A Netpbm file written from the format's definition: header, then ASCII decimal samples or
// binary samples (16-bit big-endian), PBM bits packed most significant first per row.
std::string NetpbmBytes(char kind, int width, int height, int maxval, std::mt19937& rng) {
  const bool bitmap = kind == '1' || kind == '4';
  const int channels = kind == '3' || kind == '6' ? 3 : 1;
  std::string out = std::string("P") + kind + "\n# random\n" + std::to_string(width) + " " +
                    std::to_string(height) + "\n" + (bitmap ? "" : std::to_string(maxval) + "\n");
  std::uniform_int_distribution<int> sample(0, bitmap ? 1 : maxval);
  for (int r = 0; r < height; ++r) {
    unsigned bits = 0;
    for (int c = 0; c < width * channels; ++c) {
      const int v = sample(rng);
      if (kind <= '3') {
        out += std::to_string(v) + (c % 17 == 16 ? "\n" : " ");
      } else if (kind == '4') {
        bits |= static_cast<unsigned>(v) << (7 - c % 8);
        if (c % 8 == 7 || c == width - 1) {
          out += static_cast<char>(bits);
          bits = 0;
        }
      } else if (maxval > 255) {
        out += static_cast<char>(v >> 8);
        out += static_cast<char>(v & 0xff);
      } else {
        out += static_cast<char>(v);
      }
    }
    if (kind <= '3') out += "\n";
  }
  return out;
}

cv::Mat ReadWithOpenCv(const fs::path& path) {
  return cv::imread(path.string(), cv::IMREAD_UNCHANGED);
}

void ExpectSameSamples(const cv::Mat& ours, const cv::Mat& reference, const std::string& what) {
  ASSERT_EQ(ours.type(), reference.type()) << what;
  ASSERT_EQ(ours.size(), reference.size()) << what;
  EXPECT_EQ(cv::norm(ours, reference, cv::NORM_INF), 0.0) << what;
}

TEST(ImageCodecsTest, NetpbmDecodesLikeOpenCv) {
  std::mt19937 rng(13);
  const fs::path dir = ft::MakeTempDir("codecs_netpbm");
  int cases = 0;
  for (const char kind : {'1', '2', '3', '4', '5', '6'}) {
    const bool bitmap = kind == '1' || kind == '4';
    for (const int maxval : {1, 7, 100, 254, 255, 256, 1000, 65535}) {
      if (bitmap && maxval != 1) continue;
      for (int trial = 0; trial < 3; ++trial) {
        const int width = std::uniform_int_distribution<int>(1, 37)(rng);
        const int height = std::uniform_int_distribution<int>(1, 23)(rng);
        const std::string bytes = NetpbmBytes(kind, width, height, maxval, rng);
        const fs::path path = dir / ("image" + std::to_string(cases++) + ".pnm");
        ft::WriteFile(path, bytes);
        const std::optional<PnmHeader> header = ReadPnmHeader(path);
        ASSERT_TRUE(header);
        const cv::Mat ours = DecodePnm(bytes, *header);
        cv::Mat reference = ReadWithOpenCv(path);
        ASSERT_FALSE(reference.empty()) << path;
        if (reference.channels() == 3) cv::cvtColor(reference, reference, cv::COLOR_BGR2RGB);
        if (kind >= '5' && maxval < 255) {
          // OpenCV returns binary 8-bit samples raw when maxval < 255 (its ASCII path rescales
          // them); the Netpbm definition, and DecodePnm, make maxval white in both.
          cv::Mat1b samples = reference.reshape(1);  // shares reference's pixels
          for (std::uint8_t& v : samples) v = static_cast<std::uint8_t>(v * 255 / maxval);
        }
        ExpectSameSamples(ours, reference,
                          std::string("P") + kind + " maxval " + std::to_string(maxval));
      }
    }
  }
  EXPECT_EQ(cases, 2 * 3 + 4 * 8 * 3);
}

TEST(ImageCodecsTest, AsciiSamplesAboveMaxvalCountAsMaxval) {
  const std::string bytes = "P2\n3 1\n100\n0 150 100\n";
  const fs::path path = ft::MakeTempDir("codecs_clamp") / "m.pgm";
  ft::WriteFile(path, bytes);
  const cv::Mat ours = DecodePnm(bytes, *ReadPnmHeader(path));
  EXPECT_EQ(ours.at<std::uint8_t>(0, 1), 255);
  EXPECT_EQ(ours.at<std::uint8_t>(0, 2), 255);
}

TEST(ImageCodecsTest, NetpbmRasterErrorsSayWhat) {
  const auto error_of = [](const std::string& bytes) {
    const fs::path path = ft::MakeTempDir("codecs_errors") / "m.pgm";
    ft::WriteFile(path, bytes);
    try {
      DecodePnm(bytes, *ReadPnmHeader(path));
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(error_of("P2\n2 2\n255\n1 2 3\n").find("ends after 3 of the 4 samples"),
            std::string::npos);
  EXPECT_NE(error_of("P2\n2 1\n255\n1 x\n").find("sample 2 of 2 is 'x'"), std::string::npos);
  EXPECT_NE(error_of("P2\n2 1\n255\n1 2x\n").find("runs into 'x'"), std::string::npos);
  EXPECT_NE(error_of("P5\n4 4\n255\nabc").find("holds 3 bytes"), std::string::npos);
}

// Random samples of `type`; alpha (channel 4) includes 0 so transparency is exercised.
cv::Mat RandomImage(int type, std::mt19937& rng) {
  const int rows = std::uniform_int_distribution<int>(1, 31)(rng);
  const int cols = std::uniform_int_distribution<int>(1, 45)(rng);
  cv::Mat image(rows, cols, type);
  cv::randu(image, 0, CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256);
  return image;
}

// OpenCV's grey/BGR/BGRA as the R, G, B, A that DecodePng returns for non-8-bit-grey PNGs.
cv::Mat AsRgba(const cv::Mat& opencv) {
  cv::Mat rgba;
  if (opencv.channels() == 1) cv::cvtColor(opencv, rgba, cv::COLOR_GRAY2RGBA);
  if (opencv.channels() == 3) cv::cvtColor(opencv, rgba, cv::COLOR_BGR2RGBA);
  if (opencv.channels() == 4) cv::cvtColor(opencv, rgba, cv::COLOR_BGRA2RGBA);
  return rgba;
}

TEST(ImageCodecsTest, PngDecodesLikeOpenCv) {
  std::mt19937 rng(7);
  const fs::path dir = ft::MakeTempDir("codecs_png");
  for (const int type : {CV_8UC1, CV_16UC1, CV_8UC3, CV_16UC3, CV_8UC4, CV_16UC4}) {
    for (int trial = 0; trial < 3; ++trial) {
      const cv::Mat written = RandomImage(type, rng);
      const fs::path path =
          dir / ("t" + std::to_string(type) + "_" + std::to_string(trial) + ".png");
      ASSERT_TRUE(cv::imwrite(path.string(), written));
      const cv::Mat reference = ReadWithOpenCv(path);
      const cv::Mat ours = DecodePng(ft::ReadFile(path));
      ExpectSameSamples(ours, type == CV_8UC1 ? reference : AsRgba(reference),
                        "PNG of type " + std::to_string(type));
    }
  }
}

TEST(ImageCodecsTest, OneBitPngIsScaledTo255) {
  std::mt19937 rng(3);
  cv::Mat1b bits = RandomImage(CV_8UC1, rng);
  bits = (bits > 127) / 255 * 255;
  const fs::path path = ft::MakeTempDir("codecs_png_1bit") / "bits.png";
  ASSERT_TRUE(cv::imwrite(path.string(), bits, {cv::IMWRITE_PNG_BILEVEL, 1}));
  const cv::Mat ours = DecodePng(ft::ReadFile(path));
  ExpectSameSamples(ours, AsRgba(ReadWithOpenCv(path)), "1-bit PNG");
  ExpectSameSamples(ours, AsRgba(bits), "1-bit PNG against what was written");
}

TEST(ImageCodecsTest, EncodedImagesDecodeToThemselvesInOpenCv) {
  std::mt19937 rng(11);
  for (const int type : {CV_8UC1, CV_16UC1, CV_8UC3, CV_16UC3, CV_8UC4, CV_16UC4}) {
    const cv::Mat image = RandomImage(type, rng);
    const std::string png = EncodePng(image);
    const cv::Mat back =
        cv::imdecode(std::vector<uchar>(png.begin(), png.end()), cv::IMREAD_UNCHANGED);
    ExpectSameSamples(back, image, "PNG of type " + std::to_string(type));
    if (image.channels() != 1) continue;
    const std::string pgm = EncodePgm(image);
    const cv::Mat pgm_back =
        cv::imdecode(std::vector<uchar>(pgm.begin(), pgm.end()), cv::IMREAD_UNCHANGED);
    ExpectSameSamples(pgm_back, image, "PGM of type " + std::to_string(type));
  }
}

TEST(ImageCodecsTest, IndexedPngDecodesToItsPaletteColoursInOpenCvAndOurs) {
  std::mt19937 rng(17);
  // Opaque, transparent and half-transparent entries; indices spread over all of them.
  const std::vector<cv::Vec4b> palette_rgba = {cv::Vec4b(0, 0, 0, 0), cv::Vec4b(235, 235, 235, 255),
                                               cv::Vec4b(0, 0, 0, 255),
                                               cv::Vec4b(10, 200, 30, 128)};
  cv::Mat1b indices(37, 53);
  for (auto& v : indices) v = static_cast<std::uint8_t>(rng() % palette_rgba.size());
  cv::Mat4b want_bgra(indices.size());
  for (int r = 0; r < indices.rows; ++r) {
    for (int c = 0; c < indices.cols; ++c) {
      const cv::Vec4b rgba = palette_rgba[indices(r, c)];
      want_bgra(r, c) = cv::Vec4b(rgba[2], rgba[1], rgba[0], rgba[3]);
    }
  }
  const std::string png = EncodeIndexedPng(indices, palette_rgba);
  const cv::Mat back =
      cv::imdecode(std::vector<uchar>(png.begin(), png.end()), cv::IMREAD_UNCHANGED);
  ExpectSameSamples(back, want_bgra, "palette PNG in OpenCV");
  ExpectSameSamples(DecodePng(png), AsRgba(want_bgra), "palette PNG in ours");
  // An index beyond the palette is refused, not written.
  indices(3, 4) = 4;
  EXPECT_THROW(EncodeIndexedPng(indices, palette_rgba), std::runtime_error);
  EXPECT_THROW(EncodeIndexedPng(indices, {}), std::runtime_error);
}

// How many IDAT chunks a PNG has (PNG specification section 5.3: length, type, data, CRC).
int IdatChunks(const std::string& png) {
  int count = 0;
  for (std::size_t at = 8; at + 12 <= png.size();) {
    std::uint32_t length = 0;
    for (int k = 0; k < 4; ++k) length = length << 8 | static_cast<std::uint8_t>(png[at + k]);
    count += png.compare(at + 4, 4, "IDAT") == 0;
    at += 12 + std::size_t{length};
  }
  return count;
}

// A map-like image: runs of equal pixels (what compresses) with random noise in every 7th row,
// so that a band that lost its bytes or its place would show.
cv::Mat MapLikeImage(int rows, int cols, int type, std::mt19937& rng) {
  cv::Mat image(rows, cols, type);
  cv::randu(image, 0, CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256);
  for (int r = 0; r < rows; ++r) {
    if (r % 7 == 0) continue;
    const int run = std::uniform_int_distribution<int>(1, 300)(rng);
    for (int c = run; c < cols; ++c) {
      std::memcpy(image.ptr(r, c), image.ptr(r, c - c % run), image.elemSize());
    }
  }
  return image;
}

TEST(ImageCodecsTest, LargePngsAreDeflatedInBandsThatDecodeAsOneImageOnAnyThreadCount) {
  std::mt19937 rng(23);
  // Several 1 MiB bands each: 4000 x 700 RGB is 8.4 MB of scanlines, a preview's size class.
  for (const int type : {CV_8UC3, CV_16UC1, CV_8UC1, CV_16UC4}) {
    const cv::Mat image =
        MapLikeImage(700, 4000 / static_cast<int>(CV_ELEM_SIZE(type)) * 3, type, rng);
    const std::string one_thread = EncodePng(image, 1);
    EXPECT_GE(IdatChunks(one_thread), 2) << "type " << type << ": expected several bands";
    EXPECT_EQ(EncodePng(image, 2), one_thread) << "type " << type;
    EXPECT_EQ(EncodePng(image, 0), one_thread) << "type " << type;
    const cv::Mat back = cv::imdecode(std::vector<uchar>(one_thread.begin(), one_thread.end()),
                                      cv::IMREAD_UNCHANGED);
    ExpectSameSamples(back, image, "banded PNG of type " + std::to_string(type) + " in OpenCV");
  }
  const std::vector<cv::Vec4b> palette_rgba = {cv::Vec4b(0, 0, 0, 0), cv::Vec4b(235, 235, 235, 255),
                                               cv::Vec4b(0, 0, 0, 255)};
  cv::Mat1b indices = MapLikeImage(1500, 2100, CV_8UC1, rng);
  for (auto& v : indices) v %= 3;
  const std::string png = EncodeIndexedPng(indices, palette_rgba, 2);
  EXPECT_GE(IdatChunks(png), 3);
  EXPECT_EQ(EncodeIndexedPng(indices, palette_rgba, 1), png);
  cv::Mat4b want_rgba(indices.size());
  for (int r = 0; r < indices.rows; ++r) {
    for (int c = 0; c < indices.cols; ++c) want_rgba(r, c) = palette_rgba[indices(r, c)];
  }
  ExpectSameSamples(DecodePng(png), want_rgba, "banded palette PNG in ours");
  cv::Mat want_bgra;
  cv::cvtColor(want_rgba, want_bgra, cv::COLOR_RGBA2BGRA);
  ExpectSameSamples(cv::imdecode(std::vector<uchar>(png.begin(), png.end()), cv::IMREAD_UNCHANGED),
                    want_bgra, "banded palette PNG in OpenCV");
}

TEST(ImageCodecsTest, PngErrorsCarryLibspngsReason) {
  std::mt19937 rng(5);
  const cv::Mat image = RandomImage(CV_8UC1, rng);
  std::string png = EncodePng(image);
  png.resize(png.size() - 20);  // cut inside the image data
  try {
    DecodePng(png);
    FAIL() << "a cut PNG decoded";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("PNG"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fleetmerge
