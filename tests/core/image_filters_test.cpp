// core/image_filters against the OpenCV imgproc calls they replace, on seeded random images of
// many shapes (1-pixel axes and odd sizes exercise the borders).
#include "core/image_filters.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

namespace fleetmerge {
namespace {

std::vector<cv::Size> Sizes() {
  std::vector<cv::Size> sizes;
  for (const int w : {1, 2, 3, 4, 5, 7, 16, 33}) {
    for (const int h : {1, 2, 3, 5, 6, 31}) sizes.emplace_back(w, h);
  }
  sizes.emplace_back(301, 97);
  return sizes;
}

// Pixels set with probability `density`, to `on` (others 0).
template <typename T>
cv::Mat_<T> RandomMask(cv::Size size, double density, T on, std::mt19937* rng) {
  std::bernoulli_distribution set(density);
  cv::Mat_<T> mask(size, T(0));
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) mask(y, x) = set(*rng) ? on : T(0);
  }
  return mask;
}

TEST(ImageFilters, MaxFilterIsOpenCvsDilation) {
  std::mt19937 rng(11);
  for (const cv::Size size : Sizes()) {
    for (const double density : {0.0, 0.02, 0.3, 1.0}) {
      const cv::Mat1b mask = RandomMask<std::uint8_t>(size, density, 255, &rng);
      cv::Mat1b expected_3x3, expected_4x4;
      cv::dilate(mask, expected_3x3, cv::Mat());
      cv::dilate(mask, expected_4x4, cv::Mat1b::ones(4, 4), cv::Point(1, 1), 1,
                 cv::BORDER_REPLICATE);
      EXPECT_EQ(cv::countNonZero(MaxFilter<1, 1>(mask) != expected_3x3), 0) << size;
      EXPECT_EQ(cv::countNonZero(MaxFilter<1, 2>(mask) != expected_4x4), 0) << size;

      const cv::Mat1f walls = RandomMask<float>(size, density, 1.f, &rng);
      cv::Mat1f expected_walls;
      cv::dilate(walls, expected_walls, cv::Mat());
      EXPECT_EQ(cv::countNonZero(MaxFilter<1, 1>(walls) != expected_walls), 0) << size;
    }
  }
}

TEST(ImageFilters, NonZeroBoxIsOpenCvsBoundingRect) {
  std::mt19937 rng(12);
  for (const cv::Size size : Sizes()) {
    for (const double density : {0.0, 0.001, 0.05, 1.0}) {
      const cv::Mat1b mask = RandomMask<std::uint8_t>(size, density, 7, &rng);
      EXPECT_EQ(NonZeroBox(mask), cv::boundingRect(mask)) << size << " density " << density;
    }
  }
  // A view into a larger image (rows not contiguous).
  const cv::Mat1b big = RandomMask<std::uint8_t>(cv::Size(64, 64), 0.01, 1, &rng);
  const cv::Mat1b view = big(cv::Rect(5, 9, 40, 30));
  EXPECT_EQ(NonZeroBox(view), cv::boundingRect(view));
  EXPECT_TRUE(NonZeroBox(cv::Mat1b()).empty());
}

TEST(ImageFilters, GaussianBlurIsOpenCvsToFloatRounding) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> value(-2.f, 3.f);
  for (const cv::Size size : Sizes()) {
    cv::Mat1f image(size);
    for (float& v : image) v = value(rng);
    for (const cv::Mat1f& input : {image, RandomMask<float>(size, 0.2, 1.f, &rng)}) {
      for (const double sigma : {0.8, 1.0, 1.7}) {
        cv::Mat1f expected;
        cv::GaussianBlur(input, expected, cv::Size(5, 5), sigma);
        EXPECT_LE(cv::norm(GaussianBlur5x5(input, sigma), expected, cv::NORM_INF), 2e-6)
            << size << " sigma " << sigma;
      }
    }
  }
  EXPECT_TRUE(GaussianBlur5x5(cv::Mat1f(), 1.0).empty());
}

}  // namespace
}  // namespace fleetmerge
