#include "core/image_filters.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace fleetmerge {
namespace {

// out[x] = max of in[x - before .. x + after] within [0, n). Written as whole-row passes, one per
// offset, so that the compiler vectorises them.
template <typename T>
void MaxAlongRow(const T* in, T* out, int n, int before, int after) {
  std::copy(in, in + n, out);
  for (int d = 1; d <= after; ++d) {
    for (int x = 0; x + d < n; ++x) out[x] = std::max(out[x], in[x + d]);
  }
  for (int d = 1; d <= before; ++d) {
    for (int x = d; x < n; ++x) out[x] = std::max(out[x], in[x - d]);
  }
}

template <typename T>
cv::Mat_<T> MaxFilterOf(const cv::Mat_<T>& image, int before, int after) {
  const int w = image.cols, h = image.rows;
  cv::Mat_<T> rows_max(h, w), out(h, w);
  for (int y = 0; y < h; ++y) MaxAlongRow(image[y], rows_max[y], w, before, after);
  for (int y = 0; y < h; ++y) {
    T* out_row = out[y];
    std::copy(rows_max[y], rows_max[y] + w, out_row);
    for (int yy = std::max(0, y - before); yy <= std::min(h - 1, y + after); ++yy) {
      if (yy == y) continue;
      const T* row = rows_max[yy];
      for (int x = 0; x < w; ++x) out_row[x] = std::max(out_row[x], row[x]);
    }
  }
  return out;
}

// BORDER_REFLECT_101: -1 -> 1, n -> n - 2 (a 1-pixel axis reflects onto itself).
int Reflect101(int p, int n) {
  if (n == 1) return 0;
  while (p < 0 || p >= n) p = p < 0 ? -p : 2 * (n - 1) - p;
  return p;
}

}  // namespace

cv::Mat1b MaxFilter(const cv::Mat1b& image, int before, int after) {
  return MaxFilterOf(image, before, after);
}

cv::Mat1f MaxFilter(const cv::Mat1f& image, int before, int after) {
  return MaxFilterOf(image, before, after);
}

cv::Rect NonZeroBox(const cv::Mat1b& mask) {
  int x0 = mask.cols, x1 = -1, y0 = mask.rows, y1 = -1;
  for (int y = 0; y < mask.rows; ++y) {
    const std::uint8_t* row = mask[y];
    const std::uint8_t* first =
        std::find_if(row, row + mask.cols, [](std::uint8_t v) { return v; });
    if (first == row + mask.cols) continue;
    // The last non-zero pixel: from the right end, stopping at the first one found.
    const std::uint8_t* last = row + mask.cols - 1;
    while (*last == 0) --last;
    x0 = std::min(x0, static_cast<int>(first - row));
    x1 = std::max(x1, static_cast<int>(last - row));
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
    for (int x = -2; x < w + 2; ++x) padded[x + 2] = in[Reflect101(x, w)];
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
