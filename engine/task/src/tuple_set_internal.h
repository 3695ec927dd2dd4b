// Interning of small integer tuples (ground atoms, function terms, action
// bindings): the grounder's replacement for string-keyed maps. Open
// addressing over a flat array; ids are dense and stable.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace seaplan::task::internal {

class TupleSet {
 public:
  TupleSet() { slots_.assign(64, -1); offsets_.push_back(0); }

  std::size_t size() const { return offsets_.size() - 1; }
  std::size_t memory_words() const { return data_.size() + offsets_.size() + slots_.size(); }

  std::span<const std::int32_t> Get(std::int32_t id) const {
    const auto i = static_cast<std::size_t>(id);
    return {data_.data() + offsets_[i], offsets_[i + 1] - offsets_[i]};
  }

  std::int32_t Find(std::span<const std::int32_t> key) const {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t s = Hash(key) & mask;; s = (s + 1) & mask) {
      const std::int32_t id = slots_[s];
      if (id < 0) return -1;
      if (Equal(Get(id), key)) return id;
    }
  }

  // Returns (id, inserted).
  std::pair<std::int32_t, bool> Insert(std::span<const std::int32_t> key) {
    if ((size() + 1) * 2 > slots_.size()) Grow();
    const std::size_t mask = slots_.size() - 1;
    std::size_t s = Hash(key) & mask;
    for (;; s = (s + 1) & mask) {
      const std::int32_t id = slots_[s];
      if (id < 0) break;
      if (Equal(Get(id), key)) return {id, false};
    }
    const auto id = static_cast<std::int32_t>(size());
    data_.insert(data_.end(), key.begin(), key.end());
    offsets_.push_back(static_cast<std::uint32_t>(data_.size()));
    slots_[s] = id;
    return {id, true};
  }

 private:
  static std::size_t Hash(std::span<const std::int32_t> key) {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL ^ key.size();
    for (std::int32_t v : key) {
      h ^= static_cast<std::uint32_t>(v);
      h *= 0xff51afd7ed558ccdULL;
      h ^= h >> 32;
    }
    return static_cast<std::size_t>(h);
  }
  static bool Equal(std::span<const std::int32_t> a, std::span<const std::int32_t> b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i] != b[i]) return false;
    }
    return true;
  }
  void Grow() {
    std::vector<std::int32_t> old(slots_.size() * 2, -1);
    old.swap(slots_);
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t id = 0; id < size(); ++id) {
      std::size_t s = Hash(Get(static_cast<std::int32_t>(id))) & mask;
      while (slots_[s] >= 0) s = (s + 1) & mask;
      slots_[s] = static_cast<std::int32_t>(id);
    }
  }

  std::vector<std::int32_t> data_;
  std::vector<std::uint32_t> offsets_;
  std::vector<std::int32_t> slots_;
};

}  // namespace seaplan::task::internal
