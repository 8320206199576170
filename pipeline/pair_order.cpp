#include "pipeline/pair_order.hpp"

#include "core/error.hpp"

namespace fleetmerge {

PairOrder::PairOrder(std::vector<std::pair<int, int>> pairs, std::size_t map_count)
    : pairs_(std::move(pairs)),
      taken_(pairs_.size(), 0),
      being_prepared_(map_count, 0),
      prepared_(map_count, 0) {
  for (const auto& [a, b] : pairs_) {
    if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= map_count ||
        static_cast<std::size_t>(b) >= map_count) {
      throw Error("PairOrder: pair " + std::to_string(a) + "-" + std::to_string(b) +
                  " of a fleet of " + std::to_string(map_count) + " maps");
    }
  }
}

std::size_t PairOrder::Take() {
  const std::lock_guard<std::mutex> lock(mutex_);
  while (first_left_ < pairs_.size() && taken_[first_left_]) ++first_left_;
  if (first_left_ == pairs_.size()) throw Error("PairOrder: every pair was taken");
  std::size_t pick = first_left_;
  for (std::size_t i = first_left_; i < pairs_.size(); ++i) {
    const auto [a, b] = pairs_[i];
    if (!taken_[i] && !being_prepared_[a] && !being_prepared_[b]) {
      pick = i;
      break;
    }
  }
  taken_[pick] = 1;
  for (const int m : {pairs_[pick].first, pairs_[pick].second}) {
    if (!prepared_[m]) being_prepared_[m] = 1;
  }
  return pick;
}

void PairOrder::Prepared(int m) {
  const std::lock_guard<std::mutex> lock(mutex_);
  being_prepared_[m] = 0;
  prepared_[m] = 1;
}

}  // namespace fleetmerge
