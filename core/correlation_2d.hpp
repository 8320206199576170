// Linear 2-D cross-correlation by FFT (OpenCV's dft), used to find the translation between two
// occupied-cell images once the rotation is known (the costly alternative that Section III-B
// mentions and replaces by X/Y spectra; on real maps it is the more reliable of the two).
//
//   R(dx, dy) = sum_(x, y) A(x + dx, y + dy) * B(x, y)
// for every shift at which the images overlap: dx in [-(B.cols-1), A.cols-1], likewise dy.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace fleetmerge {

// Correlates many images B (one per rotation hypothesis) with one fixed image A: A's spectrum is
// computed once, at a padded size that fits any B up to max_b_size without wrap-around.
//
// It may also hold several fixed layers A_1..A_k of one size, correlated with as many layers
// B_1..B_k: the sum R_1 + ... + R_k costs one inverse transform (the sum is taken in the
// frequency domain), which is how a score mixing several cell classes stays cheap.
// Not thread-safe: each thread needs its own correlator (it keeps work buffers).
class FixedImageCorrelator {
 public:
  FixedImageCorrelator(const cv::Mat1f& a, cv::Size max_b_size);
  // Throws if `a_layers` is empty or its images differ in size.
  FixedImageCorrelator(const std::vector<cv::Mat1f>& a_layers, cv::Size max_b_size);

  // R as an image of (A.rows + B.rows - 1) x (A.cols + B.cols - 1): element (row, col) holds
  // R(dx = col - (B.cols - 1), dy = row - (B.rows - 1)). Throws if B exceeds max_b_size or the
  // correlator holds more than one layer.
  cv::Mat1f Correlate(const cv::Mat1f& b);

  // R(A_1, B_1) + ... + R(A_k, B_k), laid out as Correlate's. Throws unless there is one B per
  // fixed layer, all of one size within max_b_size.
  cv::Mat1f CorrelateSum(const std::vector<cv::Mat1f>& b_layers);

  // CorrelateSum of the B layers and of the same layers turned by half a turn (each flipped in
  // both axes, B'(x, y) = B(cols - 1 - x, rows - 1 - y)), from one forward transform per layer:
  // B' has the spectrum conj(B) times a phase ramp, so R(A, B') is the convolution A * B read
  // at shifted indices, and costs one inverse transform more instead of k forward ones. Both
  // are laid out as Correlate's.
  void CorrelateSumAndHalfTurn(const std::vector<cv::Mat1f>& b_layers, cv::Mat1f* r,
                               cv::Mat1f* r_half_turn);

  // A correlator for another thread: the same fixed spectra (shared, only read), work buffers
  // of its own. The results are the same as this one's.
  FixedImageCorrelator WithOwnBuffers() const;

 private:
  cv::Size a_size_;
  cv::Size max_b_size_;
  cv::Size dft_size_;
  std::vector<cv::Mat> a_spectra_;
  // Forward transforms of the B layers into b_spectra_; returns their common size.
  cv::Size TransformB(const std::vector<cv::Mat1f>& b_layers);
  // sum_k A_k conj(B_k) (correlation) or sum_k A_k B_k (convolution), inverse-transformed into
  // circular_; output_rows > 0: only its first output_rows rows are needed.
  void InverseOfProducts(bool conjugate_b, int output_rows = 0);

  // Work buffers (so one correlator serves one thread).
  cv::Mat1f padded_, circular_;
  std::vector<cv::Mat> b_spectra_;
  cv::Mat product_, sum_;
};

// The direct O(N^2 M^2) sum, for tests and tiny images.
cv::Mat1f CrossCorrelateDirect(const cv::Mat1f& a, const cv::Mat1f& b);

}  // namespace fleetmerge
