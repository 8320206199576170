// The sampling experiment's plot (like the paper's Fig. 6 and 7, both samplings in one figure):
// three stacked panels over the fraction of points kept (log scale), random sampling in blue,
// every k-th point in red: median time per pair, best omega (mean, bars from the lowest to the
// highest), and the share of trials whose best hypothesis is right (within 1 degree and 3 cells).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "sim/sampling_experiment.hpp"

namespace fleetmerge {

// A BGR image; `title` goes on top.
cv::Mat DrawSamplingPlot(const std::vector<SamplingSummary>& summary, const std::string& title);

}  // namespace fleetmerge
