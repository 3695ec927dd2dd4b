// Monotone priority queue of (time, id) pairs: a radix heap (Ahuja,
// Mehlhorn, Orlin and Tarjan 1990) over the bit patterns of non-negative
// doubles, whose order as unsigned integers is the order of the times.
//
// Monotone: every pushed time is at least the last popped one, which is
// what a Dijkstra-style exploration in time order does. In exchange a pop
// moves each entry down at most 64 buckets over its life, with no
// comparisons between entries: a binary heap's sift-down mispredicts a
// branch per level, and on trucks' deadline reachability, whose queue
// holds thousands of entries per evaluation, it was a fifth of the search's
// time (bench/planner/README.md, "Deadline reachability per state, and
// restarts under deadlines").
//
// Entries of equal time pop in no specified order. Not thread-safe;
// buckets keep their capacity across Clear(), so a warmed-up queue
// allocates nothing.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace seaplan::search {

class RadixTimeQueue {
 public:
  struct Entry {
    double time_s;
    std::int32_t id;
  };

  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }

  // Empties the queue and lets it start again from time 0.
  void Clear() {
    for (auto& bucket : buckets_) bucket.clear();
    last_ = 0;
    size_ = 0;
  }

  // `time_s` >= 0 and >= the time of the last Pop() since Clear().
  void Push(double time_s, std::int32_t id) {
    const std::uint64_t key = Key(time_s);
    buckets_[Bucket(key)].push_back({time_s, id});
    ++size_;
  }

  // An entry of the least time. Requires !empty().
  Entry Pop() {
    if (buckets_[0].empty()) Refill();
    const Entry entry = buckets_[0].back();
    buckets_[0].pop_back();
    --size_;
    return entry;
  }

 private:
  // Negative zero and (out of contract) negative times key as 0.
  static std::uint64_t Key(double time_s) {
    return time_s > 0 ? std::bit_cast<std::uint64_t>(time_s) : 0;
  }
  // 0 for keys equal to last_, else 1 + the highest bit in which they differ.
  std::size_t Bucket(std::uint64_t key) const {
    return key == last_ ? 0 : static_cast<std::size_t>(64 - std::countl_zero(key ^ last_));
  }
  // Moves the least non-empty bucket's entries into lower buckets, with
  // last_ its least key: they land in buckets below the one they left.
  void Refill() {
    std::size_t i = 1;
    while (buckets_[i].empty()) ++i;
    std::uint64_t least = Key(buckets_[i].front().time_s);
    for (const Entry& e : buckets_[i]) least = std::min(least, Key(e.time_s));
    last_ = least;
    for (const Entry& e : buckets_[i]) buckets_[Bucket(Key(e.time_s))].push_back(e);
    buckets_[i].clear();
  }

  std::array<std::vector<Entry>, 65> buckets_;
  std::uint64_t last_ = 0;
  std::size_t size_ = 0;
};

}  // namespace seaplan::search
