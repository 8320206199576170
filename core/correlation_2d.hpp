// Linear 2-D cross-correlation by FFT (OpenCV's dft), used to find the translation between two
// occupied-cell images once the rotation is known (the costly alternative that Section III-B
// mentions and replaces by X/Y spectra; on real maps it is the more reliable of the two).
//
//   R(dx, dy) = sum_(x, y) A(x + dx, y + dy) * B(x, y)
// for every shift at which the images overlap: dx in [-(B.cols-1), A.cols-1], likewise dy.
#pragma once

#include <opencv2/core.hpp>

namespace fleetmerge {

// Correlates many images B (one per rotation hypothesis) with one fixed image A: A's spectrum is
// computed once, at a padded size that fits any B up to max_b_size without wrap-around.
class FixedImageCorrelator {
 public:
  FixedImageCorrelator(const cv::Mat1f& a, cv::Size max_b_size);

  // R as an image of (A.rows + B.rows - 1) x (A.cols + B.cols - 1): element (row, col) holds
  // R(dx = col - (B.cols - 1), dy = row - (B.rows - 1)). Throws if B exceeds max_b_size.
  cv::Mat1f Correlate(const cv::Mat1f& b) const;

 private:
  cv::Size a_size_;
  cv::Size max_b_size_;
  cv::Size dft_size_;
  cv::Mat a_spectrum_;
};

// The direct O(N^2 M^2) sum, for tests and tiny images.
cv::Mat1f CrossCorrelateDirect(const cv::Mat1f& a, const cv::Mat1f& b);

}  // namespace fleetmerge
