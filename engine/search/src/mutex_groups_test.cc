// Mutex groups found by invariant synthesis on the ground task, and the
// dead ends the order of goals shows (goal_order.h).
#include "mutex_groups.h"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <utility>

#include "goal_order.h"
#include "seaplan/search/planner.h"
#include "search_test_util.h"
#include "snap_task.h"

namespace seaplan::search {
namespace {

// Robots on a row of tiles paint them; a painted tile is never clear again
// and no robot can stand on it (floortile's shape, written for this test).
const char* kPaintDomain = R"(
(define (domain paint-row)
  (:requirements :typing :durative-actions)
  (:types robot tile color)
  (:predicates (robot-at ?r - robot ?t - tile) (clear ?t - tile) (next ?a ?b - tile)
               (painted ?t - tile ?c - color) (has ?r - robot ?c - color))
  (:durative-action move
    :parameters (?r - robot ?from ?to - tile)
    :duration (= ?duration 1)
    :condition (and (at start (robot-at ?r ?from)) (at start (clear ?to))
                    (over all (next ?from ?to)))
    :effect (and (at start (not (robot-at ?r ?from))) (at start (not (clear ?to)))
                 (at end (clear ?from)) (at end (robot-at ?r ?to))))
  (:durative-action paint
    :parameters (?r - robot ?t ?from - tile ?c - color)
    :duration (= ?duration 2)
    :condition (and (over all (has ?r ?c)) (at start (robot-at ?r ?from))
                    (over all (next ?from ?t)) (at start (clear ?t)))
    :effect (and (at start (not (clear ?t))) (at end (painted ?t ?c))))
))";
// A problem of paint-row: tiles t0 ... t(n-1) in a row, black paint, the
// robots, the rest of the initial state and the goal as given.
std::string PaintRowProblem(int tiles, std::string_view robots, std::string_view init,
                            std::string_view goal) {
  std::string objects, next;
  for (int i = 0; i < tiles; ++i) {
    objects += " t" + std::to_string(i);
    if (i + 1 < tiles) {
      const std::string a = "t" + std::to_string(i), b = "t" + std::to_string(i + 1);
      next += " (next " + a + " " + b + ") (next " + b + " " + a + ")";
    }
  }
  return "(define (problem paint-row) (:domain paint-row)\n  (:objects " + std::string(robots) +
         " - robot" + objects + " - tile black - color)\n  (:init " + std::string(init) + next +
         ")\n  (:goal (and " + std::string(goal) + ")))";
}

// Two robots at the ends of t0 - t1 - t2 - t3; t1 and t2 to be painted.
const std::string kPaintProblem =
    PaintRowProblem(4, "r1 r2",
                    "(robot-at r1 t0) (robot-at r2 t3) (clear t1) (clear t2) (has r1 black) "
                    "(has r2 black)",
                    "(painted t1 black) (painted t2 black)");

TEST(MutexGroupsTest, ATileIsClearOrOccupiedOrPaintedOrBeingEntered) {
  auto task = testing::LoadTaskOrFail(kPaintDomain, kPaintProblem);
  ASSERT_NE(task, nullptr);
  const MutexGroups mutex(*task);
  const auto fact = [&](const char* name) { return testing::FactIdOf(*task, name); };
  EXPECT_TRUE(mutex.Mutex(fact("(clear t1)"), fact("(painted t1 black)")));
  EXPECT_TRUE(mutex.Mutex(fact("(robot-at r1 t1)"), fact("(painted t1 black)")));
  EXPECT_TRUE(mutex.Mutex(fact("(robot-at r1 t1)"), fact("(robot-at r2 t1)")));
  EXPECT_TRUE(mutex.Mutex(fact("(clear t2)"), fact("(robot-at r2 t2)")));
  // A robot is on one tile at a time.
  EXPECT_TRUE(mutex.Mutex(fact("(robot-at r1 t1)"), fact("(robot-at r1 t2)")));
  // A move into t2 holds t2 from its start to its end.
  EXPECT_TRUE(mutex.Mutex(RunningMember(testing::ActionIdOf(*task, "(move r1 t1 t2)")),
                          fact("(clear t2)")));
  // Not mutex: two tiles, a tile and another tile's paint.
  EXPECT_FALSE(mutex.Mutex(fact("(clear t1)"), fact("(clear t2)")));
  EXPECT_FALSE(mutex.Mutex(fact("(robot-at r1 t1)"), fact("(painted t2 black)")));
  EXPECT_FALSE(mutex.Mutex(fact("(clear t1)"), fact("(clear t1)")));
}

// A fact added without taking anything is in no group.
TEST(MutexGroupsTest, AnAddWithoutADeleteBreaksTheInvariant) {
  std::string domain = kPaintDomain;
  domain.erase(domain.rfind(')'));  // the domain's closing parenthesis
  domain += R"(
  (:action drop-in :parameters (?r - robot ?t - tile) :precondition (clear ?t)
    :effect (robot-at ?r ?t))))";
  auto task = testing::LoadTaskOrFail(domain, kPaintProblem);
  ASSERT_NE(task, nullptr);
  const MutexGroups mutex(*task);
  const auto fact = [&](const char* name) { return testing::FactIdOf(*task, name); };
  EXPECT_FALSE(mutex.Mutex(fact("(clear t1)"), fact("(robot-at r1 t1)")));
  EXPECT_FALSE(mutex.Mutex(fact("(robot-at r1 t1)"), fact("(robot-at r1 t2)")));
}

// grab(x, x) requires (free x) once, deletes it once (listed twice) and
// adds both (h1 x) and (h2 x): {free, h1, h2} is no group.
TEST(MutexGroupsTest, ADeleteListedTwiceRemovesOneMember) {
  const char* domain = R"(
(define (domain grab)
  (:predicates (free ?a) (h1 ?a) (h2 ?a))
  (:action grab :parameters (?a ?b) :precondition (and (free ?a) (free ?b))
    :effect (and (not (free ?a)) (not (free ?b)) (h1 ?a) (h2 ?b)))
  (:action swap12 :parameters (?a) :precondition (h1 ?a) :effect (and (not (h1 ?a)) (h2 ?a)))
  (:action swap21 :parameters (?a) :precondition (h2 ?a) :effect (and (not (h2 ?a)) (h1 ?a))))
)";
  const char* problem = R"(
(define (problem grab-1) (:domain grab) (:objects x y) (:init (free x) (free y))
  (:goal (and (h1 x) (h2 x)))))";
  auto task = testing::LoadTaskOrFail(domain, problem);
  ASSERT_NE(task, nullptr);
  const MutexGroups mutex(*task);
  EXPECT_FALSE(mutex.Mutex(testing::FactIdOf(*task, "(h1 x)"), testing::FactIdOf(*task, "(h2 x)")));
}

// One action reaches both goals at once: neither has to come first.
TEST(GoalOrderTest, OneActionReachingTwoGoalsOrdersNeither) {
  const char* domain = R"(
(define (domain finish)
  (:predicates (free1 ?a) (free2 ?a) (g1 ?a) (g2 ?a))
  (:action finish :parameters (?a ?b) :precondition (and (free1 ?a) (free2 ?b))
    :effect (and (not (free1 ?a)) (not (free2 ?b)) (g1 ?a) (g2 ?b))))
)";
  const char* problem = R"(
(define (problem finish-1) (:domain finish) (:objects a b) (:init (free1 a) (free2 b))
  (:goal (and (g1 a) (g2 b)))))";
  auto task = testing::LoadTaskOrFail(domain, problem);
  ASSERT_NE(task, nullptr);
  const MutexGroups mutex(*task);
  ASSERT_TRUE(
      mutex.Mutex(testing::FactIdOf(*task, "(free1 a)"), testing::FactIdOf(*task, "(g1 a)")));
  const GoalOrderDeadEnds goal_order(*task, mutex);
  const SnapTask snap(*task);
  EXPECT_FALSE(goal_order.DeadEnd(testing::InitialState(*task, snap)));
  EXPECT_EQ(testing::SolveFirstPlan(*task).status, PlanStatus::kSolvedSatisficing);
}

// One robot; tiles t0 - t1 - t2 - t3; t1 and t2 to be painted.
const std::string kOneRobotProblem =
    PaintRowProblem(4, "r1", "(robot-at r1 t1) (clear t0) (clear t2) (clear t3) (has r1 black)",
                    "(painted t1 black) (painted t2 black)");

TEST(GoalOrderTest, TwoTilesEachPaintableOnlyFromTheOtherAreADeadEnd) {
  auto task = testing::LoadTaskOrFail(kPaintDomain, kOneRobotProblem);
  ASSERT_NE(task, nullptr);
  const MutexGroups mutex(*task);
  const GoalOrderDeadEnds goal_order(*task, mutex);
  ASSERT_TRUE(goal_order.active());
  const SnapTask snap(*task);
  const auto fact = [&](const char* name) { return testing::FactIdOf(*task, name); };
  StateData state = testing::InitialState(*task, snap);
  EXPECT_FALSE(goal_order.DeadEnd(state));
  // t3 painted: t2 can still be painted from t1 and t1 from t0, in that order.
  state.Clear(fact("(clear t3)"));
  state.Set(fact("(painted t3 black)"));
  EXPECT_FALSE(goal_order.DeadEnd(state));
  // t0 painted too: whichever of t1 and t2 is painted first leaves the other
  // without a tile to be painted from.
  state.Clear(fact("(clear t0)"));
  state.Set(fact("(painted t0 black)"));
  EXPECT_TRUE(goal_order.DeadEnd(state));
  // A paint of t2 already running: not a dead end by this rule.
  state.Clear(fact("(clear t2)"));
  state.running.push_back({testing::ActionIdOf(*task, "(paint r1 t2 t1 black)"), 2, 2});
  EXPECT_FALSE(goal_order.DeadEnd(state));
}

// A row of `tiles` tiles with one robot (initial state and goals given),
// the last tile painted: is it a dead end? And with the first painted too?
std::pair<bool, bool> DeadEndsAsTheEndsArePainted(int tiles, std::string_view init,
                                                  std::string_view goal) {
  auto task = testing::LoadTaskOrFail(kPaintDomain, PaintRowProblem(tiles, "r1", init, goal));
  if (task == nullptr) return {false, false};
  const MutexGroups mutex(*task);
  const GoalOrderDeadEnds goal_order(*task, mutex);
  const SnapTask snap(*task);
  StateData state = testing::InitialState(*task, snap);
  const auto paint = [&](int tile) {
    const std::string t = "t" + std::to_string(tile);
    state.Clear(testing::FactIdOf(*task, "(clear " + t + ")"));
    state.Set(testing::FactIdOf(*task, "(painted " + t + " black)"));
  };
  paint(tiles - 1);
  const bool last = goal_order.DeadEnd(state);
  paint(0);
  return {last, goal_order.DeadEnd(state)};
}

// Tiles t0 - t1 - t2 - t3 - t4, t1 to t3 to be painted: with t4 painted,
// t3, t2, t1 from the left, in that order; with t0 painted too, t1 and t3
// need t2 unpainted, t2 needs t1 or t3 unpainted.
TEST(GoalOrderTest, AChainOfThreeTilesWithBothEndsPaintedIsADeadEnd) {
  EXPECT_EQ(DeadEndsAsTheEndsArePainted(
                5, "(robot-at r1 t2) (clear t0) (clear t1) (clear t3) (clear t4) (has r1 black)",
                "(painted t1 black) (painted t2 black) (painted t3 black)"),
            std::make_pair(false, true));
}

// Tiles t0 - ... - t5, t1 to t4 to be painted. With t5 painted, t4 must
// go first (from t3), then t3, t2 and t1 from the left. With t0 painted as
// well, t1 must be painted from t2 and t4 from t3, so t2 and t3 each have
// one achiever left, each needing the other unpainted: a dead end that
// shows only once those achievers are dropped and the orders found again.
TEST(GoalOrderTest, ARunOfFourTilesWithBothEndsPaintedIsADeadEnd) {
  EXPECT_EQ(
      DeadEndsAsTheEndsArePainted(
          6,
          "(robot-at r1 t2) (clear t0) (clear t1) (clear t3) (clear t4) (clear t5) (has r1 black)",
          "(painted t1 black) (painted t2 black) (painted t3 black) (painted t4 black)"),
      std::make_pair(false, true));
}

TEST(GoalOrderTest, ThePlannerSolvesTheRowWithTheCheckOn) {
  auto task = testing::LoadTaskOrFail(kPaintDomain, kOneRobotProblem);
  ASSERT_NE(task, nullptr);
  const PlanResult r = testing::SolveFirstPlan(*task);
  EXPECT_EQ(r.status, PlanStatus::kSolvedSatisficing) << r.message;
}

// The goals the check would watch, counted without mutex groups: the
// paint goals nothing deletes; not a goal an action deletes (a robot's
// place), nor one a timed literal adds; each goal once.
TEST(GoalOrderTest, WatchableGoalsAreThoseNothingDeletesAndOnlyActionsAdd) {
  auto task = testing::LoadTaskOrFail(kPaintDomain, kPaintProblem);
  ASSERT_NE(task, nullptr);
  EXPECT_EQ(GoalOrderDeadEnds::NumWatchableGoals(*task), 2u);

  auto moved = testing::LoadTaskOrFail(
      kPaintDomain,
      PaintRowProblem(4, "r1 r2",
                      "(robot-at r1 t0) (robot-at r2 t3) (clear t1) (clear t2) (has r1 black) "
                      "(has r2 black) (at 50 (painted t2 black))",
                      "(painted t1 black) (painted t1 black) (painted t2 black) (robot-at r1 t1)"));
  ASSERT_NE(moved, nullptr);
  // (painted t1 black) once; (painted t2 black) a literal adds; a robot's
  // place a move deletes.
  EXPECT_EQ(GoalOrderDeadEnds::NumWatchableGoals(*moved), 1u);
}

}  // namespace
}  // namespace seaplan::search
