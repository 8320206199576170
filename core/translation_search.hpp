// Translation hypotheses for map b, already rotated by psi, against map a (Section III-B).
//
// Two methods share one result type:
// - XySpectraTranslation, the paper's: map a is first aligned with the axes by its own dominant
//   Hough direction; the X- and Y-spectra (Eq. 3, 4: occupied-cell counts per column and row,
//   computed from the occupied cells only, footnote 2) of a and of rotated b are cross-correlated
//   and the argmax of each gives dx and dy.
// - CorrelationTranslation: 2-D cross-correlation of the two occupied-cell images by FFT on a
//   coarse grid (max-pooled, so walls survive), with a's free space scored negatively so that b's
//   walls are not laid across a's rooms. More robust on real maps (see README).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/correlation_2d.hpp"
#include "core/occupancy_grid.hpp"

namespace fleetmerge {

enum class TranslationMethod { kCorrelation2D, kXySpectra };

struct TranslationOptions {
  TranslationMethod method = TranslationMethod::kCorrelation2D;
  int candidates = 3;         // translation peaks kept per rotation
  int coarse_max_side = 128;  // kCorrelation2D: coarse image side that sets the pooling
  double free_penalty = 0.5;  // kCorrelation2D: weight of b walls on a's free space
};

struct TranslationCandidate {
  Eigen::Vector2d t_cells = Eigen::Vector2d::Zero();  // rotated b point q lands on q + t in a
  double score = 0.0;
};

// Cells per coarse pixel of the correlation search for b against a: it sets the precision of
// the translation candidates (about half a pixel), which local refinement must then bridge.
int CorrelationPooling(const OccupancyGrid& a, const OccupancyGrid& b,
                       const TranslationOptions& options);

class CorrelationTranslation {
 public:
  // b_extent_cells bounds the side of rotated b's bounding box (b's diagonal).
  CorrelationTranslation(const OccupancyGrid& a, double b_extent_cells,
                         const TranslationOptions& options);
  std::vector<TranslationCandidate> Find(const std::vector<Eigen::Vector2f>& b_rotated) const;
  int pooling() const { return pooling_; }

 private:
  TranslationOptions options_;
  int pooling_ = 1;  // cells per coarse pixel
  cv::Size max_b_size_;
  FixedImageCorrelator correlator_;
};

class XySpectraTranslation {
 public:
  // a_points: a's (sampled) occupied cell centres; a_axis_rad: a's dominant Hough direction.
  XySpectraTranslation(const std::vector<Eigen::Vector2f>& a_points, double a_axis_rad,
                       const TranslationOptions& options);
  std::vector<TranslationCandidate> Find(const std::vector<Eigen::Vector2f>& b_rotated) const;

  // A spectrum (Eq. 3 or 4) as counts per 1-cell bin, starting at coordinate `origin`.
  struct Spectrum {
    double origin = 0.0;
    std::vector<double> counts;
  };

 private:
  TranslationOptions options_;
  Eigen::Matrix2f R_axis_inv_;  // rotates points so that a's dominant direction is an axis
  double axis_rad_;
  Spectrum a_x_, a_y_;
};

}  // namespace fleetmerge
