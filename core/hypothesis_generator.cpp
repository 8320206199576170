#include "core/hypothesis_generator.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include "core/acceptance_index.hpp"
#include "core/circular_correlation.hpp"
#include "core/error.hpp"
#include "core/map_features.hpp"
#include "core/parallel.hpp"

namespace fleetmerge {
namespace {

void CheckSameResolution(const OccupancyGrid& a, const OccupancyGrid& b) {
  const double ra = a.geometry().resolution_m(), rb = b.geometry().resolution_m();
  if (std::abs(ra - rb) > 1e-9 * std::max(ra, rb)) {
    std::ostringstream msg;
    msg << "maps have different resolutions (" << ra << " m and " << rb
        << " m): resample them to one resolution first";
    throw Error(msg.str());
  }
}

std::vector<double> RotationCandidates(const std::vector<double>& hs_a,
                                       const std::vector<double>& hs_b, int peaks) {
  const double bin_rad = M_PI / hs_a.size();
  std::vector<double> yaws;
  for (const Peak& peak : CircularLocalMaxima(CircularCrossCorrelation(hs_a, hs_b), peaks)) {
    yaws.push_back(peak.position * bin_rad);
    yaws.push_back(peak.position * bin_rad + M_PI);  // same spectrum, period pi
  }
  return yaws;
}

// a's dominant wall normal: the argmax of its own spectrum (Section III-B alignment).
double DominantDirection(const std::vector<double>& hs) {
  const auto it = std::max_element(hs.begin(), hs.end());
  return M_PI * double(it - hs.begin()) / hs.size();
}

std::vector<Eigen::Vector2f> RotatePoints(const std::vector<Eigen::Vector2f>& points,
                                          double yaw_rad) {
  const Eigen::Matrix2f R = Eigen::Rotation2Df(static_cast<float>(yaw_rad)).toRotationMatrix();
  // Sized once and written in place: a plain loop the compiler vectorises.
  std::vector<Eigen::Vector2f> out(points.size());
  for (std::size_t n = 0; n < points.size(); ++n) out[n] = R * points[n];
  return out;
}

}  // namespace

std::vector<CellHypothesis> GenerateHypotheses(const OccupancyGrid& a, const OccupancyGrid& b,
                                               const HypothesisOptions& options) {
  CheckSameResolution(a, b);
  return GenerateHypotheses(MapFeatures(a, options), MapFeatures(b, options), options);
}

std::vector<CellHypothesis> GenerateHypotheses(const MapFeatures& fa, const MapFeatures& fb,
                                               const HypothesisOptions& options, int threads) {
  const OccupancyGrid& a = fa.grid;
  const OccupancyGrid& b = fb.grid;
  CheckSameResolution(a, b);
  const std::vector<Eigen::Vector2f>& b_points = fb.walls.centres;
  if (fa.walls.centres.empty() || b_points.empty()) return {};
  const std::vector<double>& hs_a = fa.hough_spectrum;
  const std::vector<double>& hs_b = fb.hough_spectrum;

  const std::vector<Eigen::Vector2f>& b_spectra_points = fb.spectra_points;
  // The correlation search also needs where b is open (core/translation_search.hpp).
  const std::vector<Eigen::Vector2f>& b_free_points = fb.free;
  const RowSpans& b_spans = fb.walls.known_spans;
  const bool sampled = b_spectra_points.size() != b_points.size();
  // Rotation candidates come as (psi, psi + pi) pairs (RotationCandidates).
  const std::vector<double> yaws = RotationCandidates(hs_a, hs_b, options.rotation_peaks);

  // b rotated by each psi: its scored walls, all walls (when the scored ones are a sample) and
  // free cells. Rotated before the correlator is made, so that its transforms are sized for the
  // largest of these images rather than for b's diagonal.
  struct RotatedB {
    std::vector<Eigen::Vector2f> scored_walls, walls, free;
    CorrelationTranslation::PointBox box;  // of all three
  };
  const std::size_t rotation_pairs = yaws.size() / 2;
  std::vector<RotatedB> rotated;
  std::unique_ptr<CorrelationTranslation> correlation;
  std::unique_ptr<XySpectraTranslation> spectra;
  if (options.translation.method == TranslationMethod::kCorrelation2D) {
    const int pooling = CorrelationPooling(a, b, options.translation);
    rotated.resize(rotation_pairs);
    std::vector<cv::Size> sizes(rotation_pairs);
    ParallelFor(rotation_pairs, threads, [&](std::size_t pair_index) {
      const double yaw = yaws[2 * pair_index];
      RotatedB& r = rotated[pair_index];
      r.scored_walls = RotatePoints(b_spectra_points, yaw);
      if (sampled) r.walls = RotatePoints(b_points, yaw);
      r.free = RotatePoints(b_free_points, yaw);
      r.box = CorrelationTranslation::Bounds(r.scored_walls, sampled ? r.walls : r.scored_walls,
                                             r.free);
      sizes[pair_index] = CorrelationTranslation::RasterSize(r.box, pooling);
    });
    cv::Size max_b_pixels(1, 1);
    for (const cv::Size& size : sizes) {
      max_b_pixels.width = std::max(max_b_pixels.width, size.width);
      max_b_pixels.height = std::max(max_b_pixels.height, size.height);
    }
    correlation =
        std::make_unique<CorrelationTranslation>(a, pooling, max_b_pixels, options.translation);
  } else {
    spectra = std::make_unique<XySpectraTranslation>(fa.spectra_points, DominantDirection(hs_a),
                                                     options.translation);
  }

  // Each rotation pair (psi, psi + pi) is searched on its own, in parallel; its candidates are
  // then gathered in rotation order, so the result does not depend on the thread count.
  std::vector<std::vector<CellHypothesis>> found_per_pair(rotation_pairs);
  ParallelFor(rotation_pairs, threads, [&](std::size_t pair_index) {
    std::vector<CellHypothesis>& found = found_per_pair[pair_index];
    const auto add_candidates = [&](const std::vector<TranslationCandidate>& translations,
                                    double yaw) {
      for (const auto& t : translations) {
        const Pose2 T_ga_gb(t.t_cells, yaw);
        // Ranking pass on every other row and column: 4x cheaper, same order in practice (the
        // overlap estimate scales by the 4 cells each visited one stands for).
        const Agreement agreement = CountAgreement(a, b, T_ga_gb, 2, &b_spans);
        found.push_back({T_ga_gb, agreement.omega(), 4 * (agreement.agree + agreement.disagree)});
      }
    };
    const std::size_t k = 2 * pair_index;
    const double yaw = yaws[k], yaw_half_turn = yaws[k + 1];
    if (correlation) {
      // The correlation search serves psi + pi from psi's forward transforms
      // (CorrelationTranslation::FindWithHalfTurn). Its work buffers are per thread.
      std::optional<CorrelationTranslation> own;
      if (threads != 1) own.emplace(correlation->WithOwnBuffers());
      CorrelationTranslation& search = own ? *own : *correlation;
      const RotatedB& r = rotated[pair_index];
      const auto translations = search.FindWithHalfTurn(
          r.scored_walls, sampled ? r.walls : r.scored_walls, r.free, &r.box);
      add_candidates(translations[0], yaw);
      add_candidates(translations[1], yaw_half_turn);
    } else {
      add_candidates(spectra->Find(RotatePoints(b_spectra_points, yaw)), yaw);
      add_candidates(spectra->Find(RotatePoints(b_spectra_points, yaw_half_turn)), yaw_half_turn);
    }
  });
  std::vector<CellHypothesis> candidates;
  for (const auto& found : found_per_pair) {
    candidates.insert(candidates.end(), found.begin(), found.end());
  }
  SortHypotheses(candidates, options.min_overlap_cells);
  candidates = RemoveDuplicates(std::move(candidates), options);
  if (static_cast<int>(candidates.size()) > options.max_hypotheses) {
    candidates.resize(std::max(options.max_hypotheses, 0));
  }
  ParallelFor(candidates.size(), threads, [&](std::size_t k) {
    const Agreement agreement = CountAgreement(a, b, candidates[k].T_ga_gb, 1, &b_spans);
    candidates[k].omega = agreement.omega();  // Eq. (1)
    candidates[k].overlap_cells = agreement.agree + agreement.disagree;
  });
  SortHypotheses(candidates, options.min_overlap_cells);
  return candidates;
}

void SortHypotheses(std::vector<CellHypothesis>& hypotheses, std::int64_t min_overlap_cells) {
  std::stable_sort(hypotheses.begin(), hypotheses.end(), [&](const auto& l, const auto& r) {
    const bool l_enough = l.overlap_cells >= min_overlap_cells;
    const bool r_enough = r.overlap_cells >= min_overlap_cells;
    if (l_enough != r_enough) return l_enough;
    return l.omega > r.omega;
  });
}

std::vector<CellHypothesis> RemoveDuplicates(std::vector<CellHypothesis> sorted,
                                             const HypothesisOptions& options) {
  std::vector<CellHypothesis> kept;
  for (const auto& c : sorted) {
    const bool duplicate = std::any_of(kept.begin(), kept.end(), [&](const CellHypothesis& k) {
      const Pose2 delta = k.T_ga_gb.inverse() * c.T_ga_gb;
      return std::abs(delta.yaw_rad()) < options.duplicate_yaw_rad &&
             (k.T_ga_gb.translation_m() - c.T_ga_gb.translation_m()).norm() <
                 options.duplicate_translation_cells;
    });
    if (!duplicate) kept.push_back(c);
  }
  return kept;
}

Pose2 MapPoseFromCellPose(const GridGeometry& a, const GridGeometry& b, const Pose2& T_ga_gb) {
  const Pose2 T_ga_gb_m(T_ga_gb.translation_m() * a.resolution_m(), T_ga_gb.yaw_rad());
  return a.T_map_grid() * T_ga_gb_m * b.T_map_grid().inverse();
}

Pose2 CellPoseFromMapPose(const GridGeometry& a, const GridGeometry& b, const Pose2& T_a_b) {
  const Pose2 T_ga_gb_m = a.T_map_grid().inverse() * T_a_b * b.T_map_grid();
  return Pose2(T_ga_gb_m.translation_m() / a.resolution_m(), T_ga_gb_m.yaw_rad());
}

}  // namespace fleetmerge
