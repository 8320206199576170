#include "core/image_filters.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

namespace fleetmerge {
namespace {

// out[x] = max of in[x - kBefore .. x + kAfter] within [0, n). The window is a compile-time
// constant so that the interior loop is unrolled over it and vectorised over x.
template <int kBefore, int kAfter, typename T>
void MaxAlongRow(const T* in, T* out, int n) {
  const auto clipped = [&](int x) {
    T m = in[x];
    for (int xx = std::max(0, x - kBefore); xx <= std::min(n - 1, x + kAfter); ++xx) {
      m = std::max(m, in[xx]);
    }
    out[x] = m;
  };
  const int interior_end = std::max(kBefore, n - kAfter);
  for (int x = 0; x < std::min(kBefore, n); ++x) clipped(x);
  for (int x = kBefore; x < interior_end; ++x) {
    T m = in[x - kBefore];
    for (int d = 1 - kBefore; d <= kAfter; ++d) m = std::max(m, in[x + d]);
    out[x] = m;
  }
  for (int x = interior_end; x < n; ++x) clipped(x);
}

// out[x] = max over rows[0 .. count)[x]; count is the window but at the image's top and bottom.
template <int kWindow, typename T>
void MaxAcrossRows(const T* const* rows, int count, T* out, int n) {
  if (count == kWindow) {
    for (int x = 0; x < n; ++x) {
      T m = rows[0][x];
      for (int i = 1; i < kWindow; ++i) m = std::max(m, rows[i][x]);
      out[x] = m;
    }
    return;
  }
  std::copy(rows[0], rows[0] + n, out);
  for (int i = 1; i < count; ++i) {
    for (int x = 0; x < n; ++x) out[x] = std::max(out[x], rows[i][x]);
  }
}

}  // namespace

// Separable: each input row's maximum along the row once, kept in a ring of the window's rows
// (not a whole intermediate image: its fresh pages would cost as much as the filtering).
template <int kBefore, int kAfter, typename T>
cv::Mat_<T> MaxFilter(const cv::Mat_<T>& image) {
  constexpr int kWindow = kBefore + kAfter + 1;
  const int w = image.cols, h = image.rows;
  cv::Mat_<T> out(h, w);
  std::vector<T> ring(static_cast<std::size_t>(kWindow) * w);
  const auto row_max = [&](int y) {
    return ring.data() + static_cast<std::size_t>(y % kWindow) * w;
  };
  int next = 0;  // the next input row to take its row maximum of
  for (int y = 0; y < h; ++y) {
    const int first = std::max(0, y - kBefore), last = std::min(h - 1, y + kAfter);
    for (; next <= last; ++next) MaxAlongRow<kBefore, kAfter>(image[next], row_max(next), w);
    const T* rows[kWindow];
    for (int yy = first; yy <= last; ++yy) rows[yy - first] = row_max(yy);
    MaxAcrossRows<kWindow>(rows, last - first + 1, out[y], w);
  }
  return out;
}

template cv::Mat1b MaxFilter<1, 1>(const cv::Mat1b&);
template cv::Mat1f MaxFilter<1, 1>(const cv::Mat1f&);
template cv::Mat1b MaxFilter<1, 2>(const cv::Mat1b&);

namespace {

// BORDER_REFLECT_101: -1 -> 1, n -> n - 2 (a 1-pixel axis reflects onto itself).
int Reflect101(int p, int n) {
  if (n == 1) return 0;
  while (p < 0 || p >= n) p = p < 0 ? -p : 2 * (n - 1) - p;
  return p;
}

}  // namespace

cv::Rect NonZeroBox(const cv::Mat1b& mask) {
  constexpr int kWord = sizeof(std::uint64_t);
  const auto zero_word = [](const std::uint8_t* p) {
    std::uint64_t word;
    std::memcpy(&word, p, kWord);
    return word == 0;
  };
  int x0 = mask.cols, x1 = -1, y0 = mask.rows, y1 = -1;
  for (int y = 0; y < mask.rows; ++y) {
    const std::uint8_t* row = mask[y];
    // The first non-zero pixel, eight pixels at a time over the zero ones.
    int first = 0;
    while (first + kWord <= mask.cols && zero_word(row + first)) first += kWord;
    while (first < mask.cols && row[first] == 0) ++first;
    if (first == mask.cols) continue;
    // The last one: from the right end, stopping at the first found.
    int last = mask.cols - 1;
    while (last + 1 - kWord > first && zero_word(row + last + 1 - kWord)) last -= kWord;
    while (row[last] == 0) --last;
    x0 = std::min(x0, first);
    x1 = std::max(x1, last);
    y0 = std::min(y0, y);
    y1 = y;
  }
  return x1 < 0 ? cv::Rect() : cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
}

cv::Mat1f GaussianBlur5x5(const cv::Mat1f& image, double sigma) {
  // The kernel as cv::getGaussianKernel(5, sigma, CV_32F): exp(-x^2 / (2 sigma^2)), normalised.
  std::array<double, 3> k_double{};  // weights of offsets 0, +-1, +-2
  double sum = 0.0;
  for (int x = -2; x <= 2; ++x) {
    const double t = std::exp(-0.5 * x * x / (sigma * sigma));
    k_double[std::abs(x)] = t;
    sum += t;
  }
  const float k0 = float(k_double[0] / sum), k1 = float(k_double[1] / sum),
              k2 = float(k_double[2] / sum);
  const int w = image.cols, h = image.rows;
  if (image.empty()) return image.clone();
  cv::Mat1f rows_blurred(h, w), out(h, w);
  std::vector<float> padded(w + 4);
  for (int y = 0; y < h; ++y) {
    const float* in = image[y];
    std::copy(in, in + w, padded.begin() + 2);
    for (const int x : {-2, -1, w, w + 1}) padded[x + 2] = in[Reflect101(x, w)];
    const float* s = padded.data() + 2;
    float* row_out = rows_blurred[y];
    for (int x = 0; x < w; ++x) {
      row_out[x] = k0 * s[x] + k1 * (s[x - 1] + s[x + 1]) + k2 * (s[x - 2] + s[x + 2]);
    }
  }
  for (int y = 0; y < h; ++y) {
    const float* r[5];
    for (int d = -2; d <= 2; ++d) r[d + 2] = rows_blurred[Reflect101(y + d, h)];
    float* row_out = out[y];
    for (int x = 0; x < w; ++x) {
      row_out[x] = k0 * r[2][x] + k1 * (r[1][x] + r[3][x]) + k2 * (r[0][x] + r[4][x]);
    }
  }
  return out;
}

}  // namespace fleetmerge
