// Helpers the engine/search unit tests share: loading a task from text,
// ground actions and facts by their display name, and the initial state of
// a task. A name that is not grounded is a test failure (ADD_FAILURE) and
// yields id 0, a valid index, so the test goes on to report its other
// checks.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <memory>
#include <string_view>

#include "heuristics/relaxed_plan_heuristic.h"
#include "seaplan/search/planner.h"
#include "seaplan/task/ground_task.h"
#include "seaplan/task/grounder.h"
#include "snap_task.h"
#include "state_registry.h"
#include "timeline.h"
#include "transitions.h"

namespace seaplan::search::testing {

inline task::ActionId ActionIdOf(const task::GroundTask& task, std::string_view display_name) {
  for (std::size_t a = 0; a < task.actions.size(); ++a) {
    if (task.actions[a].DisplayName() == display_name) return static_cast<task::ActionId>(a);
  }
  ADD_FAILURE() << "no action " << display_name;
  return 0;
}

inline task::FactId FactIdOf(const task::GroundTask& task, std::string_view display_name) {
  for (std::size_t f = 0; f < task.facts.size(); ++f) {
    if (task.facts[f].DisplayName() == display_name) return static_cast<task::FactId>(f);
  }
  ADD_FAILURE() << "no fact " << display_name;
  return 0;
}

// Grounds a test's own domain and problem text; a task that does not load
// is a test failure (with the loader's errors) and yields null.
inline std::shared_ptr<const task::GroundTask> LoadTaskOrFail(std::string_view domain,
                                                              std::string_view problem) {
  auto loaded = task::LoadTask(domain, problem);
  EXPECT_TRUE(loaded.ok()) << loaded.ErrorText();
  return loaded.ok() ? loaded.task : nullptr;
}

// The task's initial facts and numeric values, no running action.
inline StateData InitialState(const task::GroundTask& task, const SnapTask& snap) {
  StateRegistry registry(snap.num_facts(), snap.num_vars());
  StateData state = registry.MakeEmpty();
  for (auto f : task.initial_facts) state.Set(f);
  for (std::size_t v = 0; v < state.values.size(); ++v) state.values[v] = task.initial_values[v];
  return state;
}

// The planner on `task` up to its first plan and the bounded searches
// after it (no anytime phases), within 10 s.
inline PlanResult SolveFirstPlan(const task::GroundTask& task) {
  PlannerOptions options;
  options.anytime = false;
  options.time_limit_s = 10;
  return SolveTask(task, options, StopToken());
}

// What a LazySearch borrows, built for `task` with the planner's default
// epsilon and no concurrency bound.
struct SearchParts {
  static constexpr double kEpsilonS = 0.001;
  explicit SearchParts(const task::GroundTask& task)
      : snap(task),
        registry(snap.num_facts(), snap.num_vars()),
        heuristic(snap, kEpsilonS),
        transitions(snap, 0, kEpsilonS),
        timeline(snap, kEpsilonS) {}
  SnapTask snap;
  StateRegistry registry;
  RelaxedPlanHeuristic heuristic;
  Transitions transitions;
  Timeline timeline;
};

}  // namespace seaplan::search::testing
