// The paper's translation step (Section III-B, Eq. 3 and 4, Algorithm 1 lines 6-12).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/translation_search.hpp"

namespace fleetmerge {
namespace {

using Spectrum = XySpectraTranslation::Spectrum;

// Eq. (3)/(4) from the occupied cells only (footnote 2): counts per 1-cell bin along one axis.
Spectrum AxisSpectrum(const std::vector<Eigen::Vector2f>& points, int axis) {
  Spectrum s;
  if (points.empty()) return s;
  float lo = points.front()[axis], hi = lo;
  for (const auto& p : points) {
    lo = std::min(lo, p[axis]);
    hi = std::max(hi, p[axis]);
  }
  s.origin = std::floor(lo);
  s.counts.assign(static_cast<std::size_t>(std::floor(hi) - s.origin) + 1, 0.0);
  for (const auto& p : points) s.counts[static_cast<std::size_t>(p[axis] - s.origin)] += 1.0;
  return s;
}

// Shifts dx (in cells) with the largest linear cross-correlation sum_u A(u + s) B(u), best first.
std::vector<std::pair<double, double>> BestShifts(const Spectrum& a, const Spectrum& b, int count) {
  const int na = static_cast<int>(a.counts.size()), nb = static_cast<int>(b.counts.size());
  std::vector<double> corr(na + nb - 1, 0.0);
  for (int s = -(nb - 1); s < na; ++s) {
    double sum = 0.0;
    for (int u = std::max(0, -s); u < nb && u + s < na; ++u) sum += a.counts[u + s] * b.counts[u];
    corr[s + nb - 1] = sum;
  }
  std::vector<std::pair<double, double>> peaks;  // (score, shift)
  for (int k = 0; k < static_cast<int>(corr.size()); ++k) {
    const double left = k > 0 ? corr[k - 1] : -1.0;
    const double right = k + 1 < static_cast<int>(corr.size()) ? corr[k + 1] : -1.0;
    if (corr[k] > left && corr[k] >= right) {
      // b's bin u sits at b.origin + u and meets a's bin u + s at a.origin + u + s.
      peaks.emplace_back(corr[k], a.origin - b.origin + (k - (nb - 1)));
    }
  }
  std::sort(peaks.begin(), peaks.end(), [](auto& l, auto& r) { return l.first > r.first; });
  if (static_cast<int>(peaks.size()) > count) peaks.resize(count);
  return peaks;
}

std::vector<Eigen::Vector2f> Rotated(const std::vector<Eigen::Vector2f>& points,
                                     const Eigen::Matrix2f& R) {
  std::vector<Eigen::Vector2f> out;
  out.reserve(points.size());
  for (const auto& p : points) out.push_back(R * p);
  return out;
}

}  // namespace

XySpectraTranslation::XySpectraTranslation(const std::vector<Eigen::Vector2f>& a_points,
                                           double a_axis_rad, const TranslationOptions& options)
    : options_(options),
      R_axis_inv_(Eigen::Rotation2Df(static_cast<float>(-a_axis_rad)).toRotationMatrix()),
      axis_rad_(a_axis_rad) {
  // Section III-B: align a with the axes by its own dominant direction so that its walls give
  // sharp peaks in the X- and Y-spectra.
  const auto aligned = Rotated(a_points, R_axis_inv_);
  a_x_ = AxisSpectrum(aligned, 0);
  a_y_ = AxisSpectrum(aligned, 1);
}

std::vector<TranslationCandidate> XySpectraTranslation::Find(
    const std::vector<Eigen::Vector2f>& b_rotated) const {
  if (b_rotated.empty() || a_x_.counts.empty()) return {};
  const auto aligned = Rotated(b_rotated, R_axis_inv_);
  // The paper keeps only the argmax of each axis; we keep a few per axis and let omega choose.
  const int per_axis = std::max(1, static_cast<int>(std::ceil(std::sqrt(options_.candidates))));
  const auto xs = BestShifts(a_x_, AxisSpectrum(aligned, 0), per_axis);
  const auto ys = BestShifts(a_y_, AxisSpectrum(aligned, 1), per_axis);
  const Eigen::Matrix2d R_axis = Eigen::Rotation2Dd(axis_rad_).toRotationMatrix();
  std::vector<TranslationCandidate> out;
  for (const auto& [score_x, dx] : xs) {
    for (const auto& [score_y, dy] : ys) {
      // Shift found in a's aligned frame; rotate it back into a's grid frame.
      out.push_back({R_axis * Eigen::Vector2d(dx, dy), score_x * score_y});
    }
  }
  std::sort(out.begin(), out.end(), [](auto& l, auto& r) { return l.score > r.score; });
  if (static_cast<int>(out.size()) > options_.candidates) out.resize(options_.candidates);
  return out;
}

}  // namespace fleetmerge
