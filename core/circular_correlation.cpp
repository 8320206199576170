#include "core/circular_correlation.hpp"

#include <algorithm>

#include "core/error.hpp"

namespace fleetmerge {

std::vector<double> CircularCrossCorrelation(const std::vector<double>& a,
                                             const std::vector<double>& b) {
  if (a.size() != b.size()) throw Error("circular cross-correlation needs equal-length spectra");
  // n_theta is a few hundred: the direct O(n^2) sum takes microseconds and is exact.
  const std::size_t n = a.size();
  std::vector<double> c(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) sum += a[(i + k) % n] * b[i];
    c[k] = sum;
  }
  return c;
}

std::vector<Peak> CircularLocalMaxima(const std::vector<double>& signal, int count) {
  const int n = static_cast<int>(signal.size());
  std::vector<Peak> peaks;
  for (int k = 0; k < n; ++k) {
    const double prev = signal[(k + n - 1) % n];
    const double here = signal[k];
    const double next = signal[(k + 1) % n];
    if (!(here > prev && here >= next)) continue;
    // Vertex of the parabola through the three samples: sub-bin position of the maximum.
    const double curvature = prev - 2.0 * here + next;
    const double offset = curvature < 0.0 ? 0.5 * (prev - next) / curvature : 0.0;
    peaks.push_back({k + offset, here});
  }
  std::sort(peaks.begin(), peaks.end(),
            [](const Peak& l, const Peak& r) { return l.value > r.value; });
  if (static_cast<int>(peaks.size()) > count) peaks.resize(std::max(count, 0));
  return peaks;
}

}  // namespace fleetmerge
