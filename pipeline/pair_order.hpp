// The order in which ComputeAllPairs' threads take the pairs to compute (pipeline/all_pairs.hpp).
// Each pair's outcome is its own, so the order changes no result, only how long threads wait:
// a map is prepared by the first pair that needs it (pipeline/prepared_map.hpp), and a thread
// whose pair needs a map another thread is preparing waits for it. A site's map is the dearest
// to prepare and is in every pair of a site job's first round, so in row order every thread but
// one waited for it (docs/speed.md, "How the work is shared").
#pragma once

#include <cstddef>
#include <mutex>
#include <utility>
#include <vector>

namespace fleetmerge {

class PairOrder {
 public:
  // `pairs`: (a, b) map indices below `map_count`, in row order.
  PairOrder(std::vector<std::pair<int, int>> pairs, std::size_t map_count);

  // The pair (its index in `pairs`) a thread takes next: the first one left whose maps no thread
  // is preparing, or when every pair left waits for such a map, the first one left. Its maps not
  // yet prepared count as being prepared from now on (by this thread, or one it will wait for).
  // Call it at most once per pair.
  std::size_t Take();
  // Map m's preparation is done: its pairs no longer wait.
  void Prepared(int m);

 private:
  std::mutex mutex_;
  std::vector<std::pair<int, int>> pairs_;
  std::vector<char> taken_;
  std::vector<char> being_prepared_, prepared_;  // per map
  std::size_t first_left_ = 0;
};

}  // namespace fleetmerge
