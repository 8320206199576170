#include "cli/process_threads.hpp"

#include <opencv2/core/utility.hpp>

namespace fleetmerge {

void RunOpenCvOnTheCallingThread() { cv::setNumThreads(0); }

}  // namespace fleetmerge
