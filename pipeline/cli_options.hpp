// Command-line options for the method's parameters, shared by the subcommands that merge.
#pragma once

#include <CLI/App.hpp>
#include <string>

#include "core/point_sampling.hpp"
#include "pipeline/pair_merge.hpp"

namespace fleetmerge {

// "all", "random:F" (fraction in (0, 1]) or "every:K"; throws fleetmerge::Error naming the
// option and what was expected.
SamplingOptions ParseSampling(const std::string& option, const std::string& text);

// --n-theta, --hough-sampling, --spectra-sampling, --translation, --no-refine, --seed.
void AddMethodOptions(CLI::App& app, PairOptions& options);

}  // namespace fleetmerge
