// Translation hypotheses for map b, already rotated by psi, against map a (Section III-B).
//
// Two methods share one result type:
// - XySpectraTranslation, the paper's: map a is first aligned with the axes by its own dominant
//   Hough direction; the X- and Y-spectra (Eq. 3, 4: occupied-cell counts per column and row,
//   computed from the occupied cells only, footnote 2) of a and of rotated b are cross-correlated
//   and the argmax of each gives dx and dy.
// - CorrelationTranslation: 2-D cross-correlation by FFT on a coarse grid (max-pooled, so walls
//   survive). Walls of b on walls of a score; a wall of either map laid across the other's open
//   space (free pixels not next to a wall pixel) costs free_penalty. The penalty both ways is
//   what lets a small true overlap beat a large wrong one: a raw wall count grows with the
//   overlap, and wrong overlaps of one building are large (in simulated fleets in GDC and MIT
//   CSAIL a walls-only count put the true translation 30-120th; see docs/accuracy.md, "Accuracy
//   suite").
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "core/correlation_2d.hpp"
#include "core/occupancy_grid.hpp"

namespace fleetmerge {

enum class TranslationMethod { kCorrelation2D, kXySpectra };

struct TranslationOptions {
  TranslationMethod method = TranslationMethod::kCorrelation2D;
  int candidates = 3;  // translation peaks kept per rotation
  // kCorrelation2D: coarse image side that sets the pooling. 192 rather than 256: DFTs of 324
  // instead of 432 for a 530 x 530 pair (5-8 ms of its search); 160 lost held-out pairs.
  int coarse_max_side = 192;
  double free_penalty = 2.0;  // kCorrelation2D: weight of a wall on the other map's open space
};

struct TranslationCandidate {
  Eigen::Vector2d t_cells = Eigen::Vector2d::Zero();  // rotated b point q lands on q + t in a
  double score = 0.0;
};

// A map's extent in the correlation search, in cells: map a, the fixed image, spans its larger
// side; map b, rotated over it, its diagonal (the side of the square any rotation of b fits in).
double FixedExtentCells(const OccupancyGrid& a);
double RotatedExtentCells(const OccupancyGrid& b);

// Cells per coarse pixel of the correlation search for b against a: it sets the precision of
// the translation candidates (about half a pixel), which local refinement must then bridge.
int CorrelationPooling(const OccupancyGrid& a, const OccupancyGrid& b,
                       const TranslationOptions& options);

class CorrelationTranslation {
 public:
  // With the pooling (CorrelationPooling) and the largest b image (RasterSize of every rotation
  // that will be searched): the transforms are only as large as those images need, not as b's
  // diagonal.
  CorrelationTranslation(const OccupancyGrid& a, int pooling, cv::Size max_b_pixels,
                         const TranslationOptions& options);
  // The bounding box of every point the search rasterizes (b's rotated points; `walls` must not be
  // empty), and the size of the b image it makes from them at this pooling. A caller that
  // sizes the search first passes the box on to FindWithHalfTurn instead of a second pass over
  // 10^5 free points.
  struct PointBox {
    Eigen::Vector2f min, max;
  };
  static PointBox Bounds(const std::vector<Eigen::Vector2f>& scored_walls,
                         const std::vector<Eigen::Vector2f>& walls,
                         const std::vector<Eigen::Vector2f>& free);
  static cv::Size RasterSize(const PointBox& box, int pooling);
  // Translation candidates for b's cell centres, rotated by the hypothesis: scored_walls, the
  // occupied cells that vote (sampled, Section III-D); walls, every occupied cell, and free,
  // every free cell, which say where b is open. Open space must come from all walls: a wall
  // left out of a sample would turn its pixel open and penalise a's wall there (every k-th
  // point of a row-major list drops whole walls for k >= 6, and the true pose was then found in
  // 0-22 % of trials, not 96 %). For the points as given (result[0]) and turned by a further
  // half turn, q -> -q (result[1]): the Hough spectrum cannot tell psi from psi + pi (Section
  // III-A), so both are searched, and the half-turned images are the given ones flipped, which the
  // correlator serves from the same forward transforms. Pass one vector as scored_walls and walls
  // when every wall is scored. `box`: Bounds of these points when the caller has it (nullptr:
  // computed here).
  std::array<std::vector<TranslationCandidate>, 2> FindWithHalfTurn(
      const std::vector<Eigen::Vector2f>& scored_walls, const std::vector<Eigen::Vector2f>& walls,
      const std::vector<Eigen::Vector2f>& free, const PointBox* box = nullptr);
  int pooling() const { return pooling_; }

  // A search for another thread (a search changes the correlator's work buffers): the same fixed
  // layers and transforms, shared; buffers of its own.
  CorrelationTranslation WithOwnBuffers() const;

 private:
  TranslationOptions options_;
  int pooling_ = 1;  // cells per coarse pixel
  cv::Size max_b_size_;
  cv::Point a_offset_px_;  // a's coarse pixel of the fixed layers' (0, 0): they are cropped
  // Layers of a: score for b's walls (blurred walls - penalty * open space), a's walls (against
  // b's open space).
  FixedImageCorrelator correlator_;

  // b's layers (scored walls, -penalty * open space) on the coarse grid anchored at q_min.
  struct BLayers {
    std::vector<cv::Mat1f> layers;
    Eigen::Vector2f q_min;
  };
  // Peaks of a correlation surface (pixel positions, b's images w x h = b_pixels) to the
  // translations t in cells, for b's image anchored at `anchor` (its first pixel's corner).
  void ToTranslations(cv::Size b_pixels, const Eigen::Vector2d& anchor,
                      std::vector<TranslationCandidate>& peaks) const;
  BLayers RasterizeB(const std::vector<Eigen::Vector2f>& scored_walls,
                     const std::vector<Eigen::Vector2f>& walls,
                     const std::vector<Eigen::Vector2f>& free, const PointBox& box) const;
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
