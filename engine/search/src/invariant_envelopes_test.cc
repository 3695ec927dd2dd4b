// Over-all envelopes (invariant_envelopes.h) on a small kiln domain in the
// spirit of the temporal machine shop: a kiln is ready only while it is
// fired, and a bake needs the kiln ready over all of it.
#include "invariant_envelopes.h"

#include <gtest/gtest.h>

#include <string>

#include "heuristics/relaxed_plan_heuristic.h"
#include "seaplan/search/planner.h"
#include "seaplan/task/grounder.h"
#include "seaplan/validate/validator.h"
#include "search_test_util.h"
#include "snap_task.h"
#include "state_registry.h"
#include "timeline.h"
#include "transitions.h"

namespace seaplan::search {
namespace {

constexpr char kDomain[] = R"(
(define (domain kiln)
  (:requirements :strips :typing :durative-actions)
  (:types piece kiln)
  (:predicates (energy) (ready ?k - kiln) (baked ?p - piece) (cooled ?p - piece)
               (short ?k - kiln) (long ?k - kiln))
  (:durative-action fire-short
    :parameters (?k - kiln) :duration (= ?duration 8)
    :condition (and (at start (short ?k)) (over all (energy)))
    :effect (and (at start (ready ?k)) (at end (not (ready ?k)))))
  (:durative-action fire-long
    :parameters (?k - kiln) :duration (= ?duration 20)
    :condition (and (at start (long ?k)) (over all (energy)))
    :effect (and (at start (ready ?k)) (at end (not (ready ?k)))))
  (:durative-action bake-slow
    :parameters (?p - piece ?k - kiln) :duration (= ?duration 15)
    :condition (over all (ready ?k))
    :effect (at end (baked ?p)))
  (:durative-action bake-fast
    :parameters (?p - piece ?k - kiln) :duration (= ?duration 5)
    :condition (over all (ready ?k))
    :effect (at end (baked ?p)))
  (:durative-action cool
    :parameters (?p - piece) :duration (= ?duration 2)
    :condition (at start (baked ?p))
    :effect (at end (cooled ?p))))
)";

std::string Problem(const std::string& kilns, const std::string& init, const std::string& goal) {
  return "(define (problem p) (:domain kiln) (:objects a b c - piece " + kilns +
         " - kiln) (:init (energy) " + init + ") (:goal (and " + goal + ")))";
}

using testing::ActionIdOf;

std::shared_ptr<const task::GroundTask> MustLoad(const std::string& problem) {
  auto loaded = task::LoadTask(kDomain, problem);
  EXPECT_TRUE(loaded.ok()) << loaded.ErrorText();
  return loaded.task;
}

TEST(InvariantEnvelopesTest, ActionLongerThanEveryWindowOfItsInvariantIsUnschedulable) {
  auto task = MustLoad(Problem("k8 k20", "(short k8) (long k20)", "(baked a)"));
  ASSERT_TRUE(task);
  const InvariantEnvelopes env(*task);
  // (ready k8) only holds inside an 8-unit firing: a 15-unit bake never fits.
  EXPECT_TRUE(env.Unschedulable(ActionIdOf(*task, "(bake-slow a k8)")));
  EXPECT_FALSE(env.Unschedulable(ActionIdOf(*task, "(bake-fast a k8)")));
  EXPECT_FALSE(env.Unschedulable(ActionIdOf(*task, "(bake-slow a k20)")));
  EXPECT_FALSE(env.Unschedulable(ActionIdOf(*task, "(fire-short k8)")));
  EXPECT_EQ(env.num_unschedulable(), 3);  // bake-slow of a, b and c in k8
  EXPECT_TRUE(env.MustEndWithin(ActionIdOf(*task, "(bake-fast a k8)"),
                                ActionIdOf(*task, "(fire-short k8)")));
  EXPECT_FALSE(env.MustEndWithin(ActionIdOf(*task, "(bake-fast a k8)"),
                                 ActionIdOf(*task, "(fire-long k20)")));
  EXPECT_FALSE(
      env.MustEndWithin(ActionIdOf(*task, "(cool a)"), ActionIdOf(*task, "(fire-short k8)")));
  EXPECT_TRUE(env.IsEnvelope(ActionIdOf(*task, "(fire-short k8)")));
  EXPECT_FALSE(env.IsEnvelope(ActionIdOf(*task, "(bake-fast a k8)")));
}

TEST(InvariantEnvelopesTest, FactTrueInitiallyIsNoEnvelope) {
  // (ready k8) holds from time 0 until the first firing ends: any bake may fit.
  auto task = MustLoad(Problem("k8", "(short k8) (ready k8)", "(baked a)"));
  ASSERT_TRUE(task);
  const InvariantEnvelopes env(*task);
  EXPECT_EQ(env.num_unschedulable(), 0);
}

TEST(InvariantEnvelopesTest, DurationBoundsReadConstantConstraints) {
  auto task = MustLoad(Problem("k8", "(short k8)", "(baked a)"));
  ASSERT_TRUE(task);
  const task::Action& fire =
      task->actions[static_cast<std::size_t>(ActionIdOf(*task, "(fire-short k8)"))];
  EXPECT_EQ(MinDurationBound(fire), 8.0);
  EXPECT_EQ(MaxDurationBound(fire), 8.0);
}

TEST(InvariantEnvelopesTest, ScheduleRejectsAStartThatCannotEndInsideItsEnvelope) {
  auto task = MustLoad(Problem("k8", "(short k8)", "(baked a)"));
  ASSERT_TRUE(task);
  const SnapTask snap(*task);
  Timeline timeline(snap, 0.001);
  const auto fire = ActionIdOf(*task, "(fire-short k8)");
  const std::vector<Event> path = {{2 * fire, 8.0, 8.0}};
  ASSERT_TRUE(timeline.Build(path));
  Timeline::Outcome out;
  // 5 units fit into the 8-unit firing...
  EXPECT_TRUE(timeline.TryAdd({2 * ActionIdOf(*task, "(bake-fast a k8)"), 5.0, 5.0}, &out));
  timeline.Undo();
  // ...a 9-unit window would not (bake-slow itself is unschedulable here, so
  // give bake-fast a longer duration than the firing).
  EXPECT_FALSE(timeline.TryAdd({2 * ActionIdOf(*task, "(bake-fast a k8)"), 9.0, 9.0}, &out));
  timeline.Undo();
}

TEST(InvariantEnvelopesTest, RunningEndsDoNotWaitForASuppressedWindowFact) {
  auto task = MustLoad(Problem("k8", "(short k8)", "(baked a)"));
  ASSERT_TRUE(task);
  const SnapTask snap(*task);
  StateRegistry registry(snap.num_facts(), snap.num_vars());
  Transitions transitions(snap, 0, 0.001);
  StateData s = registry.MakeEmpty();
  for (auto f : task->initial_facts) s.Set(f);
  const auto fire = ActionIdOf(*task, "(fire-short k8)");
  const auto bake = ActionIdOf(*task, "(bake-fast a k8)");
  StateData s1, s2;
  Event e1{2 * fire, 0, 0}, e2{2 * bake, 0, 0};
  ASSERT_TRUE(transitions.Apply(s, &e1, &s1));
  ASSERT_TRUE(transitions.Apply(s1, &e2, &s2));
  RelaxedPlanHeuristic h(snap, 0.001);
  std::vector<SnapId> preferred;
  // Plenty of room left in the firing: end the bake (1), and the firing's
  // end is owed (1).
  EXPECT_EQ(h.Evaluate(s2, &preferred, std::span<const double>{}), 2);
  EXPECT_EQ(preferred, std::vector<SnapId>{2 * bake + 1});
  // Too little room left for any new bake: (ready k8) is suppressed for new
  // starts, but the running bake already fits, so its end still needs no
  // new firing.
  const double slack[] = {1.0};
  EXPECT_EQ(h.Evaluate(s2, &preferred, slack), 2);
  EXPECT_EQ(preferred, std::vector<SnapId>{2 * bake + 1});
}

std::string WithoutFastBakes() {
  std::string domain = kDomain;
  const auto fast = domain.find("(:durative-action bake-fast");
  const auto cool = domain.find("(:durative-action cool");
  domain.erase(fast, cool - fast);
  return domain;
}

// Every plan the planner returns must pass the validator on its printed form.
void ExpectValid(const task::GroundTask& task, const PlanResult& r) {
  auto parsed = validate::ParsePlan(validate::FormatPlan(r.plan));
  ASSERT_TRUE(parsed.ok()) << parsed.status();
  const auto v = validate::ValidatePlan(task, *parsed);
  EXPECT_TRUE(v.valid) << v.ToString() << "\n" << validate::FormatPlan(r.plan);
}

TEST(InvariantEnvelopesTest, PlannerBakesSlowPiecesInTheLongKiln) {
  // Only slow bakes: each needs a firing of k20 around it.
  auto loaded = task::LoadTask(WithoutFastBakes(), Problem("k8 k20", "(short k8) (long k20)",
                                                           "(cooled a) (cooled b) (cooled c)"));
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorText();
  const task::GroundTask* task = loaded.task.get();
  PlannerOptions o;
  o.time_limit_s = 5;
  const PlanResult r = SolveTask(*task, o, StopToken());
  ASSERT_TRUE(r.status == PlanStatus::kSolvedSatisficing ||
              r.status == PlanStatus::kSolvedOptimally)
      << ToString(r.status) << ": " << r.message;
  ExpectValid(*task, r);
  int slow = 0;
  for (const auto& step : r.plan.steps) {
    if (step.name != "bake-slow") continue;
    ++slow;
    EXPECT_EQ(step.args[1], "k20") << step.DisplayName();
  }
  EXPECT_EQ(slow, 3);
}

TEST(InvariantEnvelopesTest, OnlyTooShortWindowsIsProvenUnsolvable) {
  // Only slow bakes can bake and only the short kiln exists: the relaxation
  // without the unschedulable bakes proves it at once.
  auto loaded = task::LoadTask(WithoutFastBakes(), Problem("k8", "(short k8)", "(baked a)"));
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorText();
  PlannerOptions o;
  o.time_limit_s = 5;
  const PlanResult r = SolveTask(*loaded.task, o, StopToken());
  EXPECT_EQ(r.status, PlanStatus::kUnsolvableProven) << ToString(r.status) << ": " << r.message;
  EXPECT_LE(r.stats.expanded, 1u);
}

}  // namespace
}  // namespace seaplan::search
