#include "state_registry.h"

#include <bit>

namespace seaplan::search {

StateRegistry::StateRegistry(int num_facts, int num_vars)
    : num_facts_(num_facts),
      num_vars_(num_vars),
      fact_words_((num_facts + 63) / 64),
      states_(fact_words_ + 2),
      values_(num_vars),
      running_(-1) {}

StateData StateRegistry::MakeEmpty() const {
  StateData s;
  s.facts.assign(static_cast<std::size_t>(fact_words_), 0);
  s.values.assign(static_cast<std::size_t>(num_vars_), 0.0);
  return s;
}

namespace {
std::uint64_t Pair(std::int32_t low, std::int32_t high) {
  return static_cast<std::uint64_t>(static_cast<std::uint32_t>(low)) |
         (static_cast<std::uint64_t>(static_cast<std::uint32_t>(high)) << 32);
}
std::int32_t Low(std::uint64_t w) {
  return static_cast<std::int32_t>(w & 0xffffffffu);
}
std::int32_t High(std::uint64_t w) {
  return static_cast<std::int32_t>(w >> 32);
}
}  // namespace

StateId StateRegistry::Insert(const StateData& state, bool* is_new) {
  words_.clear();
  for (double v : state.values) {
    if (v == 0.0) v = 0.0;  // one bit pattern for +0 and -0
    words_.push_back(std::bit_cast<std::uint64_t>(v));
  }
  const std::int32_t values_id = values_.Intern(words_, nullptr);
  words_.clear();
  for (const auto& r : state.running) {
    words_.push_back(static_cast<std::uint64_t>(r.action));
    words_.push_back(std::bit_cast<std::uint64_t>(r.min_duration_s));
    words_.push_back(std::bit_cast<std::uint64_t>(r.max_duration_s));
  }
  const std::int32_t running_id = running_.Intern(words_, nullptr);
  packed_.assign(state.facts.begin(), state.facts.end());
  packed_.push_back(Pair(values_id, running_id));
  packed_.push_back(Pair(state.next_til, state.variant));
  return StateId(states_.Intern(packed_, is_new));
}

void StateRegistry::Unpack(StateId id, StateData* out) const {
  const auto packed = states_.Get(id.value());
  const std::uint64_t* p = packed.data();
  out->facts.assign(p, p + fact_words_);
  p += fact_words_;
  const auto values = values_.Get(Low(*p));
  out->values.resize(static_cast<std::size_t>(num_vars_));
  for (int i = 0; i < num_vars_; ++i) out->values[i] = std::bit_cast<double>(values[i]);
  const auto running = running_.Get(High(*p++));
  out->running.resize(running.size() / 3);
  for (std::size_t i = 0; i < out->running.size(); ++i) {
    auto& r = out->running[i];
    r.action = static_cast<task::ActionId>(running[3 * i]);
    r.min_duration_s = std::bit_cast<double>(running[3 * i + 1]);
    r.max_duration_s = std::bit_cast<double>(running[3 * i + 2]);
  }
  out->next_til = Low(*p);
  out->variant = High(*p);
}

std::size_t StateRegistry::MemoryBytes() const {
  return states_.MemoryBytes() + values_.MemoryBytes() + running_.MemoryBytes() +
         (packed_.capacity() + words_.capacity()) * sizeof(std::uint64_t);
}

}  // namespace seaplan::search
