// What put a map where it is in its component's frame, and its name in report.json
// (`placed_by`). Apart from pipeline/fleet_graph so that a pair's report, which names it, does
// not link the pose graph (and Ceres' solvers) into `fleetmerge pair`.
#pragma once

namespace fleetmerge {

enum class PlacedBy {
  kFixed,      // a fixed map: at its given pose
  kReference,  // its component's reference map (its frame, or the site frame with priors)
  kPairs,      // accepted pairs link it to its component's reference (or to a fixed map)
  // Known start poses put it (and the maps accepted pairs link it to, its group) in the site
  // frame: no accepted pair links it to a fixed map or, without fixed maps, to the largest
  // group of the maps with priors (pipeline/fleet_graph.hpp).
  kPrior,
  kUnmerged,  // alone in its component
};

// "fixed", "reference", "pairs", "prior", "unmerged"
inline const char* PlacedByName(PlacedBy placed_by) {
  switch (placed_by) {
    case PlacedBy::kFixed:
      return "fixed";
    case PlacedBy::kReference:
      return "reference";
    case PlacedBy::kPairs:
      return "pairs";
    case PlacedBy::kPrior:
      return "prior";
    case PlacedBy::kUnmerged:
      break;
  }
  return "unmerged";
}

}  // namespace fleetmerge
