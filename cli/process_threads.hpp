// Which threads the `fleetmerge` process computes on: its own only (--threads). Called first
// thing in main; benchmarks of the commands' code call it too, so that they measure what the
// executable runs. A program that links the library keeps OpenCV's defaults.
#pragma once

namespace fleetmerge {

// Debian's OpenCV runs some functions (cv::LUT on every map loaded, among others) on a TBB
// pool of its own, one worker per core, on top of the pipeline's threads. Starting that pool
// loads TBB's allocator and reads /proc at the first such call, and its workers then compete
// with the pipeline's. With OpenCV on the calling thread (cv::setNumThreads(0)) the outputs are
// the same byte for byte and the 8-robot ACES job and `fleetmerge pair` are faster
// (docs/speed.md, "How the work is shared").
void RunOpenCvOnTheCallingThread();

}  // namespace fleetmerge
