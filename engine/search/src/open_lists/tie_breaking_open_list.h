// A best-first open list over (primary, secondary, insertion order) keys
// holding StateIds only (per-state data lives in side tables). Insertion
// order makes ties FIFO, so results never depend on hash-table iteration.
#pragma once

#include <cstdint>
#include <queue>
#include <vector>

namespace seaplan::search {

struct OpenEntry {
  double primary;
  double secondary;
  std::uint64_t order;
  std::int32_t state;
  bool operator>(const OpenEntry& o) const {
    if (primary != o.primary) return primary > o.primary;
    if (secondary != o.secondary) return secondary > o.secondary;
    return order > o.order;
  }
};

class TieBreakingOpenList {
 public:
  void Insert(double primary, double secondary, std::int32_t state) {
    heap_.push(OpenEntry{primary, secondary, next_order_++, state});
  }
  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  OpenEntry Pop() {
    OpenEntry e = heap_.top();
    heap_.pop();
    return e;
  }
  void Clear() { heap_ = {}; }
  std::size_t MemoryBytes() const { return heap_.size() * sizeof(OpenEntry) * 2; }

 private:
  std::priority_queue<OpenEntry, std::vector<OpenEntry>, std::greater<>> heap_;
  std::uint64_t next_order_ = 0;
};

}  // namespace seaplan::search
