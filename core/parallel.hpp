// The small concurrency and timing helpers the library shares (the pair search, the pipeline
// stages).
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>

namespace fleetmerge {

// Runs body(k) for k in [0, count) on `threads` threads (<= 0: all cores), the calling thread
// included. Indices are handed out one at a time, so each k runs exactly once; what body writes
// at index k does not depend on the thread count. If any body throws, the remaining indices
// still run and the exception of the lowest index that threw is rethrown here (so which error
// is reported does not depend on the thread count either). The helper threads are kept for the
// next call (a process-wide pool; a body may call ParallelFor itself).
void ParallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& body);

inline double MillisecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace fleetmerge
