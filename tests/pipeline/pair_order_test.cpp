// The order in which ComputeAllPairs' threads take pairs (pipeline/pair_order.hpp), played out
// step by step as threads would: what a thread takes while another prepares a map, against the
// rule worked by hand.
#include "pipeline/pair_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "core/error.hpp"

namespace fleetmerge {
namespace {

std::vector<std::pair<int, int>> AllPairs(int maps) {
  std::vector<std::pair<int, int>> pairs;
  for (int a = 0; a < maps; ++a) {
    for (int b = a + 1; b < maps; ++b) pairs.emplace_back(a, b);
  }
  return pairs;
}

// A site job: map 0 (the site) and three robots, no pair cached. While the first thread
// prepares the site (and robot 1), the second computes the pair of robots 2 and 3, then the one
// pair left without the site or robot 1 in the making; only then does it wait for the site.
TEST(PairOrderTest, ThreadsTakeThePairsWhoseMapsNobodyIsPreparing) {
  const std::vector<std::pair<int, int>> pairs = AllPairs(4);  // 01 02 03 12 13 23
  PairOrder order(pairs, 4);
  EXPECT_EQ(order.Take(), 0u);  // 0-1: maps 0 and 1 are being prepared
  EXPECT_EQ(order.Take(), 5u);  // 2-3, not 0-2 (which waits for map 0)
  order.Prepared(2);
  order.Prepared(3);
  // Every pair left has map 0 or 1, both still in the making: the first one left.
  EXPECT_EQ(order.Take(), 1u);  // 0-2
  order.Prepared(0);
  order.Prepared(1);
  EXPECT_EQ(order.Take(), 2u);  // 0-3, in row order again
  EXPECT_EQ(order.Take(), 3u);
  EXPECT_EQ(order.Take(), 4u);
  EXPECT_THROW(order.Take(), Error);  // ParallelFor asks once per pair
}

// A re-run with one new map: every pair left has it, so the order is row order.
TEST(PairOrderTest, PairsThatAllShareOneNewMapKeepRowOrder) {
  std::vector<std::pair<int, int>> pairs;
  for (int a = 0; a < 6; ++a) pairs.emplace_back(a, 6);
  PairOrder order(pairs, 7);
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    EXPECT_EQ(order.Take(), i);
    if (i == 1) order.Prepared(6);
  }
}

// Any interleaving of takes and preparations hands out every pair exactly once.
TEST(PairOrderTest, EveryPairIsTakenOnce) {
  const std::vector<std::pair<int, int>> pairs = AllPairs(9);
  PairOrder order(pairs, 9);
  std::vector<int> times(pairs.size(), 0);
  for (std::size_t n = 0; n < pairs.size(); ++n) {
    const std::size_t i = order.Take();
    ASSERT_LT(i, pairs.size());
    ++times[i];
    if (n % 3 == 0) order.Prepared(pairs[i].first);  // some maps finish, others stay pending
  }
  EXPECT_TRUE(std::all_of(times.begin(), times.end(), [](int t) { return t == 1; }));
}

TEST(PairOrderTest, APairBeyondTheFleetIsRefused) {
  EXPECT_THROW(PairOrder({{0, 3}}, 3), Error);
  EXPECT_THROW(PairOrder({{-1, 2}}, 3), Error);
}

}  // namespace
}  // namespace fleetmerge
