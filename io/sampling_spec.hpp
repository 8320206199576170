// The text form of a point-sampling choice (Section III-D), shared by the command line and job
// files: "all", "random:F" (keep a random fraction F in (0, 1]) or "every:K" (every K-th point).
#pragma once

#include <optional>
#include <string>

#include "core/point_sampling.hpp"

namespace fleetmerge {

// What ParseSamplingSpec accepts, as error messages state it.
inline constexpr const char* kSamplingSpecExpected =
    "'all', 'random:F' with F in (0, 1] or 'every:K' with K >= 1";

// The sampling `text` stands for (seed 0), or nullopt when it is none of the three forms.
std::optional<SamplingOptions> ParseSamplingSpec(const std::string& text);

// As ParseSamplingSpec, for a command-line option: throws fleetmerge::Error naming the option
// and what was expected.
SamplingOptions ParseSampling(const std::string& option, const std::string& text);

}  // namespace fleetmerge
