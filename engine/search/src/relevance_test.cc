#include "relevance.h"

#include <gtest/gtest.h>

#include <string>

#include "seaplan/task/grounder.h"
#include "search_test_util.h"

namespace seaplan::search {
namespace {

constexpr char kDomain[] = R"(
(define (domain rel)
  (:requirements :strips :typing :durative-actions :negative-preconditions :numeric-fluents)
  (:types item)
  (:predicates (made ?i - item) (packed ?i - item) (blocked) (lamp))
  (:functions (fuel))
  (:durative-action make
    :parameters (?i - item) :duration (= ?duration 1)
    :condition (and (at start (not (blocked))) (at start (>= (fuel) 1)))
    :effect (at end (made ?i)))
  (:durative-action pack
    :parameters (?i - item) :duration (= ?duration 1)
    :condition (at start (made ?i))
    :effect (at end (packed ?i)))
  (:durative-action unblock
    :parameters () :duration (= ?duration 1)
    :condition (at start (lamp))
    :effect (at end (not (blocked))))
  (:durative-action block
    :parameters () :duration (= ?duration 1)
    :effect (at end (blocked)))
  (:durative-action refuel
    :parameters () :duration (= ?duration 1)
    :effect (at end (increase (fuel) 1)))
  (:durative-action light
    :parameters () :duration (= ?duration 1)
    :effect (at end (lamp))))
)";

constexpr char kProblem[] = R"(
(define (problem p) (:domain rel) (:objects a b - item)
  (:init (blocked) (= (fuel) 0))
  (:goal (packed a)))
)";

// The entry of a per-action flag vector for the action named `name`.
bool ActionFlag(const task::GroundTask& task, const std::vector<bool>& flags,
                const std::string& name) {
  return flags[static_cast<std::size_t>(testing::ActionIdOf(task, name))];
}

TEST(RelevanceTest, KeepsWhatTheGoalNeedsThroughFactsNegationsAndNumbers) {
  const auto loaded = testing::LoadTaskOrFail(kDomain, kProblem);
  ASSERT_NE(loaded, nullptr);
  const task::GroundTask& task = *loaded;
  const std::vector<bool> relevant = RelevantActions(task);
  EXPECT_TRUE(ActionFlag(task, relevant, "(pack a)"));
  EXPECT_TRUE(ActionFlag(task, relevant, "(make a)"));
  // Nothing needs (packed b) or (made b).
  EXPECT_FALSE(ActionFlag(task, relevant, "(pack b)"));
  EXPECT_FALSE(ActionFlag(task, relevant, "(make b)"));
  // make needs (not (blocked)): its deleter is relevant, and the condition
  // of that deleter too; adding (blocked) only hurts, so block is not.
  EXPECT_TRUE(ActionFlag(task, relevant, "(unblock)"));
  EXPECT_TRUE(ActionFlag(task, relevant, "(light)"));
  EXPECT_FALSE(ActionFlag(task, relevant, "(block)"));
  // make reads (fuel).
  EXPECT_TRUE(ActionFlag(task, relevant, "(refuel)"));
}

// Sheets go through a press; the goal keeps some faces unprinted, and
// nothing makes a printed face clean again.
constexpr char kPressDomain[] = R"(
(define (domain press)
  (:requirements :strips :typing :durative-actions :negative-preconditions :timed-initial-literals)
  (:types sheet)
  (:predicates (clean-front ?s - sheet) (clean-back ?s - sheet) (printed ?s - sheet)
               (stamped ?s - sheet) (ready ?s - sheet) (glossy ?s - sheet) (washed ?s - sheet))
  (:durative-action print-front
    :parameters (?s - sheet) :duration (= ?duration 2)
    :condition (at start (clean-front ?s))
    :effect (and (at start (not (clean-front ?s))) (at end (printed ?s))))
  (:durative-action print-back
    :parameters (?s - sheet) :duration (= ?duration 2)
    :condition (at start (clean-back ?s))
    :effect (and (at end (not (clean-back ?s))) (at end (printed ?s))))
  (:durative-action stamp
    :parameters (?s - sheet) :duration (= ?duration 1)
    :condition (at start (ready ?s))
    :effect (and (at end (stamped ?s)) (at end (not (ready ?s)))))
  (:durative-action prepare
    :parameters (?s - sheet) :duration (= ?duration 1)
    :condition (at start (clean-back ?s))
    :effect (at end (ready ?s)))
  (:durative-action unprepare
    :parameters (?s - sheet) :duration (= ?duration 1)
    :condition (at start (ready ?s))
    :effect (at end (not (ready ?s))))
  (:durative-action varnish
    :parameters (?s - sheet) :duration (= ?duration 1)
    :condition (at start (printed ?s))
    :effect (and (at end (glossy ?s)) (at end (not (washed ?s)))))
  (:durative-action rinse
    :parameters (?s - sheet) :duration (= ?duration 1)
    :condition (at start (printed ?s))
    :effect (at end (when (clean-front ?s) (not (washed ?s))))))
)";

constexpr char kPressProblem[] = R"(
(define (problem p) (:domain press) (:objects a b - sheet)
  (:init (clean-front a) (clean-back a) (clean-front b) (clean-back b) (washed a)
         (at 5 (washed b)))
  (:goal (and (printed a) (clean-back a) (printed b) (washed a) (washed b) (not (glossy b))
              (ready a))))
)";

TEST(RelevanceTest, GoalBreakingActionsDeleteAGoalFactNothingAddsBack) {
  const auto loaded = testing::LoadTaskOrFail(kPressDomain, kPressProblem);
  ASSERT_NE(loaded, nullptr);
  const task::GroundTask& task = *loaded;
  const std::vector<bool> breaks = GoalBreakingActions(task, {});
  // (clean-back a) is a goal and nothing adds it.
  EXPECT_TRUE(ActionFlag(task, breaks, "(print-back a)"));
  // (clean-back b) and (clean-front ...) are not goals.
  EXPECT_FALSE(ActionFlag(task, breaks, "(print-back b)"));
  EXPECT_FALSE(ActionFlag(task, breaks, "(print-front a)"));
  // (washed a): a goal nothing adds; (washed b): a timed literal adds it.
  EXPECT_TRUE(ActionFlag(task, breaks, "(varnish a)"));
  // varnish b adds (glossy b), which the goal needs false and nothing deletes.
  EXPECT_TRUE(ActionFlag(task, breaks, "(varnish b)"));
  // A conditional delete may never happen.
  EXPECT_FALSE(ActionFlag(task, breaks, "(rinse a)"));
  // (ready a) is a goal added only by prepare a: stamp a and unprepare a
  // delete it, but prepare a can add it back.
  EXPECT_FALSE(ActionFlag(task, breaks, "(stamp a)"));
  EXPECT_FALSE(ActionFlag(task, breaks, "(unprepare a)"));
  // With prepare a excluded (as an irrelevant action would be), nothing
  // adds (ready a) any more.
  std::vector<bool> excluded(task.actions.size(), false);
  excluded[static_cast<std::size_t>(testing::ActionIdOf(task, "(prepare a)"))] = true;
  const std::vector<bool> without_prepare = GoalBreakingActions(task, excluded);
  EXPECT_TRUE(ActionFlag(task, without_prepare, "(stamp a)"));
  EXPECT_TRUE(ActionFlag(task, without_prepare, "(unprepare a)"));
  EXPECT_FALSE(ActionFlag(task, without_prepare, "(prepare a)"));  // excluded, not breaking
}

TEST(RelevanceTest, GoalBreakingActionsReachAFixpoint) {
  // (done) is a goal added only by finish, which deletes the goal (kept);
  // so finish breaks the goal, and then nothing adds (done): reset, which
  // deletes it, breaks the goal too, found in the second round.
  constexpr char kDomain2[] = R"(
(define (domain chain)
  (:requirements :strips :durative-actions)
  (:predicates (kept) (done))
  (:durative-action finish :parameters () :duration (= ?duration 1)
    :effect (and (at end (done)) (at end (not (kept)))))
  (:durative-action reset :parameters () :duration (= ?duration 1)
    :effect (at end (not (done)))))
)";
  constexpr char kProblem2[] = R"(
(define (problem p) (:domain chain) (:init (kept) (done)) (:goal (and (kept) (done))))
)";
  const auto loaded = testing::LoadTaskOrFail(kDomain2, kProblem2);
  ASSERT_NE(loaded, nullptr);
  const task::GroundTask& task = *loaded;
  const std::vector<bool> breaks = GoalBreakingActions(task, {});
  EXPECT_TRUE(ActionFlag(task, breaks, "(finish)"));
  EXPECT_TRUE(ActionFlag(task, breaks, "(reset)"));
}

}  // namespace
}  // namespace seaplan::search
