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

// Per action: true when no plan can contain it because it breaks the goal
// for good: it deletes (unconditionally, at start or at end) a goal fact
// that no other action left and no timed literal adds, or adds a fact the
// goal needs false that nothing deletes. `excluded` (empty: none) holds the
// actions already known not to occur (irrelevant ones); they count as
// neither adders nor deleters. To a fixpoint: a fact whose only adders are
// excluded here has none left. Parcprinter: printing colour on a face the
// goal keeps free of colour (a goal fact nothing re-adds), 172 of the 505
// actions of parcprinter-2011 p01.
std::vector<bool> GoalBreakingActions(const task::GroundTask& task,
                                      const std::vector<bool>& excluded);

}  // namespace seaplan::search
