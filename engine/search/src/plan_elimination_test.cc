#include "plan_elimination.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "search_test_util.h"

namespace seaplan::search {
namespace {

using testing::ActionIdOf;
using testing::InitialState;
using testing::LoadTaskOrFail;

// A ship sails between three ports and carries one box from a to c; a
// light stays switched on from the start to the end of a shift.
constexpr std::string_view kDomain = R"(
(define (domain detours)
  (:requirements :typing :durative-actions)
  (:types port)
  (:predicates (ship-at ?p - port) (box-at ?p - port) (box-on-ship) (light-on) (shift-over))
  (:durative-action sail
    :parameters (?from ?to - port)
    :duration (= ?duration 10)
    :condition (at start (ship-at ?from))
    :effect (and (at start (not (ship-at ?from))) (at end (ship-at ?to))))
  (:durative-action load
    :parameters (?p - port)
    :duration (= ?duration 2)
    :condition (and (at start (ship-at ?p)) (at start (box-at ?p)))
    :effect (and (at start (not (box-at ?p))) (at end (box-on-ship))))
  (:durative-action unload
    :parameters (?p - port)
    :duration (= ?duration 2)
    :condition (and (at start (ship-at ?p)) (at start (box-on-ship)))
    :effect (and (at start (not (box-on-ship))) (at end (box-at ?p))))
  (:durative-action shift
    :parameters ()
    :duration (= ?duration 100)
    :condition (at start (light-on))
    :effect (at end (shift-over))))
)";

constexpr std::string_view kProblem = R"(
(define (problem carry) (:domain detours)
  (:objects a b c - port)
  (:init (ship-at a) (box-at a) (light-on))
  (:goal (box-at c)))
)";

struct Fixture {
  std::shared_ptr<const task::GroundTask> task = LoadTaskOrFail(kDomain, kProblem);
  SnapTask snap{*task};
  Transitions transitions{snap, 0, 0.001};
  StateData initial = InitialState(*task, snap);

  // The start and end events of each named action, one after the other.
  std::vector<Event> Steps(const std::vector<std::string>& names) const {
    std::vector<Event> events;
    for (const auto& name : names) {
      const SnapId start = 2 * ActionIdOf(*task, name);
      events.push_back(Event{start});
      events.push_back(Event{start + 1});
    }
    return events;
  }
  std::vector<std::string> Names(const std::vector<Event>& events) const {
    std::vector<std::string> names;
    for (const Event& e : events) {
      if ((e.snap & 1) == 0) names.push_back(task->actions[e.snap >> 1].DisplayName());
    }
    return names;
  }
};

TEST(PlanEliminationTest, DropsADetourAndWhatOnlyTheDetourNeeded) {
  Fixture f;
  ASSERT_NE(f.task, nullptr);
  // Out to b and back, the box loaded and unloaded again, then the plan.
  const auto events = f.Steps({"(sail a b)", "(sail b a)", "(load a)", "(unload a)", "(load a)",
                               "(sail a c)", "(unload c)"});
  const auto kept = EliminateRedundantSteps(f.transitions, f.initial, events);
  EXPECT_EQ(f.Names(kept), (std::vector<std::string>{"(load a)", "(sail a c)", "(unload c)"}));
  // Starts carry their duration bounds again, as the replay set them.
  ASSERT_FALSE(kept.empty());
  EXPECT_DOUBLE_EQ(kept.front().min_duration_s, 2.0);
  EXPECT_DOUBLE_EQ(kept.front().max_duration_s, 2.0);
}

TEST(PlanEliminationTest, KeepsAPlanWithoutRedundantSteps) {
  Fixture f;
  ASSERT_NE(f.task, nullptr);
  const auto events = f.Steps({"(load a)", "(sail a c)", "(unload c)"});
  const auto kept = EliminateRedundantSteps(f.transitions, f.initial, events);
  EXPECT_EQ(f.Names(kept), f.Names(events));
  EXPECT_EQ(kept.size(), events.size());
}

TEST(PlanEliminationTest, DropsAStepNoGoalNeedsEvenWhenNothingLaterReadsIt) {
  Fixture f;
  ASSERT_NE(f.task, nullptr);
  const auto events = f.Steps({"(shift)", "(load a)", "(sail a c)", "(unload c)"});
  const auto kept = EliminateRedundantSteps(f.transitions, f.initial, events);
  EXPECT_EQ(f.Names(kept), (std::vector<std::string>{"(load a)", "(sail a c)", "(unload c)"}));
}

TEST(PlanEliminationTest, WorkBoundAndNonPlansLeaveTheEventsAsTheyAre) {
  Fixture f;
  ASSERT_NE(f.task, nullptr);
  const auto detour = f.Steps({"(sail a b)", "(sail b a)", "(load a)", "(sail a c)", "(unload c)"});
  EXPECT_EQ(EliminateRedundantSteps(f.transitions, f.initial, detour, 0).size(), detour.size());
  // Not a plan from the initial state (the ship is not at b): unchanged.
  const auto broken = f.Steps({"(sail b a)", "(load a)", "(sail a c)", "(unload c)"});
  EXPECT_EQ(f.Names(EliminateRedundantSteps(f.transitions, f.initial, broken)), f.Names(broken));
  // Nor is a sequence that does not end in the goal (the box taken on
  // board again), though without its last step it would.
  const auto unfinished = f.Steps({"(load a)", "(sail a c)", "(unload c)", "(load c)"});
  EXPECT_EQ(f.Names(EliminateRedundantSteps(f.transitions, f.initial, unfinished)),
            f.Names(unfinished));
}

}  // namespace
}  // namespace seaplan::search
