// How overlapping maps' cells are fused into the merged map (pipeline/composite.hpp). An option
// of every job (job/fleet_options.hpp), so it lives below io/ and pipeline/.
#pragma once

namespace fleetmerge {

enum class FusionMode { kLogOdds, kMax, kVote };

}  // namespace fleetmerge
