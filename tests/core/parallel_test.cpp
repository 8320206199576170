// ParallelFor (core/parallel.hpp): every index runs exactly once, and when bodies throw the
// error rethrown is the lowest index's, whatever the thread count and timing.
#include "core/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace fleetmerge {
namespace {

TEST(ParallelFor, RunsEveryIndexOnceForAnyThreadCount) {
  for (const int threads : {1, 2, 3, 8, 0}) {
    std::vector<std::atomic<int>> runs(100);
    ParallelFor(runs.size(), threads, [&](std::size_t k) { ++runs[k]; });
    for (std::size_t k = 0; k < runs.size(); ++k) EXPECT_EQ(runs[k], 1) << k << ", " << threads;
  }
  ParallelFor(0, 2, [](std::size_t) { FAIL() << "no index to run"; });
}

TEST(ParallelFor, RethrowsTheLowestFailingIndexAfterRunningTheRest) {
  for (const int threads : {1, 2, 4}) {
    for (int trial = 0; trial < 20; ++trial) {
      std::atomic<int> ran{0};
      try {
        ParallelFor(40, threads, [&](std::size_t k) {
          ++ran;
          // Index 7 fails late and 30 early, so in time 30 usually fails first.
          if (k == 7) {
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
            throw std::runtime_error("index 7");
          }
          if (k == 30) throw std::runtime_error("index 30");
        });
        FAIL() << "nothing was rethrown";
      } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "index 7") << threads << " threads";
      }
      EXPECT_EQ(ran, 40);
    }
  }
}

}  // namespace
}  // namespace fleetmerge
