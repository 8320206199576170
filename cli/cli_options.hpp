// Command-line options for the method's parameters, shared by the subcommands that merge.
#pragma once

#include <CLI/App.hpp>
#include <string>

#include "pipeline/pair_merge.hpp"

namespace fleetmerge {

// --n-theta, --rho-step, --hough-sampling, --spectra-sampling, --translation, --no-refine, --seed.
void AddMethodOptions(CLI::App& app, PairOptions& options);

}  // namespace fleetmerge
