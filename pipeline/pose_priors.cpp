#include "pipeline/pose_priors.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>

#include "core/error.hpp"
#include "pipeline/map_label.hpp"

namespace fleetmerge {
namespace {

bool Finite(const Pose2& T) {
  return std::isfinite(T.x_m()) && std::isfinite(T.y_m()) && std::isfinite(T.yaw_rad());
}

// A map's known pose: its prior, or a fixed map's given pose with sigma 0.
std::optional<PosePrior> KnownPose(const FixedPoses& fixed, const PosePriors& priors, int m) {
  if (IsFixed(fixed, m)) return PosePrior{*fixed[m], 0.0, 0.0};
  if (HasPrior(priors, m)) return priors[m];
  return std::nullopt;
}

// "initial_pose of map 'run3'" or "fixed pose of map 1" (pipeline/map_label.hpp).
std::string KnownPoseName(const FixedPoses& fixed, const std::vector<std::string>& names, int m) {
  return (IsFixed(fixed, m) ? "fixed pose of " : "initial_pose of ") + MapLabel(names, m);
}

}  // namespace

void CheckPriors(const PosePriors& priors, const FixedPoses& fixed, std::size_t map_count,
                 const std::vector<std::string>& names) {
  if (priors.empty()) return;
  if (priors.size() != map_count) {
    throw Error("initial poses: " + std::to_string(priors.size()) + " given for " +
                std::to_string(map_count) + " maps (one per map, or none)");
  }
  for (std::size_t m = 0; m < priors.size(); ++m) {
    if (!priors[m]) continue;
    const PosePrior& p = *priors[m];
    std::ostringstream what;
    what << MapLabel(names, static_cast<int>(m)) << JobOrderNote(names) << ": ";
    if (!Finite(p.T_site_map)) {
      what << "initial_pose [" << p.T_site_map.x_m() << ", " << p.T_site_map.y_m() << ", "
           << p.T_site_map.yaw_rad() << "] is not finite; expected finite [x, y, yaw]";
      throw Error(what.str());
    }
    if (!(p.translation_sigma_m > 0.0) || !(p.yaw_sigma_rad > 0.0) ||
        !std::isfinite(p.translation_sigma_m) || !std::isfinite(p.yaw_sigma_rad)) {
      what << "initial_pose_sigma [" << p.translation_sigma_m << ", " << p.yaw_sigma_rad
           << "]; expected finite [metres, radians] > 0";
      throw Error(what.str());
    }
    if (p.yaw_sigma_rad > kMaxYawSigmaRad) {
      what << "initial_pose_sigma yaw " << YawLooksLikeDegrees(p.yaw_sigma_rad)
           << "; expected radians, at most pi";
      throw Error(what.str());
    }
    if (IsFixed(fixed, static_cast<int>(m))) {
      what << "a fixed map has no initial_pose (its pose is given exactly by its fixed pose)";
      throw Error(what.str());
    }
  }
}

double SigmasFromPriors(const Pose2& T_a_b, const PosePrior& a, const PosePrior& b) {
  const Pose2 predicted_b = a.T_site_map * T_a_b;
  const double translation_m = (predicted_b.translation_m() - b.T_site_map.translation_m()).norm();
  const double yaw_rad = std::abs(WrapAngle(predicted_b.yaw_rad() - b.T_site_map.yaw_rad()));
  const double lever_m = a.yaw_sigma_rad * T_a_b.translation_m().norm();
  const double sigma_t =
      std::sqrt(a.translation_sigma_m * a.translation_sigma_m +
                b.translation_sigma_m * b.translation_sigma_m + lever_m * lever_m);
  const double sigma_yaw =
      std::sqrt(a.yaw_sigma_rad * a.yaw_sigma_rad + b.yaw_sigma_rad * b.yaw_sigma_rad);
  return std::max(translation_m / sigma_t, yaw_rad / sigma_yaw);
}

void DropHypothesesAgainstPriors(std::vector<PairOutcome>& pairs, const FixedPoses& fixed,
                                 const PosePriors& priors, const std::vector<std::string>& names) {
  if (priors.empty()) return;
  for (PairOutcome& pair : pairs) {
    if (IsFixed(fixed, pair.a) && IsFixed(fixed, pair.b)) continue;
    const auto known_a = KnownPose(fixed, priors, pair.a);
    const auto known_b = KnownPose(fixed, priors, pair.b);
    if (!known_a || !known_b || pair.hypotheses.empty()) continue;
    std::vector<PairHypothesis> kept;
    std::vector<PairOutcome::Dropped> dropped;
    int nearest = -1;
    double nearest_sigmas = std::numeric_limits<double>::infinity();
    for (int h = 0; h < static_cast<int>(pair.hypotheses.size()); ++h) {
      const double sigmas = SigmasFromPriors(pair.hypotheses[h].T_a_b, *known_a, *known_b);
      if (sigmas < nearest_sigmas) nearest = h, nearest_sigmas = sigmas;
      if (sigmas > kPriorContradictionSigmas) {
        dropped.push_back({h + 1, sigmas, pair.hypotheses[h]});
      } else {
        kept.push_back(pair.hypotheses[h]);
      }
    }
    if (dropped.empty()) continue;
    const std::string known =
        KnownPoseName(fixed, names, pair.a) + " and " + KnownPoseName(fixed, names, pair.b);
    std::ostringstream note;
    note << std::fixed;
    if (kept.empty()) {
      // The hypotheses stay in the report: they show where the maps' walls put the pair.
      const Pose2 predicted_b = known_a->T_site_map * pair.hypotheses[nearest].T_a_b;
      const double off_m =
          (predicted_b.translation_m() - known_b->T_site_map.translation_m()).norm();
      const double off_deg =
          std::abs(WrapAngle(predicted_b.yaw_rad() - known_b->T_site_map.yaw_rad())) * 180.0 / M_PI;
      note << "every hypothesis contradicts the " << known << "; the nearest, hypothesis "
           << nearest + 1 << ", is " << std::setprecision(1) << nearest_sigmas
           << " sigma from them (" << std::setprecision(2) << off_m << " m, "
           << std::setprecision(1) << off_deg << " deg; at most " << std::setprecision(0)
           << kPriorContradictionSigmas << " sigma is accepted)";
      pair.refused_by_priors = true;
      pair.note = note.str();
      continue;
    }
    note << "hypothes" << (dropped.size() == 1 ? "is " : "es ");
    for (std::size_t k = 0; k < dropped.size(); ++k) {
      note << (k ? ", " : "") << dropped[k].search_rank;
    }
    note << " of the search dropped: more than " << std::setprecision(0)
         << kPriorContradictionSigmas << " sigma from the " << known;
    const bool front_two_kept =
        dropped.front().search_rank > std::min<int>(2, static_cast<int>(pair.hypotheses.size()));
    pair.hypotheses = std::move(kept);
    pair.dropped_by_priors = std::move(dropped);
    pair.overlap_cells = pair.hypotheses.front().overlap_cells;
    pair.wall_agreement = pair.hypotheses.front().wall_agreement;
    if (!front_two_kept) {
      // The priors decided between the maps' look-alike poses: the pair is no longer a coin toss.
      pair.ambiguous = false;
      // The evidence of the two now in front, when the ranking measured both (core/
      // pose_evidence.hpp measures only the hypotheses it compares, NaN for the others; those
      // were ordered by omega, so no runner-up is left that the evidence ties with the best).
      const double margin_nats =
          pair.hypotheses.size() >= 2
              ? pair.hypotheses[0].evidence_nats - pair.hypotheses[1].evidence_nats
              : std::numeric_limits<double>::infinity();
      pair.margin_nats =
          std::isnan(margin_nats) ? std::numeric_limits<double>::infinity() : margin_nats;
    }
    pair.note = note.str();
  }
}

}  // namespace fleetmerge
