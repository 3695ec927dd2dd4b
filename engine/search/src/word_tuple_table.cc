#include "word_tuple_table.h"

#include <algorithm>

#include "absl/hash/hash.h"
#include "absl/types/span.h"

namespace seaplan::search {

WordTupleTable::WordTupleTable(int fixed_length)
    : fixed_length_(fixed_length), index_(16, Hash{this}, Eq{this}) {
  if (fixed_length_ < 0) offsets_.push_back(0);
}

std::int32_t WordTupleTable::Intern(std::span<const std::uint64_t> words, bool* is_new) {
  // Append, then look up the new id; drop it again when already known.
  const std::size_t begin = pool_.size();
  pool_.insert(pool_.end(), words.begin(), words.end());
  if (fixed_length_ < 0) offsets_.push_back(pool_.size());
  const auto id = static_cast<std::int32_t>(size_);
  ++size_;
  auto [it, inserted] = index_.insert(id);
  if (!inserted) {
    pool_.resize(begin);
    if (fixed_length_ < 0) offsets_.pop_back();
    --size_;
  }
  if (is_new != nullptr) *is_new = inserted;
  return *it;
}

std::size_t WordTupleTable::MemoryBytes() const {
  // The index is a swiss table: one control byte per slot besides the id.
  return pool_.capacity() * sizeof(std::uint64_t) + offsets_.capacity() * sizeof(std::size_t) +
         index_.capacity() * (sizeof(std::int32_t) + 1);
}

std::size_t WordTupleTable::Hash::operator()(std::int32_t id) const {
  const auto words = table->Get(id);
  return absl::Hash<absl::Span<const std::uint64_t>>{}(
      absl::MakeConstSpan(words.data(), words.size()));
}

bool WordTupleTable::Eq::operator()(std::int32_t a, std::int32_t b) const {
  const auto wa = table->Get(a);
  const auto wb = table->Get(b);
  // std::equal, not memcmp: a tuple of no words (a state without numeric
  // values or running actions) may have a null data(), which memcmp must not
  // be given even for length 0 (UBSan reports it); libstdc++ compiles this
  // to memcmp when the length is not zero.
  return std::equal(wa.begin(), wa.end(), wb.begin(), wb.end());
}

}  // namespace seaplan::search
