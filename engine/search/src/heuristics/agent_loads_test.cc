#include "agent_loads.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "../search_test_util.h"
#include "relaxed_plan_heuristic.h"
#include "seaplan/search/planner.h"
#include "seaplan/task/grounder.h"
#include "seaplan/validate/validator.h"

namespace seaplan::search {
namespace {

// Ships carrying one container at a time between ports; a team that only
// has to be present (read at start) for a repair.
constexpr char kDomain[] = R"((define (domain haul)
  (:requirements :typing :durative-actions :numeric-fluents)
  (:types ship cont team - thing port)
  (:predicates (at ?x - thing ?p - port) (available ?s - ship) (loaded ?c - cont ?s - ship)
               (connected ?a ?b - port) (no_rep ?s - ship) (repaired ?s - ship))
  (:functions (distance ?a ?b - port) (speed ?s - ship))
  (:durative-action move :parameters (?s - ship ?a ?b - port)
    :duration (= ?duration (/ (distance ?a ?b) (speed ?s)))
    :condition (and (at start (at ?s ?a)) (at start (connected ?a ?b)))
    :effect (and (at start (not (at ?s ?a))) (at end (at ?s ?b))))
  (:durative-action load :parameters (?s - ship ?p - port ?c - cont)
    :duration (= ?duration 60)
    :condition (and (over all (at ?s ?p)) (at start (at ?c ?p)) (at start (available ?s)))
    :effect (and (at start (not (available ?s))) (at start (not (at ?c ?p)))
                 (at end (loaded ?c ?s))))
  (:durative-action unload :parameters (?c - cont ?p - port ?s - ship)
    :duration (= ?duration 50)
    :condition (and (over all (at ?s ?p)) (at start (loaded ?c ?s)))
    :effect (and (at start (not (loaded ?c ?s))) (at end (at ?c ?p)) (at end (available ?s))))
  (:durative-action repair :parameters (?s - ship ?p - port ?k - team)
    :duration (= ?duration 60)
    :condition (and (over all (at ?s ?p)) (at start (at ?k ?p)) (at start (no_rep ?s)))
    :effect (and (at start (not (no_rep ?s))) (at end (repaired ?s))))))";

// Both containers wait at port a, each ship is 10 s away from it (ship0 at
// e, ship1 at d). c1 goes two legs on to c, c2 one leg to b, and ship0 must
// be repaired at c: one ship doing everything takes almost twice as long as
// the two sharing the work.
constexpr char kProblem[] = R"((define (problem two-ships) (:domain haul)
  (:objects ship0 ship1 - ship c1 c2 - cont k - team a b c d e - port)
  (:init (at ship0 e) (at ship1 d) (available ship0) (available ship1) (at c1 a) (at c2 a)
         (at k c) (no_rep ship0)
         (= (speed ship0) 1) (= (speed ship1) 1)
         (connected a b) (connected b a) (connected b c) (connected c b)
         (connected a d) (connected d a) (connected a e) (connected e a)
         (= (distance a b) 100) (= (distance b a) 100) (= (distance b c) 100)
         (= (distance c b) 100) (= (distance a d) 10) (= (distance d a) 10)
         (= (distance a e) 10) (= (distance e a) 10))
  (:goal (and (repaired ship0) (at c1 c) (at c2 b)))
  (:metric minimize (total-time))))";

class AgentLoadsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    task_ = testing::LoadTaskOrFail(kDomain, kProblem);
    ASSERT_NE(task_, nullptr);
    snap_ = std::make_unique<SnapTask>(*task_);
  }

  std::shared_ptr<const task::GroundTask> task_;
  std::unique_ptr<SnapTask> snap_;
};

TEST_F(AgentLoadsTest, PerformersAreTheObjectsWhoseFactsTheActionHolds) {
  const AgentLoads agents(*snap_);
  EXPECT_TRUE(agents.active());
  const auto agents_of = [&](const std::string& action) {
    const auto span = agents.AgentsOf(testing::ActionIdOf(*task_, action));
    return std::vector<std::int32_t>(span.begin(), span.end());
  };
  // A move holds the ship only, a load the ship and the container (both
  // deleted or needed over all); the repair team is only read at the start.
  const auto move0 = agents_of("(move ship0 a b)");
  const auto move1 = agents_of("(move ship1 d a)");
  ASSERT_EQ(move0.size(), 1u);
  ASSERT_EQ(move1.size(), 1u);
  EXPECT_NE(move0[0], move1[0]);
  const auto load = agents_of("(load ship0 a c1)");
  ASSERT_EQ(load.size(), 2u);
  EXPECT_TRUE(std::find(load.begin(), load.end(), move0[0]) != load.end());
  const auto unload = agents_of("(unload c1 b ship0)");
  EXPECT_EQ(unload, load);
  EXPECT_EQ(agents_of("(repair ship0 c k)"), move0);
  EXPECT_DOUBLE_EQ(agents.DurationOf(testing::ActionIdOf(*task_, "(move ship0 a b)")), 100.0);
  EXPECT_DOUBLE_EQ(agents.DurationOf(testing::ActionIdOf(*task_, "(load ship0 a c1)")), 60.0);
  // Without a schedule every agent is free at 0.
  std::vector<double> ready_s;
  agents.ReadyTimes(testing::InitialState(*task_, *snap_), nullptr, &ready_s);
  ASSERT_EQ(static_cast<int>(ready_s.size()), agents.num_agents());
  for (double t : ready_s) EXPECT_EQ(t, 0.0);
}

TEST_F(AgentLoadsTest, RelaxedPlanGivesTheSecondContainerToTheIdleShip) {
  RelaxedPlanHeuristic heuristic(*snap_, 0.001);
  heuristic.SetMakespanAware(true);
  ASSERT_TRUE(heuristic.makespan_aware());
  std::vector<SnapId> preferred;
  const int h = heuristic.Evaluate(testing::InitialState(*task_, *snap_), &preferred);
  // Goals in order. The repair sends ship0 to c (moves e-a, a-b, b-c and
  // the repair: 8 snaps, 270 s charged to ship0). c1 reaches c at 260 s
  // with either ship (both reach it in the same layer, FF takes ship0's
  // unload), but ship0 would start on it only after its 270 s: ship1 takes
  // it (moves d-a, a-b, b-c, load, unload: 10 snaps). c2 reaches b at 160 s
  // with ship0 plus its 270 s, 480 s with ship1 after its 320 s: ship0
  // loads and unloads it (4 snaps). FF's plan gives everything to ship0
  // (8 + 4 + 4 = 16 snaps) and never moves ship1.
  EXPECT_EQ(h, 22);
  const auto start_of = [&](const std::string& action) {
    return static_cast<SnapId>(2 * testing::ActionIdOf(*task_, action));
  };
  const auto helpful = [&](const std::string& action) {
    return std::binary_search(preferred.begin(), preferred.end(), start_of(action));
  };
  EXPECT_TRUE(helpful("(move ship1 d a)"));
  EXPECT_TRUE(helpful("(move ship0 e a)"));
}

TEST_F(AgentLoadsTest, FirstPlanSailsBothShipsAtOnce) {
  PlannerOptions options;
  options.time_limit_s = 30;
  options.anytime = false;
  const PlanResult r = SolveTask(*task_, options, StopToken());
  ASSERT_EQ(r.status, PlanStatus::kSolvedSatisficing) << r.message;
  auto parsed = validate::ParsePlan(validate::FormatPlan(r.plan));
  ASSERT_TRUE(parsed.ok()) << parsed.status();
  EXPECT_TRUE(validate::ValidatePlan(*task_, *parsed).valid);
  bool ship1_works = false;
  for (const auto& step : r.plan.steps) {
    if (std::find(step.args.begin(), step.args.end(), "ship1") != step.args.end())
      ship1_works = true;
  }
  EXPECT_TRUE(ship1_works) << validate::FormatPlan(r.plan);
  // ship0 alone: 10 + 60 + 100 + 50 + 100 + 60 + 100 + 100 + 50 + 60 = 690
  // s in that order (640 s when the repair overlaps the unload); with c1 on
  // ship1, ship0's 380 s (c2, then the repair) are the critical path.
  EXPECT_LT(r.makespan_s, 400.0) << validate::FormatPlan(r.plan);
}

}  // namespace
}  // namespace seaplan::search
