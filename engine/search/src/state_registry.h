// Search states: packed in one pool, named by dense int StateIds (Fast
// Downward's state registry). A state is the set of true facts, the numeric
// values, the running actions (each with the duration bounds fixed at its
// start) and the index of the next timed initial literal. The schedule is
// not part of the state: it is rebuilt from the path (see timeline.h).
//
// Packed layout, the same length for every state (so no offsets): one bit
// per fact, then one word holding the ids of the state's numeric values and
// of its running actions, both interned in side tables (many states share
// them: values change with few actions, and most states run the same few
// actions), then one word with the next timed literal and the variant.
//
// Thread-safety: none; one registry per search.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "seaplan/task/ground_task.h"
#include "word_tuple_table.h"

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
  // Where action `a` is, or would go, in `running` (sorted by action).
  std::vector<RunningAction>::const_iterator FindRunning(task::ActionId a) const {
    return std::lower_bound(
        running.begin(), running.end(), a,
        [](const RunningAction& r, task::ActionId id) { return r.action < id; });
  }
  bool IsRunning(task::ActionId a) const {
    const auto it = FindRunning(a);
    return it != running.end() && it->action == a;
  }
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
  std::size_t size() const { return states_.size(); }
  // Everything the registry holds, allocated capacity included.
  std::size_t MemoryBytes() const;
  // Words of one packed state (side tables not included).
  int packed_words() const { return fact_words_ + 2; }
  // Distinct numeric value vectors and running-action sets stored.
  std::size_t distinct_values() const { return values_.size(); }
  std::size_t distinct_running() const { return running_.size(); }
  int num_facts() const { return num_facts_; }
  int num_vars() const { return num_vars_; }
  StateData MakeEmpty() const;

 private:
  int num_facts_;
  int num_vars_;
  int fact_words_;
  WordTupleTable states_;   // packed states, fixed length
  WordTupleTable values_;   // numeric values (bit patterns), num_vars_ words
  WordTupleTable running_;  // running actions, 3 words each
  // Scratch for Insert.
  std::vector<std::uint64_t> packed_, words_;
};

}  // namespace seaplan::search
