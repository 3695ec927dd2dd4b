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
  TupleSet() {
    slots_.assign(64, -1);
    tags_.assign(64, 0);
    offsets_.push_back(0);
  }

  std::size_t size() const { return offsets_.size() - 1; }
  std::size_t memory_words() const { return data_.size() + offsets_.size() + slots_.size(); }

  std::span<const std::int32_t> Get(std::int32_t id) const {
    const auto i = static_cast<std::size_t>(id);
    return {data_.data() + offsets_[i], offsets_[i + 1] - offsets_[i]};
  }

  std::int32_t Find(std::span<const std::int32_t> key) const {
    const std::size_t mask = slots_.size() - 1;
    const std::size_t h = Hash(key);
    const auto tag = static_cast<std::uint32_t>(h >> 32);
    for (std::size_t s = h & mask;; s = (s + 1) & mask) {
      const std::int32_t id = slots_[s];
      if (id < 0) return -1;
      if (tags_[s] == tag && Equal(Get(id), key)) return id;
    }
  }

  // Returns (id, inserted).
  std::pair<std::int32_t, bool> Insert(std::span<const std::int32_t> key) {
    if ((size() + 1) * 2 > slots_.size()) Grow();
    const std::size_t mask = slots_.size() - 1;
    const std::size_t h = Hash(key);
    const auto tag = static_cast<std::uint32_t>(h >> 32);
    std::size_t s = h & mask;
    for (;; s = (s + 1) & mask) {
      const std::int32_t id = slots_[s];
      if (id < 0) break;
      if (tags_[s] == tag && Equal(Get(id), key)) return {id, false};
    }
    const auto id = static_cast<std::int32_t>(size());
    data_.insert(data_.end(), key.begin(), key.end());
    offsets_.push_back(static_cast<std::uint32_t>(data_.size()));
    slots_[s] = id;
    tags_[s] = tag;
    return {id, true};
  }

 private:
  static std::size_t Hash(std::span<const std::int32_t> key) {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL ^ key.size();
    for (std::int32_t v : key) {
      h ^= static_cast<std::uint32_t>(v);
      h *= 0xff51afd7ed558ccdULL;
      h ^= h >> 29;
    }
    h *= 0xc4ceb9fe1a85ec53ULL;  // final mix so both halves (slot, tag) are well spread
    h ^= h >> 32;
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
    slots_.assign(slots_.size() * 2, -1);
    tags_.assign(slots_.size(), 0);
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t id = 0; id < size(); ++id) {
      const std::size_t h = Hash(Get(static_cast<std::int32_t>(id)));
      std::size_t s = h & mask;
      while (slots_[s] >= 0) s = (s + 1) & mask;
      slots_[s] = static_cast<std::int32_t>(id);
      tags_[s] = static_cast<std::uint32_t>(h >> 32);
    }
  }

  std::vector<std::int32_t> data_;
  std::vector<std::uint32_t> offsets_;
  std::vector<std::int32_t> slots_;
  std::vector<std::uint32_t> tags_;  // high hash bits per slot: skips most key compares
};

}  // namespace seaplan::task::internal
