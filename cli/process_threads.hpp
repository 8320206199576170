// Which threads the `fleetmerge` process computes on: its own only (--threads). Called first
// thing in main; benchmarks of the commands' code call it too, so that they measure what the
// executable runs. A program that links the library keeps OpenCV's defaults.
#pragma once

namespace fleetmerge {

// Debian's OpenCV runs some functions (cv::LUT on every map loaded, cv::compare, ...) on a TBB
// pool of its own, one worker per core, on top of the pipeline's threads. Starting that pool
// loads TBB's allocator and reads /proc at the first such call, and its workers then compete
// with the pipeline's: with OpenCV on the calling thread (cv::setNumThreads(0)) the 8-robot
// ACES job took 541 ms against 558 ms and `fleetmerge pair` 57.8 ms against 59.3 ms
// (interleaved medians, docs/speed.md), with the same outputs byte for byte.
void RunOpenCvOnTheCallingThread();

}  // namespace fleetmerge
