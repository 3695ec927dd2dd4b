// A best-first open list over (primary, secondary, id) keys holding ids only
// (per-state data lives in side tables). Ties on both keys go to the smaller
// id: callers hand out ids in insertion order, so ties are FIFO and results
// never depend on hash-table iteration, without storing an insertion counter
// per entry (24 bytes an entry instead of 32).
#pragma once

#include <cstdint>
#include <queue>
#include <vector>

namespace seaplan::search {

struct OpenEntry {
  double primary;
  double secondary;
  std::int32_t state;
  bool operator>(const OpenEntry& o) const {
    if (primary != o.primary) return primary > o.primary;
    if (secondary != o.secondary) return secondary > o.secondary;
    return state > o.state;
  }
};

class TieBreakingOpenList {
 public:
  void Insert(double primary, double secondary, std::int32_t state) {
    heap_.push(OpenEntry{primary, secondary, state});
  }
  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  OpenEntry Pop() {
    OpenEntry e = heap_.top();
    heap_.pop();
    return e;
  }
  void Clear() { heap_ = {}; }
  // The heap's vector as allocated (it grows by doubling).
  std::size_t MemoryBytes() const;

 private:
  // The priority queue hides its vector; keep it here to read its capacity.
  struct Heap : std::priority_queue<OpenEntry, std::vector<OpenEntry>, std::greater<>> {
    std::size_t capacity() const { return c.capacity(); }
  };
  Heap heap_;
};

inline std::size_t TieBreakingOpenList::MemoryBytes() const {
  return heap_.capacity() * sizeof(OpenEntry);
}

}  // namespace seaplan::search
