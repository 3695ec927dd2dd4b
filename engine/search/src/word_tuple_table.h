// Interns tuples of 64-bit words: equal tuples get the same dense id (0, 1,
// ...), and each distinct tuple is stored once, back to back in one pool.
// The state registry keeps its packed states in one (fixed length: no
// offsets) and the numeric values and running actions of states in others,
// so a state refers to them by a 32-bit id and equal parts are shared.
//
// Thread-safety: none.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "absl/container/flat_hash_set.h"

namespace seaplan::search {

class WordTupleTable {
 public:
  // `fixed_length` >= 0: every tuple has that many words; < 0: any length
  // (an offset per tuple is kept).
  explicit WordTupleTable(int fixed_length);
  WordTupleTable(const WordTupleTable&) = delete;
  WordTupleTable& operator=(const WordTupleTable&) = delete;

  // The id of `words`, added when new (`*is_new` tells which; may be null).
  // Allocates only when the pool or the index grows.
  std::int32_t Intern(std::span<const std::uint64_t> words, bool* is_new);
  std::span<const std::uint64_t> Get(std::int32_t id) const {
    return {pool_.data() + Begin(id), End(id) - Begin(id)};
  }
  std::size_t size() const { return size_; }
  std::size_t MemoryBytes() const;

 private:
  struct Hash {
    const WordTupleTable* table;
    std::size_t operator()(std::int32_t id) const;
  };
  struct Eq {
    const WordTupleTable* table;
    bool operator()(std::int32_t a, std::int32_t b) const;
  };
  std::size_t Begin(std::int32_t id) const {
    const auto i = static_cast<std::size_t>(id);
    return fixed_length_ >= 0 ? i * static_cast<std::size_t>(fixed_length_) : offsets_[i];
  }
  std::size_t End(std::int32_t id) const { return Begin(id + 1); }

  int fixed_length_;
  std::size_t size_ = 0;
  std::vector<std::uint64_t> pool_;
  std::vector<std::size_t> offsets_;  // variable length only: size_ + 1 entries
  absl::flat_hash_set<std::int32_t, Hash, Eq> index_;
};

}  // namespace seaplan::search
