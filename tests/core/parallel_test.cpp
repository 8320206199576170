// ParallelFor (core/parallel.hpp): every index runs exactly once, and when bodies throw the
// error rethrown is the lowest index's, whatever the thread count and timing; nested calls and
// forked children keep working with the kept workers.
#include "core/parallel.hpp"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

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

// Bodies that run ParallelFor themselves (a fleet's pairs, each spreading its own stages) on
// more threads than the machine has: every inner index runs once and nothing waits for a worker
// that waits for it.
TEST(ParallelFor, NestedCallsRunEveryIndexOnce) {
  for (int round = 0; round < 20; ++round) {
    std::vector<std::atomic<int>> runs(8 * 16);
    ParallelFor(8, 4, [&](std::size_t outer) {
      ParallelFor(16, 3, [&](std::size_t inner) { ++runs[outer * 16 + inner]; });
    });
    for (std::size_t k = 0; k < runs.size(); ++k) ASSERT_EQ(runs[k], 1) << k;
  }
}

// Several callers at once (threads of a program that links the library, each merging a pair)
// share the kept workers: each call still runs its own indices once and returns when they ran.
TEST(ParallelFor, ConcurrentCallersEachRunTheirOwnIndicesOnce) {
  constexpr int kCallers = 4, kRounds = 50, kCount = 40;
  std::vector<std::vector<std::atomic<int>>> runs(kCallers);
  for (auto& r : runs) r = std::vector<std::atomic<int>>(kCount);
  std::vector<std::thread> callers;
  for (int c = 0; c < kCallers; ++c) {
    callers.emplace_back([&, c] {
      for (int round = 0; round < kRounds; ++round) {
        ParallelFor(kCount, 3, [&](std::size_t k) {
          ParallelFor(2, 2, [&](std::size_t half) { runs[c][k] += half == 0 ? 1 : 0; });
        });
        for (int k = 0; k < kCount; ++k) {
          if (runs[c][k] != round + 1) ADD_FAILURE() << "caller " << c << " index " << k;
        }
      }
    });
  }
  for (auto& t : callers) t.join();
}

// Workers are kept between calls; a child made by fork() has none of them and must not wait
// for its parent's.
TEST(ParallelFor, WorksInAForkedChildAfterThePoolStarted) {
  std::atomic<int> sum{0};
  ParallelFor(64, 4, [&](std::size_t k) { sum += static_cast<int>(k); });
  ASSERT_EQ(sum, 64 * 63 / 2);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    alarm(20);  // a child stuck waiting for a worker is killed, and the test fails
    std::atomic<int> child_sum{0};
    ParallelFor(64, 4, [&](std::size_t k) { child_sum += static_cast<int>(k); });
    _exit(child_sum == 64 * 63 / 2 ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << "the child did not finish (signal " << WTERMSIG(status) << ")";
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace fleetmerge
