#include "core/correlation_2d.hpp"

#include <gtest/gtest.h>

#include <random>

namespace fleetmerge {
namespace {

cv::Mat1f RandomImage(int rows, int cols, std::uint32_t seed) {
  cv::Mat1f m(rows, cols);
  cv::randu(m, 0.f, 1.f);
  cv::RNG rng(seed);
  rng.fill(m, cv::RNG::UNIFORM, 0.f, 1.f);
  return m;
}

TEST(FixedImageCorrelator, MatchesDirectSumsOnRandomImages) {
  const cv::Mat1f a = RandomImage(13, 17, 1);
  const FixedImageCorrelator correlator(a, cv::Size(9, 11));
  for (const cv::Size b_size : {cv::Size(9, 11), cv::Size(4, 3), cv::Size(1, 1)}) {
    const cv::Mat1f b = RandomImage(b_size.height, b_size.width, 2);
    const cv::Mat1f fft = correlator.Correlate(b);
    const cv::Mat1f direct = CrossCorrelateDirect(a, b);
    ASSERT_EQ(fft.size(), direct.size());
    EXPECT_LT(cv::norm(fft, direct, cv::NORM_INF), 1e-3) << b_size;
  }
}

TEST(FixedImageCorrelator, PeakIsAtTheTrueShift) {
  cv::Mat1f a = cv::Mat1f::zeros(40, 50);
  cv::Mat1f b = cv::Mat1f::zeros(10, 12);
  cv::RNG rng(3);
  rng.fill(b, cv::RNG::UNIFORM, 0.f, 1.f);
  b.copyTo(a(cv::Rect(31, 22, 12, 10)));  // b sits at dx = 31, dy = 22 in a
  const cv::Mat1f r = FixedImageCorrelator(a, b.size()).Correlate(b);
  cv::Point max_loc;
  cv::minMaxLoc(r, nullptr, nullptr, nullptr, &max_loc);
  EXPECT_EQ(max_loc.x - (b.cols - 1), 31);
  EXPECT_EQ(max_loc.y - (b.rows - 1), 22);
}

}  // namespace
}  // namespace fleetmerge
