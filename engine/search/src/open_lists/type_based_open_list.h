// Type-based exploration (Xie, Müller and Holte, AAAI 2014, "Type-based
// exploration with multiple search queues for satisficing planning"):
// entries are bucketed by their type, here (h, depth), and a pop takes a
// bucket uniformly at random among the non-empty ones, then an entry
// uniformly at random within it. Alternated with the best-first lists, it
// samples every region the search has reached, however bad its h, so that
// a greedy search stuck on a plateau also expands states far from it.
//
// Holds ids only (4 bytes an entry plus one bucket per type). The random
// choices come from the list's own generator, seeded by the caller: the
// same insertions and seed give the same pops. Not thread-safe.
#pragma once

#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"

namespace seaplan::search {

class TypeBasedOpenList {
 public:
  explicit TypeBasedOpenList(std::uint64_t seed) : rng_(seed) {}

  void Insert(std::int32_t h, std::int32_t depth, std::int32_t id) {
    const std::uint64_t key = Key(h, depth);
    auto [it, inserted] = bucket_of_.try_emplace(key, static_cast<std::int32_t>(buckets_.size()));
    if (inserted) buckets_.push_back(Bucket{key, {}});
    std::vector<std::int32_t>& ids = buckets_[static_cast<std::size_t>(it->second)].ids;
    const std::size_t capacity = ids.capacity();
    ids.push_back(id);
    id_capacity_ += ids.capacity() - capacity;
    ++size_;
  }
  bool empty() const { return size_ == 0; }
  std::size_t size() const { return size_; }
  // Number of distinct types with entries.
  std::size_t num_types() const { return buckets_.size(); }

  // A random entry of a random type; the list must not be empty.
  std::int32_t Pop() {
    const std::size_t b = Uniform(buckets_.size());
    std::vector<std::int32_t>& ids = buckets_[b].ids;
    const std::size_t i = Uniform(ids.size());
    const std::int32_t id = ids[i];
    ids[i] = ids.back();
    ids.pop_back();
    --size_;
    if (ids.empty()) {
      // Drop the bucket: the last one takes its place.
      id_capacity_ -= ids.capacity();
      bucket_of_.erase(buckets_[b].key);
      if (b + 1 != buckets_.size()) {
        buckets_[b] = std::move(buckets_.back());
        bucket_of_[buckets_[b].key] = static_cast<std::int32_t>(b);
      }
      buckets_.pop_back();
    }
    return id;
  }

  // Constant time (the planner polls it every few expansions, and a search
  // reaches thousands of types): the buckets' capacities are summed as
  // they change.
  std::size_t MemoryBytes() const {
    return buckets_.capacity() * sizeof(Bucket) +
           bucket_of_.capacity() * (sizeof(std::uint64_t) + sizeof(std::int32_t) + 1) +
           id_capacity_ * sizeof(std::int32_t);
  }

 private:
  struct Bucket {
    std::uint64_t key;
    std::vector<std::int32_t> ids;
  };
  static std::uint64_t Key(std::int32_t h, std::int32_t depth) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(h)) << 32) |
           static_cast<std::uint32_t>(depth);
  }
  // In [0, n): the modulo's bias is below n / 2^64, nothing next to the
  // sizes here; unlike std::uniform_int_distribution it is the same on
  // every standard library.
  std::size_t Uniform(std::size_t n) { return static_cast<std::size_t>(rng_() % n); }

  std::mt19937_64 rng_;
  std::vector<Bucket> buckets_;
  absl::flat_hash_map<std::uint64_t, std::int32_t> bucket_of_;
  std::size_t size_ = 0;
  std::size_t id_capacity_ = 0;  // sum of the buckets' ids.capacity()
};

}  // namespace seaplan::search
