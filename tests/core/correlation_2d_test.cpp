#include "core/correlation_2d.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/error.hpp"

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
  FixedImageCorrelator correlator(a, cv::Size(9, 11));
  for (const cv::Size b_size : {cv::Size(9, 11), cv::Size(4, 3), cv::Size(1, 1)}) {
    const cv::Mat1f b = RandomImage(b_size.height, b_size.width, 2);
    const cv::Mat1f fft = correlator.Correlate(b);
    const cv::Mat1f direct = CrossCorrelateDirect(a, b);
    ASSERT_EQ(fft.size(), direct.size());
    EXPECT_LT(cv::norm(fft, direct, cv::NORM_INF), 1e-3) << b_size;
  }
}

TEST(FixedImageCorrelator, LayerSumMatchesSumOfDirectCorrelations) {
  const std::vector<cv::Mat1f> a = {RandomImage(13, 17, 4), RandomImage(13, 17, 5)};
  const std::vector<cv::Mat1f> b = {RandomImage(6, 8, 6), RandomImage(6, 8, 7)};
  FixedImageCorrelator correlator(a, cv::Size(9, 11));
  const cv::Mat1f direct = CrossCorrelateDirect(a[0], b[0]) + CrossCorrelateDirect(a[1], b[1]);
  EXPECT_LT(cv::norm(correlator.CorrelateSum(b), direct, cv::NORM_INF), 1e-3);
  EXPECT_THROW(correlator.CorrelateSum({b[0]}), Error);  // one B per fixed layer
  EXPECT_THROW(correlator.Correlate(b[0]), Error);
  EXPECT_THROW(
      FixedImageCorrelator(std::vector<cv::Mat1f>{a[0], RandomImage(3, 3, 8)}, cv::Size(2, 2)),
      Error);
}

TEST(FixedImageCorrelator, HalfTurnMatchesDirectSumsOfFlippedImages) {
  const std::vector<cv::Mat1f> a = {RandomImage(13, 17, 8), RandomImage(13, 17, 9)};
  FixedImageCorrelator correlator(a, cv::Size(9, 11));
  for (const cv::Size b_size : {cv::Size(9, 11), cv::Size(5, 3), cv::Size(1, 1)}) {
    const std::vector<cv::Mat1f> b = {RandomImage(b_size.height, b_size.width, 10),
                                      RandomImage(b_size.height, b_size.width, 11)};
    std::vector<cv::Mat1f> b_flipped(2);
    for (int k = 0; k < 2; ++k) cv::flip(b[k], b_flipped[k], -1);  // both axes
    cv::Mat1f r, r_half_turn;
    correlator.CorrelateSumAndHalfTurn(b, &r, &r_half_turn);
    const cv::Mat1f direct = CrossCorrelateDirect(a[0], b[0]) + CrossCorrelateDirect(a[1], b[1]);
    const cv::Mat1f direct_flipped =
        CrossCorrelateDirect(a[0], b_flipped[0]) + CrossCorrelateDirect(a[1], b_flipped[1]);
    ASSERT_EQ(r_half_turn.size(), direct_flipped.size());
    EXPECT_LT(cv::norm(r, direct, cv::NORM_INF), 1e-3) << b_size;
    EXPECT_LT(cv::norm(r_half_turn, direct_flipped, cv::NORM_INF), 1e-3) << b_size;
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
