// Interchangeable objects (state symmetry; Pochter, Zohar and Rosenschein
// 2011, Fox and Long 1999) for duplicate detection in the search.
//
// Two objects are interchangeable when swapping their names maps the ground
// task onto itself: every fact and action to an existing one, every action's
// conditions, effects and durations to those of its image, the goal and the
// timed literals to themselves (the initial state need not be symmetric).
// A state and its image under such a swap then have the same futures up to
// the swap: one of them need not be searched. Swaps that hold chain into
// classes of objects (crates that only the goal names, all alike), and any
// permutation within a class is a symmetry too.
//
// Only classes whose objects never appear two in one fact or one action,
// and in no numeric variable, are used: for them the state's facts and
// running actions that name a member describe that member alone, so
// sorting the members by those descriptions and renaming them in that
// order gives the same state for any two states that differ by a
// permutation of the class. Classes are canonicalised one after another;
// the result is always a symmetric image of the state (sound), though two
// symmetric states may keep different keys when facts link two classes.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "snap_task.h"
#include "state_registry.h"

namespace seaplan::search {

class ObjectSymmetry {
 public:
  explicit ObjectSymmetry(const SnapTask& task);

  // True when some class has two or more members.
  bool active() const { return !classes_.empty(); }
  int num_classes() const { return static_cast<int>(classes_.size()); }
  // Objects in classes of two or more (a diagnostic).
  int num_symmetric_objects() const;

  // `out` becomes the image of `state` with every class's members renamed
  // in the order of their descriptions (facts and running actions naming
  // them); two states that differ by a permutation of one class get the
  // same image. Numeric values, the next timed literal and the variant are
  // copied.
  void Canonicalize(const StateData& state, StateData* out) const;

 private:
  struct Class {
    // Members; member 0 is the representative.
    std::vector<int> objects;
    // Per member i: the facts / actions naming it, and the position of
    // each one's image under the swap of member i with member 0 in member
    // 0's lists (the identity for member 0).
    std::vector<std::vector<task::FactId>> facts;
    std::vector<std::vector<std::int32_t>> fact_rep_pos;
    std::vector<std::vector<task::FactId>> fact_from_rep;  // per member, indexed like rep's facts
    std::vector<std::vector<task::ActionId>> actions;
    std::vector<std::vector<std::int32_t>> action_rep_pos;
    std::vector<std::vector<task::ActionId>> action_from_rep;
  };

  const SnapTask& task_;
  std::vector<Class> classes_;
  // Scratch.
  mutable std::vector<std::vector<std::int32_t>> signature_;
  // Per member: (index in the state's running actions, position of its
  // image in the representative's actions) of the running actions naming it.
  mutable std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>> running_of_member_;
  mutable std::vector<char> named_;
  mutable std::vector<int> order_;
  mutable StateData scratch_;
};

}  // namespace seaplan::search
