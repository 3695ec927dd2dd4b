// Backward relevance analysis (as in Fast Downward's translator): an action
// is relevant when it can add a fact some relevant condition or the goal
// needs true, delete a fact one needs false, or change a numeric variable
// one reads; the conditions, duration and effect expressions of relevant
// actions are relevant in turn (fixpoint).
//
// Dropping the other actions keeps solvability and every plan's validity:
// removing an irrelevant action from a valid plan only keeps facts it would
// have deleted true longer (no relevant condition needs them false) and
// removes interference orderings; nothing relevant reads its adds or its
// numeric effects. The metric's variables count as read, so quality is kept.
// TMS grounds make-structure/bake-structure for every pair of pieces; only
// the pairs in the goal are relevant (50 of 10,000).
#pragma once

#include <vector>

#include "seaplan/task/ground_task.h"

namespace seaplan::search {

// Per action: true when relevant.
std::vector<bool> RelevantActions(const task::GroundTask& task);

}  // namespace seaplan::search
