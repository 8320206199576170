#include "core/hough_spectrum.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "core/error.hpp"

namespace fleetmerge {

double HoughTransform::theta_rad(int theta_index) const { return M_PI * theta_index / n_theta; }

HoughTransform ComputeHoughTransform(const std::vector<Eigen::Vector2f>& points,
                                     const HoughOptions& options) {
  if (options.n_theta < 2 || !(options.rho_step_cells > 0.0)) {
    std::ostringstream msg;
    msg << "Hough transform needs n_theta >= 2 and rho_step > 0, got n_theta = " << options.n_theta
        << ", rho_step = " << options.rho_step_cells;
    throw Error(msg.str());
  }
  HoughTransform h;
  h.n_theta = options.n_theta;
  h.rho_step = options.rho_step_cells;

  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const auto& p : points) sum += p.cast<double>();
  if (!points.empty()) h.center = (sum / points.size()).cast<float>();
  double radius = 0.0;
  for (const auto& p : points) radius = std::max(radius, double((p - h.center).norm()));
  h.n_rho = 2 * static_cast<int>(std::ceil(radius / h.rho_step)) + 2;
  h.rho_min = -0.5 * h.n_rho * h.rho_step;
  h.votes.assign(static_cast<std::size_t>(h.n_rho) * h.n_theta, 0);

  // Points as separate x / y arrays centred once, so the inner loop is a plain multiply-add
  // the compiler can vectorise; only the vote itself is a scatter.
  const std::size_t m = points.size();
  std::vector<float> xs(m), ys(m);
  for (std::size_t n = 0; n < m; ++n) {
    xs[n] = points[n].x() - h.center.x();
    ys[n] = points[n].y() - h.center.y();
  }
  const float inv_step = static_cast<float>(1.0 / h.rho_step);
  const float offset = static_cast<float>(-h.rho_min / h.rho_step);
  // Bins are computed for a chunk of points at a time (kept in L1 between the vectorised
  // computation and the votes), and the votes go to kCopies interleaved partial columns, summed
  // after: successive points of a wall vote for the same rho bin, and one counter would make
  // each increment wait for the last.
  constexpr std::size_t kChunk = 1024;
  constexpr std::size_t kCopies = 4;
  std::array<int, kChunk> bins;
  std::vector<int> partial(kCopies * static_cast<std::size_t>(h.n_rho));
  for (int k = 0; k < h.n_theta; ++k) {
    const float c = static_cast<float>(std::cos(h.theta_rad(k))) * inv_step;
    const float s = static_cast<float>(std::sin(h.theta_rad(k))) * inv_step;
    std::fill(partial.begin(), partial.end(), 0);
    int* p0 = partial.data();
    int* p1 = p0 + h.n_rho;
    int* p2 = p1 + h.n_rho;
    int* p3 = p2 + h.n_rho;
    for (std::size_t start = 0; start < m; start += kChunk) {
      const std::size_t count = std::min(kChunk, m - start);
      const float* x = xs.data() + start;
      const float* y = ys.data() + start;
      for (std::size_t n = 0; n < count; ++n) {
        bins[n] = static_cast<int>(x[n] * c + y[n] * s + offset);
      }
      std::size_t n = 0;
      for (; n + kCopies <= count; n += kCopies) {  // Eq. (2): one vote per column
        ++p0[bins[n]];
        ++p1[bins[n + 1]];
        ++p2[bins[n + 2]];
        ++p3[bins[n + 3]];
      }
      for (; n < count; ++n) ++p0[bins[n]];
    }
    int* column = h.votes.data() + static_cast<std::size_t>(k) * h.n_rho;
    for (int i = 0; i < h.n_rho; ++i) column[i] = p0[i] + p1[i] + p2[i] + p3[i];
  }
  return h;
}

std::vector<double> HoughSpectrum(const HoughTransform& transform) {
  std::vector<double> spectrum(transform.n_theta, 0.0);
  for (int k = 0; k < transform.n_theta; ++k) {
    const int* column = transform.votes.data() + static_cast<std::size_t>(k) * transform.n_rho;
    double sum = 0.0;
    for (int i = 0; i < transform.n_rho; ++i) sum += double(column[i]) * column[i];
    spectrum[k] = sum;
  }
  return spectrum;
}

}  // namespace fleetmerge
