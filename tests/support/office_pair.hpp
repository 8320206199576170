// The small re-framed pair the wall-agreement and evidence tests judge poses on: a synthetic
// 30 x 20 m office (seed 4) cut into two maps, b turned by 0.7 rad (sim/ground_truth_pair.hpp).
#pragma once

#include <random>

#include "sim/ground_truth_pair.hpp"
#include "sim/synthetic_office.hpp"

namespace fleetmerge::testing {

// The cut is drawn from `rng`, which the tests go on using for the poses they judge.
inline GroundTruthPair CutOfficePair(std::mt19937& rng) {
  OfficeOptions office;
  office.width_m = 30.0;
  office.height_m = 20.0;
  return CutPair(GenerateOfficeFloor(office, 4), 0.7, rng);
}

}  // namespace fleetmerge::testing
