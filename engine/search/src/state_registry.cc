#include "state_registry.h"

#include <bit>
#include <cstring>

#include "absl/hash/hash.h"
#include "absl/types/span.h"

namespace seaplan::search {

StateRegistry::StateRegistry(int num_facts, int num_vars)
    : num_facts_(num_facts),
      num_vars_(num_vars),
      fact_words_((num_facts + 63) / 64),
      offsets_{0},
      index_(16, Hash{this}, Eq{this}) {}

StateData StateRegistry::MakeEmpty() const {
  StateData s;
  s.facts.assign(static_cast<std::size_t>(fact_words_), 0);
  s.values.assign(static_cast<std::size_t>(num_vars_), 0.0);
  return s;
}

StateId StateRegistry::Insert(const StateData& state, bool* is_new) {
  // Pack at the end of the pool, then look up; pop it again when known.
  const std::size_t begin = pool_.size();
  pool_.insert(pool_.end(), state.facts.begin(), state.facts.end());
  for (double v : state.values) {
    if (v == 0.0) v = 0.0;  // one bit pattern for +0 and -0
    pool_.push_back(std::bit_cast<std::uint64_t>(v));
  }
  pool_.push_back(static_cast<std::uint64_t>(static_cast<std::uint32_t>(state.next_til)) |
                  (static_cast<std::uint64_t>(static_cast<std::uint32_t>(state.variant)) << 32));
  for (const auto& r : state.running) {
    pool_.push_back(static_cast<std::uint64_t>(r.action));
    pool_.push_back(std::bit_cast<std::uint64_t>(r.min_duration_s));
    pool_.push_back(std::bit_cast<std::uint64_t>(r.max_duration_s));
  }
  const auto id = static_cast<std::int32_t>(offsets_.size() - 1);
  offsets_.push_back(pool_.size());
  auto [it, inserted] = index_.insert(id);
  if (!inserted) {
    pool_.resize(begin);
    offsets_.pop_back();
  }
  if (is_new) *is_new = inserted;
  return StateId(*it);
}

void StateRegistry::Unpack(StateId id, StateData* out) const {
  const std::uint64_t* p = Data(id.value());
  const std::size_t len = Length(id.value());
  out->facts.assign(p, p + fact_words_);
  p += fact_words_;
  out->values.resize(static_cast<std::size_t>(num_vars_));
  for (int i = 0; i < num_vars_; ++i) out->values[i] = std::bit_cast<double>(*p++);
  out->next_til = static_cast<std::int32_t>(*p & 0xffffffffu);
  out->variant = static_cast<std::int32_t>(*p++ >> 32);
  const std::size_t rest = len - static_cast<std::size_t>(fact_words_ + num_vars_ + 1);
  out->running.resize(rest / 3);
  for (auto& r : out->running) {
    r.action = static_cast<task::ActionId>(*p++);
    r.min_duration_s = std::bit_cast<double>(*p++);
    r.max_duration_s = std::bit_cast<double>(*p++);
  }
}

std::size_t StateRegistry::MemoryBytes() const {
  return pool_.capacity() * sizeof(std::uint64_t) + offsets_.capacity() * sizeof(std::size_t) +
         index_.capacity() * (sizeof(std::int32_t) + 1);
}

std::size_t StateRegistry::Hash::operator()(std::int32_t id) const {
  const std::uint64_t* p = registry->Data(id);
  const std::size_t len = registry->Length(id);
  return absl::Hash<absl::Span<const std::uint64_t>>{}(absl::MakeConstSpan(p, len));
}

bool StateRegistry::Eq::operator()(std::int32_t a, std::int32_t b) const {
  const std::size_t la = registry->Length(a);
  if (la != registry->Length(b)) return false;
  return std::memcmp(registry->Data(a), registry->Data(b), la * sizeof(std::uint64_t)) == 0;
}

}  // namespace seaplan::search
