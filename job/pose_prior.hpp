// A known start pose (a "prior"): where an operator says a map's frame is in the site frame, and
// how sure they are. Every prior of a job is given in that one site frame, which is the merged
// frame (with fixed maps it is theirs).
#pragma once

#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/pose2.hpp"

namespace fleetmerge {

// Defaults of initial_pose_sigma: a dock marked on a site plan is good to about half a metre and
// ten degrees. Tighter sigmas refuse more pairs; a sigma far beyond the pair search's error only
// places maps that overlap nobody.
constexpr double kDefaultPriorTranslationSigmaM = 0.5;
constexpr double kDefaultPriorYawSigmaRad = 10.0 * M_PI / 180.0;

// Yaws are radians. A yaw beyond 2 pi in magnitude, or a yaw sigma beyond pi (a heading known
// to worse than a half turn is not known), is almost surely degrees (90 for a quarter turn,
// 10 for ten degrees) and is refused rather than silently wrapped.
constexpr double kMaxYawRad = 2.0 * M_PI;
constexpr double kMaxYawSigmaRad = M_PI;
// What a refusal says: "<yaw> rad looks like degrees (<yaw> deg is <radians> rad)".
inline std::string YawLooksLikeDegrees(double yaw) {
  std::ostringstream text;
  text << yaw << " rad looks like degrees (" << yaw << " deg is " << yaw * M_PI / 180.0 << " rad)";
  return text.str();
}

struct PosePrior {
  Pose2 T_site_map;  // the map frame's pose in the site (merged) frame
  double translation_sigma_m = kDefaultPriorTranslationSigmaM;
  double yaw_sigma_rad = kDefaultPriorYawSigmaRad;
};

// Per map, its prior or nullopt; empty when no map has one.
using PosePriors = std::vector<std::optional<PosePrior>>;
inline bool HasPrior(const PosePriors& priors, int m) { return !priors.empty() && priors[m]; }

}  // namespace fleetmerge
