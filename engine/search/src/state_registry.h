// Search states: packed in one pool, named by dense int StateIds (Fast
// Downward's state registry). A state is the set of true facts, the numeric
// values, the running actions (each with the duration bounds fixed at its
// start) and the index of the next timed initial literal. The schedule is
// not part of the state: it is rebuilt from the path (see timeline.h).
//
// Thread-safety: none; one registry per search.
#pragma once

#include <cstdint>
#include <vector>

#include "absl/container/flat_hash_set.h"
#include "seaplan/task/ground_task.h"

namespace seaplan::search {

class StateId {
 public:
  explicit StateId(std::int32_t value) : value_(value) {}
  std::int32_t value() const { return value_; }
  bool operator==(const StateId&) const = default;
  static StateId None() { return StateId(-1); }

 private:
  std::int32_t value_;
};

struct RunningAction {
  task::ActionId action = -1;
  double min_duration_s = 0.0;
  double max_duration_s = 0.0;
  bool operator==(const RunningAction&) const = default;
};

// An unpacked state, used as scratch by successor generation and heuristics.
struct StateData {
  std::vector<std::uint64_t> facts;    // bitset
  std::vector<double> values;          // per numeric variable
  std::vector<RunningAction> running;  // sorted by action
  std::int32_t next_til = 0;
  // Distinguishes copies of one logical state reached with schedules that
  // do not dominate each other (see LazySearch); part of the key.
  std::int32_t variant = 0;

  bool Holds(task::FactId f) const { return (facts[f >> 6] >> (f & 63)) & 1u; }
  void Set(task::FactId f) { facts[f >> 6] |= std::uint64_t{1} << (f & 63); }
  void Clear(task::FactId f) { facts[f >> 6] &= ~(std::uint64_t{1} << (f & 63)); }
};

class StateRegistry {
 public:
  StateRegistry(int num_facts, int num_vars);
  StateRegistry(const StateRegistry&) = delete;
  StateRegistry& operator=(const StateRegistry&) = delete;

  // Returns the id of `state`, registering it if new; `*is_new` tells which.
  StateId Insert(const StateData& state, bool* is_new);
  void Unpack(StateId id, StateData* out) const;
  std::size_t size() const { return offsets_.size() - 1; }
  std::size_t MemoryBytes() const;
  int num_facts() const { return num_facts_; }
  int num_vars() const { return num_vars_; }
  StateData MakeEmpty() const;

 private:
  struct Hash {
    const StateRegistry* registry;
    std::size_t operator()(std::int32_t id) const;
  };
  struct Eq {
    const StateRegistry* registry;
    bool operator()(std::int32_t a, std::int32_t b) const;
  };
  const std::uint64_t* Data(std::int32_t id) const { return pool_.data() + offsets_[id]; }
  std::size_t Length(std::int32_t id) const { return offsets_[id + 1] - offsets_[id]; }

  int num_facts_;
  int num_vars_;
  int fact_words_;
  std::vector<std::uint64_t> pool_;
  std::vector<std::size_t> offsets_;
  absl::flat_hash_set<std::int32_t, Hash, Eq> index_;
};

}  // namespace seaplan::search
