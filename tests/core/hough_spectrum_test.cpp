#include "core/hough_spectrum.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/circular_correlation.hpp"

namespace fleetmerge {
namespace {

std::vector<Eigen::Vector2f> RandomPoints(int n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 60.f);
  std::vector<Eigen::Vector2f> points;
  for (int k = 0; k < n; ++k) points.emplace_back(u(rng), u(rng));
  return points;
}

// An L-shaped room corner: two walls, at angle `yaw` about (30, 30).
std::vector<Eigen::Vector2f> Walls(double yaw) {
  std::vector<Eigen::Vector2f> points;
  const Eigen::Vector2f c(30.f, 30.f);
  const float cy = std::cos(yaw), sy = std::sin(yaw);
  auto add = [&](float x, float y) {
    points.emplace_back(c.x() + cy * x - sy * y, c.y() + sy * x + cy * y);
  };
  for (int k = -25; k <= 25; ++k) add(float(k), -10.f);  // long wall
  for (int k = -10; k <= 8; ++k) add(-25.f, float(k));   // short wall
  return points;
}

TEST(HoughTransform, MatchesDirectVotingOracle) {
  // 300 points, and 4099: several chunks of the vote loop and a remainder of 3.
  for (const int count : {300, 4099}) {
    const auto points = RandomPoints(count, 1);
    HoughOptions options;
    options.n_theta = 90;
    options.rho_step_cells = 1.5;
    const HoughTransform h = ComputeHoughTransform(points, options);
    // Direct voting: every point, every theta, rho from Eq. (2) about the same centre.
    std::vector<int> expected(h.votes.size(), 0);
    for (const auto& p : points) {
      for (int k = 0; k < h.n_theta; ++k) {
        const double rho = (p.x() - h.center.x()) * std::cos(h.theta_rad(k)) +
                           (p.y() - h.center.y()) * std::sin(h.theta_rad(k));
        const int i = static_cast<int>(std::floor((rho - h.rho_min) / h.rho_step));
        ASSERT_GE(i, 0);
        ASSERT_LT(i, h.n_rho);
        ++expected[k * h.n_rho + i];
      }
    }
    int mismatches = 0;  // float vs double rounding may move a vote that lies on a bin edge
    for (std::size_t n = 0; n < expected.size(); ++n) mismatches += expected[n] != h.votes[n];
    EXPECT_LE(mismatches, 4 * count / 300) << count << " points";
    for (int k = 0; k < h.n_theta; ++k) {
      int column_sum = 0;
      for (int i = 0; i < h.n_rho; ++i) column_sum += h.at(i, k);
      EXPECT_EQ(column_sum, count) << "each point votes exactly once per column";
    }
  }
}

TEST(HoughSpectrum, IsSumOfSquaredColumns) {
  const HoughTransform h = ComputeHoughTransform(RandomPoints(50, 2), HoughOptions{});
  const auto hs = HoughSpectrum(h);
  for (int k = 0; k < h.n_theta; k += 17) {
    double sum = 0.0;
    for (int i = 0; i < h.n_rho; ++i) sum += double(h.at(i, k)) * h.at(i, k);
    EXPECT_DOUBLE_EQ(hs[k], sum);
  }
}

TEST(HoughSpectrum, IsInvariantToTranslation) {
  auto points = Walls(0.3);
  const auto hs = HoughSpectrum(ComputeHoughTransform(points, HoughOptions{}));
  for (auto& p : points) p += Eigen::Vector2f(13.f, -7.f);
  const auto moved = HoughSpectrum(ComputeHoughTransform(points, HoughOptions{}));
  for (std::size_t k = 0; k < hs.size(); ++k) EXPECT_NEAR(moved[k], hs[k], 0.05 * hs[k] + 20.0);
}

TEST(HoughSpectrum, CorrelationPeakRecoversRotation) {
  HoughOptions options;
  options.n_theta = 180;
  for (const double yaw_deg : {0.0, 17.0, 90.0, 135.0, 179.0}) {
    const auto hs_a = HoughSpectrum(ComputeHoughTransform(Walls(yaw_deg * M_PI / 180), options));
    const auto hs_b = HoughSpectrum(ComputeHoughTransform(Walls(0.0), options));
    const auto peaks = CircularLocalMaxima(CircularCrossCorrelation(hs_a, hs_b), 1);
    ASSERT_EQ(peaks.size(), 1u);
    // The spectrum's period is pi: the peak gives yaw mod 180 degrees.
    const double found_deg = peaks[0].position * 180.0 / options.n_theta;
    const double diff = std::remainder(found_deg - yaw_deg, 180.0);
    EXPECT_LT(std::abs(diff), 1.0) << "yaw " << yaw_deg << " found " << found_deg;
  }
}

TEST(CircularCorrelation, MatchesShiftedSignal) {
  std::vector<double> b = {0, 1, 5, 2, 0, 0, 0, 3};
  std::vector<double> a(b.size());
  for (std::size_t i = 0; i < b.size(); ++i) a[(i + 3) % b.size()] = b[i];  // a = b shifted by 3
  const auto c = CircularCrossCorrelation(a, b);
  EXPECT_EQ(std::max_element(c.begin(), c.end()) - c.begin(), 3);
  // Direct definition at one shift.
  double c5 = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i) c5 += a[(i + 5) % b.size()] * b[i];
  EXPECT_DOUBLE_EQ(c[5], c5);
}

TEST(CircularLocalMaxima, FindsWrappedPeakAndOrdersByValue) {
  const std::vector<double> s = {9, 1, 0, 4, 0, 1, 2, 8};  // 9 at index 0 wraps to 8 at the end
  const auto peaks = CircularLocalMaxima(s, 5);
  ASSERT_EQ(peaks.size(), 2u);
  // Parabola through (-1, 8), (0, 9), (1, 1): vertex at 0.5 (8 - 1) / (8 - 18 + 1) = -7/18,
  // towards the larger neighbour across the wrap.
  EXPECT_NEAR(peaks[0].position, -7.0 / 18.0, 1e-12);
  EXPECT_DOUBLE_EQ(peaks[0].value, 9);
  EXPECT_DOUBLE_EQ(peaks[1].value, 4);
  EXPECT_DOUBLE_EQ(peaks[1].position, 3.0);
}

}  // namespace
}  // namespace fleetmerge
