// Known start poses (job/pose_prior.hpp) in the fleet merge, beyond the paper: the pair search
// stays blind to them; the priors judge its hypotheses and join the pose graph.
//
// For a pair (a, b) whose two maps both have a known pose P (a prior, or a fixed map's pose with
// sigma 0), the priors predict T_a_b = P_a^-1 P_b. A hypothesis h contradicts them when P_a h is
// more than 3 sigma from P_b, with
//   translation: |t(P_a h) - t(P_b)| / sqrt(s_a^2 + s_b^2 + (yaw_s_a |t(h)|)^2)
//   yaw:         |wrap(yaw(P_a h) - yaw(P_b))| / sqrt(yaw_s_a^2 + yaw_s_b^2)
// (a's yaw error swings b's position by its lever arm |t(h)|). Such hypotheses are dropped; a
// pair left with none is refused, with a note naming the priors and the distance in sigmas.
// Pairs where a map has no known pose, and pairs of two fixed maps (their cycle check judges
// those, pipeline/fleet_graph.hpp), are left as they are.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "job/pose_prior.hpp"
#include "pipeline/all_pairs.hpp"
#include "pipeline/fleet_graph.hpp"

namespace fleetmerge {

// Beyond this many sigmas a hypothesis contradicts the priors.
constexpr double kPriorContradictionSigmas = 3.0;

// Throws fleetmerge::Error for a list of another length than map_count (empty is fine: no
// priors), a non-finite pose or sigma, a sigma <= 0, or a prior on a fixed map (its pose is
// given exactly by `pose`).
// Maps are named by `names` (pipeline/map_label.hpp).
void CheckPriors(const PosePriors& priors, const FixedPoses& fixed, std::size_t map_count,
                 const std::vector<std::string>& names = {});

// How many sigmas hypothesis T_a_b is from the known poses of a and b (see above).
double SigmasFromPriors(const Pose2& T_a_b, const PosePrior& a, const PosePrior& b);

// Drops the hypotheses that contradict the known poses (see above) and marks pairs left with none
// (PairOutcome::refused_by_priors; their hypotheses stay), with a note saying why: "every
// hypothesis contradicts ..." (MergeFleet's thresholds then refuse the pair with it, or put it
// after their own reason), or which hypotheses were dropped. Keeps a pair's measured overlap,
// walls and margin those of its new best.
void DropHypothesesAgainstPriors(std::vector<PairOutcome>& pairs, const FixedPoses& fixed,
                                 const PosePriors& priors,
                                 const std::vector<std::string>& names = {});

}  // namespace fleetmerge
