// A best-first open list over (key, key, id) entries holding ids only
// (per-state data lives in side tables). One key is an integer (a heuristic
// value), the other real (a time); the list is told which one comes first.
// Ties on both go to the smaller id: callers hand out ids in insertion
// order, so ties are FIFO and results never depend on hash-table iteration,
// without an insertion counter per entry. An entry is 16 bytes: the search
// holds one or two per generated state.
#pragma once

#include <cstdint>
#include <queue>
#include <vector>

namespace seaplan::search {

struct OpenEntry {
  double real_key;
  std::int32_t int_key;
  std::int32_t state;
};
static_assert(sizeof(OpenEntry) == 16);

class TieBreakingOpenList {
 public:
  enum class KeyOrder { kIntegerFirst, kRealFirst };
  explicit TieBreakingOpenList(KeyOrder order = KeyOrder::kIntegerFirst) : heap_(Later{order}) {}

  void Insert(std::int32_t int_key, double real_key, std::int32_t state) {
    heap_.push(OpenEntry{real_key, int_key, state});
  }
  bool empty() const { return heap_.empty(); }
  std::size_t size() const { return heap_.size(); }
  OpenEntry Pop() {
    OpenEntry e = heap_.top();
    heap_.pop();
    return e;
  }
  // The heap's vector as allocated (it grows by doubling).
  std::size_t MemoryBytes() const { return heap_.capacity() * sizeof(OpenEntry); }

 private:
  // "a comes out after b": the heap's comparison (a max-heap of it).
  struct Later {
    KeyOrder order;
    bool operator()(const OpenEntry& a, const OpenEntry& b) const {
      if (order == KeyOrder::kIntegerFirst) {
        if (a.int_key != b.int_key) return a.int_key > b.int_key;
        if (a.real_key != b.real_key) return a.real_key > b.real_key;
      } else {
        if (a.real_key != b.real_key) return a.real_key > b.real_key;
        if (a.int_key != b.int_key) return a.int_key > b.int_key;
      }
      return a.state > b.state;
    }
  };
  // The priority queue hides its vector; this exposes its capacity.
  struct Heap : std::priority_queue<OpenEntry, std::vector<OpenEntry>, Later> {
    explicit Heap(Later later)
        : std::priority_queue<OpenEntry, std::vector<OpenEntry>, Later>(later) {}
    std::size_t capacity() const { return c.capacity(); }
  };
  Heap heap_;
};

}  // namespace seaplan::search
