#include "core/correlation_2d.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

// OpenCV's dft skips the rows past `rows` (all zero in, or not needed out), but refuses that hint
// for a single-column image: a map one cell wide searched as map a, with a one-pixel-wide b.
int NonzeroRows(cv::Size dft_size, int rows) { return dft_size.width > 1 ? rows : 0; }

}  // namespace

FixedImageCorrelator::FixedImageCorrelator(const cv::Mat1f& a, cv::Size max_b_size)
    : FixedImageCorrelator(std::vector<cv::Mat1f>{a}, max_b_size) {}

FixedImageCorrelator::FixedImageCorrelator(const std::vector<cv::Mat1f>& a_layers,
                                           cv::Size max_b_size)
    : max_b_size_(max_b_size) {
  if (a_layers.empty()) throw Error("FixedImageCorrelator: no fixed image");
  a_size_ = a_layers.front().size();
  // Padding to at least A + B - 1 in each axis turns the FFT's circular correlation into the
  // linear one; getOptimalDFTSize picks a size with small prime factors for speed.
  dft_size_ = cv::Size(cv::getOptimalDFTSize(a_size_.width + max_b_size.width - 1),
                       cv::getOptimalDFTSize(a_size_.height + max_b_size.height - 1));
  for (const cv::Mat1f& a : a_layers) {
    if (a.size() != a_size_) throw Error("FixedImageCorrelator: fixed layers differ in size");
    cv::Mat1f padded(dft_size_, 0.f);
    a.copyTo(padded(cv::Rect(0, 0, a.cols, a.rows)));
    a_spectra_.emplace_back();
    cv::dft(padded, a_spectra_.back(), 0, NonzeroRows(dft_size_, a.rows));
  }
}

cv::Mat1f FixedImageCorrelator::Correlate(const cv::Mat1f& b) { return CorrelateSum({b}); }

cv::Size FixedImageCorrelator::TransformB(const std::vector<cv::Mat1f>& b_layers) {
  if (b_layers.size() != a_spectra_.size()) {
    throw Error("FixedImageCorrelator: one image B is needed per fixed layer");
  }
  const cv::Size b_size = b_layers.front().size();
  if (b_size.width > max_b_size_.width || b_size.height > max_b_size_.height) {
    throw Error("FixedImageCorrelator: image B is larger than the size fixed at construction");
  }
  // The work buffers are reused: fresh DFT-sized allocations cost more in page faults than the
  // transforms themselves (measured with perf on 530-cell maps).
  padded_.create(dft_size_);
  b_spectra_.resize(b_layers.size());
  for (std::size_t k = 0; k < b_layers.size(); ++k) {
    const cv::Mat1f& b = b_layers[k];
    if (b.size() != b_size) throw Error("FixedImageCorrelator: B layers differ in size");
    padded_.setTo(0.f);
    b.copyTo(padded_(cv::Rect(0, 0, b.cols, b.rows)));
    cv::dft(padded_, b_spectra_[k], 0, NonzeroRows(dft_size_, b.rows));
  }
  return b_size;
}

void FixedImageCorrelator::InverseOfProducts(bool conjugate_b, int output_rows) {
  for (std::size_t k = 0; k < b_spectra_.size(); ++k) {
    // conj(B) in the product: correlation rather than convolution.
    cv::mulSpectrums(a_spectra_[k], b_spectra_[k], k == 0 ? sum_ : product_, 0, conjugate_b);
    if (k > 0) sum_ += product_;
  }
  cv::idft(sum_, circular_, cv::DFT_REAL_OUTPUT | cv::DFT_SCALE,
           NonzeroRows(dft_size_, output_rows));
}

cv::Mat1f FixedImageCorrelator::CorrelateSum(const std::vector<cv::Mat1f>& b_layers) {
  const cv::Size b_size = TransformB(b_layers);
  InverseOfProducts(/*conjugate_b=*/true);
  // Circular index s holds the shift s (s >= 0) or s - N (negative shifts wrap to the end): the
  // columns dx < 0 come from the end of a row, dx >= 0 from its start.
  const int out_cols = a_size_.width + b_size.width - 1;
  const int out_rows = a_size_.height + b_size.height - 1;
  const int negative_cols = b_size.width - 1;
  cv::Mat1f out(out_rows, out_cols);
  for (int r = 0; r < out_rows; ++r) {
    const int dy = r - (b_size.height - 1);
    const float* src = circular_.ptr<float>((dy + dft_size_.height) % dft_size_.height);
    float* dst = out.ptr<float>(r);
    std::copy(src + dft_size_.width - negative_cols, src + dft_size_.width, dst);
    std::copy(src, src + (out_cols - negative_cols), dst + negative_cols);
  }
  return out;
}

void FixedImageCorrelator::CorrelateSumAndHalfTurn(const std::vector<cv::Mat1f>& b_layers,
                                                   cv::Mat1f* r, cv::Mat1f* r_half_turn) {
  *r = CorrelateSum(b_layers);  // leaves the B spectra in b_spectra_
  // The convolution is read from its first rows only, so only those are transformed back.
  InverseOfProducts(/*conjugate_b=*/false, r->rows);
  // R(A, B')(dx, dy) = sum A(x + dx, y + dy) B(w - 1 - x, h - 1 - y) = (A * B)(dx + w - 1,
  // dy + h - 1): Correlate's element (row, col) is the convolution's (row, col), no wrap-around
  // because row < A.rows + h - 1 <= N.
  circular_(cv::Rect(0, 0, r->cols, r->rows)).copyTo(*r_half_turn);
}

FixedImageCorrelator FixedImageCorrelator::WithOwnBuffers() const {
  FixedImageCorrelator copy(*this);  // cv::Mat copies share their pixels: drop the buffers
  copy.padded_.release();
  copy.circular_.release();
  copy.b_spectra_.clear();
  copy.product_.release();
  copy.sum_.release();
  return copy;
}

cv::Mat1f CrossCorrelateDirect(const cv::Mat1f& a, const cv::Mat1f& b) {
  cv::Mat1f out(a.rows + b.rows - 1, a.cols + b.cols - 1, 0.f);
  for (int r = 0; r < out.rows; ++r) {
    for (int c = 0; c < out.cols; ++c) {
      const int dy = r - (b.rows - 1);
      const int dx = c - (b.cols - 1);
      double sum = 0.0;
      for (int y = 0; y < b.rows; ++y) {
        for (int x = 0; x < b.cols; ++x) {
          const int ax = x + dx, ay = y + dy;
          if (ax >= 0 && ay >= 0 && ax < a.cols && ay < a.rows) sum += a(ay, ax) * b(y, x);
        }
      }
      out(r, c) = static_cast<float>(sum);
    }
  }
  return out;
}

}  // namespace fleetmerge
