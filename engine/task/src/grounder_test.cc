#include "seaplan/task/grounder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <utility>

#include "seaplan/testing/large_pddl.h"
#include "seaplan/testing/shared_data.h"

namespace seaplan::task {
namespace {

std::string Names(const GroundTask& task) {
  std::string out;
  for (const auto& a : task.actions)
    out += a.DisplayName() + "#" + std::to_string(a.variant) + "\n";
  return out;
}

bool HasFact(const GroundTask& task, const std::string& name) {
  for (const auto& f : task.facts) {
    if (f.DisplayName() == name) return true;
  }
  return false;
}

FactId FactIdOf(const GroundTask& task, const std::string& name) {
  for (std::size_t i = 0; i < task.facts.size(); ++i) {
    if (task.facts[i].DisplayName() == name) return static_cast<FactId>(i);
  }
  return -1;
}

const Action* FindAction(const GroundTask& task, const std::string& display) {
  for (const auto& a : task.actions) {
    if (a.DisplayName() == display) return &a;
  }
  return nullptr;
}

LoadResult MustLoad(const std::string& domain, const std::string& problem) {
  LoadResult r = LoadTask(domain, problem);
  EXPECT_TRUE(r.ok()) << r.ErrorText();
  return r;
}

constexpr const char* kNav = R"(
(define (domain nav) (:requirements :strips :typing :negative-preconditions)
 (:types place robot)
 (:predicates (at ?r - robot ?p - place) (road ?a ?b - place) (visited ?p - place)
              (broken ?r - robot) (blocked ?p - place))
 (:action move :parameters (?r - robot ?a ?b - place)
   :precondition (and (at ?r ?a) (road ?a ?b) (not (broken ?r)) (not (blocked ?b)))
   :effect (and (not (at ?r ?a)) (at ?r ?b) (visited ?b))))
)";

TEST(GrounderTest, ReachabilityDrivenWithStaticFactsFolded) {
  // Roads p1->p2, p2->p3, p3->p2, p3->p4 (p4 blocked), p5->p1 (p5 unreachable).
  auto r = MustLoad(kNav, R"(
(define (problem p) (:domain nav)
 (:objects p1 p2 p3 p4 p5 - place r1 - robot)
 (:init (at r1 p1) (road p1 p2) (road p2 p3) (road p3 p2) (road p3 p4) (road p5 p1) (blocked p4))
 (:goal (visited p3))))");
  ASSERT_TRUE(r.task);
  const GroundTask& t = *r.task;
  // Hand count: move(r1 p1 p2), move(r1 p2 p3), move(r1 p3 p2); p3->p4 pruned by the static
  // (not (blocked p4)), p5->p1 unreachable. A blind enumeration would give 25.
  EXPECT_EQ(t.actions.size(), 3u) << Names(t);
  EXPECT_NE(FindAction(t, "(move r1 p1 p2)"), nullptr);
  EXPECT_NE(FindAction(t, "(move r1 p3 p2)"), nullptr);
  // Facts: (at r1 p1..p3), (visited p2), (visited p3); no static (road/blocked) and no never-added
  // (broken).
  EXPECT_EQ(t.facts.size(), 5u);
  EXPECT_FALSE(HasFact(t, "(road p1 p2)"));
  EXPECT_FALSE(HasFact(t, "(broken r1)"));
  EXPECT_FALSE(HasFact(t, "(at r1 p5)"));
  // Negative preconditions on never-added/static facts are folded away.
  for (const auto& a : t.actions) {
    EXPECT_TRUE(a.at_start.negative.empty()) << a.DisplayName();
    EXPECT_FALSE(a.is_durative);
    EXPECT_EQ(a.at_start.positive.size(), 1u);
  }
  EXPECT_EQ(t.initial_facts, std::vector<FactId>{FactIdOf(t, "(at r1 p1)")});
  EXPECT_EQ(t.goal.positive, std::vector<FactId>{FactIdOf(t, "(visited p3)")});
  EXPECT_EQ(t.Size().actions, 3u);
  EXPECT_EQ(r.stats.size.facts, 5u);
}

TEST(GrounderTest, TypeHierarchiesAndEither) {
  auto r = MustLoad(R"(
(define (domain shop) (:requirements :typing)
 (:types hammer saw - tool tool part - item robot)
 (:predicates (free ?r - robot) (holding ?r - robot ?x - (either tool part)) (fixed ?x - item))
 (:action grab :parameters (?r - robot ?x - (either saw part))
   :precondition (free ?r) :effect (and (not (free ?r)) (holding ?r ?x)))
 (:action fix :parameters (?r - robot ?x - item)
   :precondition (holding ?r ?x) :effect (fixed ?x)))
)",
                    R"(
(define (problem p) (:domain shop)
 (:objects h1 - hammer s1 s2 - saw b1 - part r1 r2 - robot)
 (:init (free r1) (free r2))
 (:goal (fixed b1))))");
  ASSERT_TRUE(r.task);
  // grab: 2 robots x {s1, s2, b1} = 6; fix: the same 6 pairs (h1 is never held).
  EXPECT_EQ(r.task->actions.size(), 12u) << Names(*r.task);
  EXPECT_EQ(FindAction(*r.task, "(grab r1 h1)"), nullptr);
  EXPECT_NE(FindAction(*r.task, "(fix r2 b1)"), nullptr);
}

TEST(GrounderTest, DisjunctionsBecomeVariantsAndEqualityIsFolded) {
  auto r = MustLoad(R"(
(define (domain dis) (:requirements :typing :disjunctive-preconditions :equality)
 (:types obj)
 (:predicates (p ?x - obj) (q ?x - obj) (r ?x ?y - obj) (done ?x - obj))
 (:action a :parameters (?x - obj) :precondition (or (p ?x) (q ?x)) :effect (done ?x))
 (:action b :parameters (?x ?y - obj) :precondition (not (= ?x ?y)) :effect (r ?x ?y)))
)",
                    R"(
(define (problem p) (:domain dis) (:objects o1 o2 o3 - obj)
 (:init (p o1) (q o1) (p o2))
 (:goal (done o1))))");
  ASSERT_TRUE(r.task);
  const GroundTask& t = *r.task;
  // a: o1 twice (p and q; p/q are static so each variant has an empty precondition), o2 once.
  // b: 3 x 2 ordered pairs of distinct objects.
  int a_o1 = 0;
  std::set<int> variants;
  for (const auto& act : t.actions) {
    if (act.DisplayName() == "(a o1)") {
      ++a_o1;
      variants.insert(act.variant);
    }
  }
  EXPECT_EQ(a_o1, 2);
  EXPECT_EQ(variants, (std::set<int>{0, 1}));
  EXPECT_EQ(t.actions.size(), 9u) << Names(t);
  // The index finds each variant on its own.
  const ActionIndex index(t);
  const std::vector<std::string> o1{"o1"};
  for (int v : {0, 1}) {
    const ActionId found = index.Find("A", o1, v);
    ASSERT_GE(found, 0);
    EXPECT_EQ(t.actions[static_cast<std::size_t>(found)].DisplayName(), "(a o1)");
    EXPECT_EQ(t.actions[static_cast<std::size_t>(found)].variant, v);
  }
  EXPECT_EQ(index.Find("a", o1, 2), -1);
  EXPECT_EQ(index.Find("a", std::vector<std::string>{"o2"}, 1), -1);
  EXPECT_EQ(index.Find("a", std::vector<std::string>{"o3"}, 0), -1);
  EXPECT_EQ(FindAction(t, "(b o1 o1)"), nullptr);
  EXPECT_EQ(FindAction(t, "(a o3)"), nullptr);
}

TEST(GrounderTest, ForallAndConditionalEffectsAreExpanded) {
  auto r = MustLoad(R"(
(define (domain truck) (:requirements :typing :adl :durative-actions)
 (:types pkg loc truck)
 (:predicates (at ?t - truck ?l - loc) (in ?p - pkg ?t - truck) (pat ?p - pkg ?l - loc)
              (closer ?a ?b - loc) (free ?l - loc))
 (:durative-action drive :parameters (?t - truck ?a ?b - loc) :duration (= ?duration 3)
   :condition (and (at start (at ?t ?a)) (at start (not (= ?a ?b)))
                   (at start (forall (?c - loc) (imply (closer ?c ?b) (free ?c)))))
   :effect (and (at start (not (at ?t ?a))) (at end (at ?t ?b))
                (forall (?p - pkg) (when (at start (in ?p ?t)) (at end (pat ?p ?b))))))
 (:durative-action drop :parameters (?p - pkg ?t - truck) :duration (= ?duration 1)
   :condition (at start (in ?p ?t)) :effect (at end (not (in ?p ?t)))))
)",
                    R"(
(define (problem p) (:domain truck)
 (:objects t1 - truck l1 l2 l3 - loc k1 k2 - pkg)
 (:init (at t1 l1) (in k1 t1) (in k2 t1) (closer l1 l3) (free l1))
 (:goal (pat k1 l3))))");
  ASSERT_TRUE(r.task);
  const GroundTask& t = *r.task;
  // drive between 3 locations, a != b: 6 actions; drop: 2 packages.
  EXPECT_EQ(t.actions.size(), 8u) << Names(t);
  const Action* d = FindAction(t, "(drive t1 l1 l3)");
  ASSERT_NE(d, nullptr);
  EXPECT_TRUE(d->is_durative);
  EXPECT_EQ(d->ConstantDuration(), 3.0);
  // One conditional effect per package, condition at start, effect at end.
  ASSERT_EQ(d->end_effects.conditional.size(), 2u);
  EXPECT_EQ(d->end_effects.conditional[0].condition_time, TimePoint::kStart);
  EXPECT_EQ(d->end_effects.conditional[0].condition.positive,
            std::vector<FactId>{FactIdOf(t, "(in k1 t1)")});
  // forall (imply (closer ?c l3) (free ?c)): closer is static, only (free l1) remains;
  // free is never added so it is static and true: nothing remains.
  EXPECT_EQ(d->at_start.positive, std::vector<FactId>{FactIdOf(t, "(at t1 l1)")});
}

TEST(GrounderTest, NumericExpressionsStaticFoldedDynamicKept) {
  auto r = MustLoad(R"(
(define (domain rov) (:requirements :typing :durative-actions :fluents)
 (:types rover wp)
 (:predicates (at ?r - rover ?w - wp) (link ?a ?b - wp))
 (:functions (energy ?r - rover) (rate ?r - rover) (dist ?a ?b - wp) (speed ?r - rover))
 (:durative-action go :parameters (?r - rover ?a ?b - wp)
   :duration (= ?duration (/ (dist ?a ?b) (speed ?r)))
   :condition (and (at start (at ?r ?a)) (at start (link ?a ?b)) (at start (>= (energy ?r) 8))
                   (at start (> (speed ?r) 1)))
   :effect (and (at start (not (at ?r ?a))) (at end (at ?r ?b)) (at end (decrease (energy ?r) 8))))
 (:durative-action recharge :parameters (?r - rover ?w - wp)
   :duration (= ?duration (/ (- 80 (energy ?r)) (rate ?r)))
   :condition (at start (at ?r ?w))
   :effect (at end (increase (energy ?r) (* ?duration (rate ?r))))))
)",
                    R"(
(define (problem p) (:domain rov) (:objects r1 r2 - rover w1 w2 w3 - wp)
 (:init (at r1 w1) (at r2 w1) (link w1 w2) (link w2 w1) (link w1 w3)
        (= (dist w1 w2) 10) (= (dist w2 w1) 10)
        (= (energy r1) 50) (= (energy r2) 50) (= (rate r1) 2) (= (rate r2) 2)
        (= (speed r1) 2) (= (speed r2) 0.5))
 (:goal (at r1 w2))))");
  ASSERT_TRUE(r.task);
  const GroundTask& t = *r.task;
  // go: r1 only (r2's speed 0.5 fails the static (> (speed ?r) 1)); w1->w3 has no dist
  // (undefined duration) so it is pruned: go r1 w1 w2, go r1 w2 w1.
  // recharge: r1 at w1, w2; r2 at w1.
  EXPECT_EQ(t.actions.size(), 5u) << Names(t);
  const Action* go = FindAction(t, "(go r1 w1 w2)");
  ASSERT_NE(go, nullptr);
  EXPECT_EQ(go->ConstantDuration(), 5.0);      // 10 / 2 folded
  ASSERT_EQ(go->at_start.numeric.size(), 1u);  // energy >= 8 stays (energy changes)
  EXPECT_EQ(FindAction(t, "(go r1 w1 w3)"), nullptr);
  const Action* rech = FindAction(t, "(recharge r1 w1)");
  ASSERT_NE(rech, nullptr);
  EXPECT_FALSE(rech->ConstantDuration().has_value());
  ASSERT_EQ(rech->duration.size(), 1u);
  EXPECT_EQ(rech->duration[0].value.Variables().size(), 1u);  // (energy r1); rate folded
  EXPECT_EQ(ToString(rech->duration[0].value, t), "(/ (- 80 (energy r1)) 2)");
  EXPECT_TRUE(rech->end_effects.numeric[0].value.ReadsDuration());
  // Only changing fluents are variables: energy r1, energy r2.
  EXPECT_EQ(t.numeric_vars.size(), 2u);
  EXPECT_EQ(t.initial_values.size(), 2u);
  EXPECT_DOUBLE_EQ(t.initial_values[0], 50);
  ASSERT_EQ(t.metric.expression.nodes.size(), 1u);
  EXPECT_EQ(t.metric.expression.nodes[0].op, NumericExpr::Op::kTotalTime);
}

TEST(GrounderTest, TimedInitialLiteralsMakeFactsReachable) {
  auto r = MustLoad(R"(
(define (domain til) (:requirements :typing :durative-actions :timed-initial-literals)
 (:types item)
 (:predicates (open) (sent ?i - item) (ready ?i - item))
 (:durative-action send :parameters (?i - item) :duration (= ?duration 2)
   :condition (and (at start (ready ?i)) (over all (open))) :effect (at end (sent ?i))))
)",
                    R"(
(define (problem p) (:domain til) (:objects a b - item)
 (:init (ready a) (at 10 (open)) (at 20 (not (open))))
 (:goal (sent a))))");
  ASSERT_TRUE(r.task);
  const GroundTask& t = *r.task;
  ASSERT_EQ(t.actions.size(), 1u) << Names(t);  // send a; b is never ready (static, false)
  EXPECT_EQ(t.actions[0].over_all.positive, std::vector<FactId>{FactIdOf(t, "(open)")});
  ASSERT_EQ(t.timed_literals.size(), 2u);
  EXPECT_DOUBLE_EQ(t.timed_literals[0].time_s, 10);
  EXPECT_TRUE(t.timed_literals[0].value);
  EXPECT_FALSE(t.timed_literals[1].value);
  EXPECT_EQ(t.timed_literals[0].fact, FactIdOf(t, "(open)"));
  EXPECT_TRUE(t.initial_facts.empty());
}

TEST(GrounderTest, StaticallyFalseGoalsAreKeptNotDropped) {
  const char* problem_unreachable = R"(
(define (problem p) (:domain nav) (:objects p1 p2 - place r1 - robot)
 (:init (at r1 p1) (road p1 p2))
 (:goal (and (visited p2) (at r1 p1) (visited p1)))))";
  auto r = LoadTask(kNav, problem_unreachable);
  ASSERT_TRUE(r.ok()) << r.ErrorText();
  // (visited p1) is never added: kept as a goal fact nothing achieves, with a warning.
  const FactId v1 = FactIdOf(*r.task, "(visited p1)");
  ASSERT_GE(v1, 0);
  EXPECT_NE(std::find(r.task->goal.positive.begin(), r.task->goal.positive.end(), v1),
            r.task->goal.positive.end());
  EXPECT_NE(r.ErrorText().find("unreachable"), std::string::npos);

  const char* problem_false = R"(
(define (problem p) (:domain nav) (:objects p1 p2 - place r1 - robot)
 (:init (at r1 p1) (road p1 p2))
 (:goal (and (visited p2) (road p2 p1)))))";
  auto f = LoadTask(kNav, problem_false);
  ASSERT_TRUE(f.ok()) << f.ErrorText();
  // (road p2 p1) is static and false: the goal keeps that fact rather than vanishing.
  EXPECT_EQ(f.task->goal.positive.size(), 2u);
  EXPECT_TRUE(HasFact(*f.task, "(road p2 p1)"));

  const char* problem_equal = R"(
(define (problem p) (:domain nav) (:objects p1 p2 - place r1 - robot)
 (:init (at r1 p1) (road p1 p2)) (:goal (= p1 p2))))";
  auto e = LoadTask(kNav, problem_equal);
  ASSERT_TRUE(e.ok()) << e.ErrorText();
  // Generated names contain '@', which no PDDL name can.
  ASSERT_EQ(e.task->goal.positive.size(), 1u);
  EXPECT_EQ(e.task->facts[static_cast<std::size_t>(e.task->goal.positive[0])].predicate, "@false");
  EXPECT_NE(e.ErrorText().find("statically false"), std::string::npos);
}

TEST(GrounderTest, BudgetsEndInAnErrorNotUnboundedMemory) {
  std::string objects;
  for (int i = 0; i < 60; ++i) objects += " o" + std::to_string(i);
  const auto [domain, problem] = testing::CubicGroundingTask(60);
  GroundingOptions options;
  options.max_actions = 10'000;  // 60^3 = 216000 would be needed
  auto r = LoadTask(domain, problem, options);
  EXPECT_FALSE(r.ok());
  EXPECT_NE(r.ErrorText().find("budget"), std::string::npos) << r.ErrorText();
  // A universally quantified goal over 60^4 combinations hits the work budget.
  GroundingOptions small_work;
  small_work.max_work = 1'000'000;
  const std::string no_actions =
      "(define (domain big) (:requirements :typing) (:types obj) (:predicates (p ?a ?b ?c - obj)))";
  auto q = LoadTask(no_actions,
                    "(define (problem q) (:domain big) (:objects" + objects +
                        " - obj) (:init) (:goal (forall (?a ?b ?c ?d - obj) (p ?a ?b ?c))))",
                    small_work);
  EXPECT_FALSE(q.ok());
  EXPECT_NE(q.ErrorText().find("work budget"), std::string::npos) << q.ErrorText();
  // Many predicates over many objects: the reachability index is bounded too.
  std::string preds, init, objs;
  for (int i = 0; i < 100; ++i) {
    preds += " (q" + std::to_string(i) + " ?a ?b ?c - obj)";
    init += " (q" + std::to_string(i) + " o0 o1 o2)";
  }
  for (int i = 0; i < 4000; ++i) objs += " o" + std::to_string(i);
  GroundingOptions few_facts;
  few_facts.max_facts = 1000;
  auto wide = LoadTask(
      "(define (domain wide) (:requirements :typing) (:types obj) (:predicates" + preds + "))",
      "(define (problem w) (:domain wide) (:objects" + objs + " - obj) (:init" + init +
          ") (:goal (q0 o0 o1 o2)))",
      few_facts);
  EXPECT_FALSE(wide.ok());
  EXPECT_NE(wide.ErrorText().find("index exceeds the fact budget"), std::string::npos)
      << wide.ErrorText();
  options.max_actions = 0;
  EXPECT_FALSE(options.Validate().ok());
  auto refused = LoadTask(domain, problem, options);
  EXPECT_FALSE(refused.ok());
  EXPECT_FALSE(refused.task);
  EXPECT_NE(refused.ErrorText().find(
                "error: GroundingOptions: max_actions, max_facts and max_work must be > 0"),
            std::string::npos)
      << refused.ErrorText();
}

// A problem whose grounding takes far longer than a stop token allows: the
// 60^3 actions of the budget test, with no budget in the way.
std::pair<std::string, std::string> LargeProblem() {
  std::string objects;
  for (int i = 0; i < 60; ++i) objects += " o" + std::to_string(i);
  return {R"(
(define (domain big) (:requirements :typing) (:types obj)
 (:predicates (p ?a ?b ?c - obj) (q ?a - obj))
 (:action a :parameters (?x ?y ?z - obj) :precondition (q ?x) :effect (p ?x ?y ?z))))",
          "(define (problem q) (:domain big) (:objects" + objects +
              " - obj) (:init (q o1)) (:goal (p o1 o2 o3)))"};
}

TEST(GrounderTest, AStopTokenEndsGroundingAsAResultNotAnError) {
  const auto [domain, problem] = LargeProblem();
  const StopToken expired(StopToken::Clock::now() - std::chrono::seconds(1));
  auto r = LoadTask(domain, problem, GroundingOptions{}, expired);
  EXPECT_TRUE(r.stopped());
  EXPECT_EQ(r.stop_reason, StopReason::kDeadline);
  EXPECT_EQ(r.task, nullptr);
  EXPECT_FALSE(pddl::HasErrors(r.diagnostics)) << r.ErrorText();
  // Stopped at the first check, after the symbols: no later stage ran.
  EXPECT_EQ(r.stats.stages.reachability_ms, 0.0);
  EXPECT_EQ(r.stats.stages.instantiation_ms, 0.0);
  // Cancelled by another component (an RPC whose client left): the same.
  StopToken cancelled;
  cancelled.Cancel();
  auto c = LoadTask(domain, problem, GroundingOptions{}, cancelled);
  EXPECT_EQ(c.stop_reason, StopReason::kCancelled);
  EXPECT_EQ(c.task, nullptr);
}

TEST(GrounderTest, StatisticsTimeEveryStage) {
  const auto [domain, problem] = LargeProblem();
  auto r = LoadTask(domain, problem);
  ASSERT_TRUE(r.ok()) << r.ErrorText();
  EXPECT_FALSE(r.stopped());
  EXPECT_EQ(r.task->actions.size(), 60u * 60u);  // ?x is o1 only
  const GroundingStageTimes& t = r.stats.stages;
  EXPECT_GT(t.symbols_ms, 0.0);
  EXPECT_GT(t.schemas_ms, 0.0);
  EXPECT_GT(t.reachability_ms, 0.0);
  EXPECT_GT(t.instantiation_ms, 0.0);
  EXPECT_GE(r.stats.ground_ms,
            t.symbols_ms + t.schemas_ms + t.reachability_ms + t.instantiation_ms);
  EXPECT_EQ(r.stats.static_atoms, 1u);  // (q o1): no effect changes q
  EXPECT_EQ(r.stats.reachable_atoms, 1u + 60u * 60u);
}

TEST(GrounderTest, ActionAndFactIndexAndExplainMissingAction) {
  auto r = MustLoad(kNav, R"(
(define (problem p) (:domain nav)
 (:objects p1 p2 p3 p4 - place r1 - robot)
 (:init (at r1 p1) (road p1 p2) (road p2 p1) (road p3 p4))
 (:goal (visited p2))))");
  ASSERT_TRUE(r.task && r.domain && r.problem);
  ActionIndex index(*r.task);
  std::vector<std::string> args{"r1", "p1", "p2"};
  ASSERT_EQ(index.Find("move", args).size(), 1u);
  EXPECT_EQ(r.task->actions[static_cast<std::size_t>(index.Find("MOVE", args)[0])].DisplayName(),
            "(move r1 p1 p2)");
  EXPECT_EQ(ExplainMissingAction(*r.domain, *r.problem, "move", args, r.task.get()), "");
  // Case-insensitive arguments too; unreachable, unknown and wrong-arity
  // queries find nothing.
  EXPECT_EQ(index.Find("Move", std::vector<std::string>{"R1", "P1", "p2"}),
            index.Find("move", args));
  EXPECT_TRUE(index.Find("move", std::vector<std::string>{"r1", "p1", "p3"}).empty());
  EXPECT_TRUE(index.Find("move", std::vector<std::string>{"r1", "p1"}).empty());
  EXPECT_TRUE(index.Find("fly", args).empty());
  for (std::size_t a = 0; a < r.task->actions.size(); ++a) {
    const auto& action = r.task->actions[a];
    const auto found = index.Find(action.name, action.args);
    EXPECT_NE(std::find(found.begin(), found.end(), static_cast<ActionId>(a)), found.end())
        << action.DisplayName();
  }

  // Facts the same way: every fact is found under its own name, a static
  // atom (road) or an unreachable one is not a fact.
  FactIndex facts(*r.task);
  for (std::size_t f = 0; f < r.task->facts.size(); ++f) {
    const auto& fact = r.task->facts[f];
    EXPECT_EQ(facts.Find(fact.predicate, fact.args), static_cast<FactId>(f));
  }
  EXPECT_GE(facts.Find("AT", std::vector<std::string>{"R1", "p2"}), 0);
  EXPECT_EQ(facts.Find("road", std::vector<std::string>{"p1", "p2"}), -1);
  EXPECT_EQ(facts.Find("at", std::vector<std::string>{"r1", "p4"}), -1);
  EXPECT_EQ(facts.Find("at", std::vector<std::string>{"r1"}), -1);

  auto explain = [&](const std::string& name, std::vector<std::string> a) {
    return ExplainMissingAction(*r.domain, *r.problem, name, a, r.task.get());
  };
  EXPECT_NE(explain("fly", {"r1"}).find("unknown action"), std::string::npos);
  EXPECT_NE(explain("move", {"r1", "p1"}).find("wrong number of arguments"), std::string::npos);
  EXPECT_NE(explain("move", {"r1", "p1", "p9"}).find("unknown object 'p9'"), std::string::npos);
  EXPECT_NE(explain("move", {"p1", "p1", "p2"}).find("type mismatch"), std::string::npos);
  const std::string s = explain("move", {"r1", "p1", "p3"});
  EXPECT_NE(s.find("(road p1 p3) is false and never changes"), std::string::npos) << s;
  const std::string u = explain("move", {"r1", "p3", "p4"});
  EXPECT_NE(u.find("(at r1 p3) can never become true"), std::string::npos) << u;
}

TEST(GrounderTest, EditedProblemThatNoLongerMatchesTheDomainIsADiagnostic) {
  auto r = MustLoad(kNav, R"(
(define (problem p) (:domain nav) (:objects p1 p2 - place r1 - robot)
 (:init (at r1 p1) (road p1 p2)) (:goal (visited p2))))");
  ASSERT_TRUE(r.domain && r.problem);
  pddl::Problem edited = *r.problem;  // as a replanning loop might do
  edited.init.push_back({"at", {{"r1", {}}, {"port-x", {}}}, {}});
  edited.init.push_back({"teleported", {{"r1", {}}}, {}});
  auto g = Ground(*r.domain, edited);
  EXPECT_FALSE(g.ok());
  EXPECT_NE(g.ErrorText().find("unknown object (found 'port-x'"), std::string::npos)
      << g.ErrorText();
  EXPECT_NE(g.ErrorText().find("teleported"), std::string::npos) << g.ErrorText();
}

std::string ReadTestData(const std::string& name) {
  return seaplan::testing::ReadFile(std::filesystem::path(SEAPLAN_PDDL_TESTDATA) / name);
}

TEST(GrounderTest, LoadTaskFromFilesNamesThePaths) {
  const std::string dir = SEAPLAN_PDDL_TESTDATA;
  auto ok = LoadTaskFromFiles(dir + "/fjord_domain.pddl", dir + "/fjord_case_a.pddl");
  EXPECT_TRUE(ok.ok()) << ok.ErrorText();
  auto bad = LoadTaskFromFiles(dir + "/paper000_domain_verbatim.pddl", dir + "/fjord_case_a.pddl");
  EXPECT_FALSE(bad.ok());
  EXPECT_NE(bad.ErrorText().find("paper000_domain_verbatim.pddl:34:17: error: type mismatch"),
            std::string::npos)
      << bad.ErrorText();
  auto missing = LoadTaskFromFiles(dir + "/no-such-file.pddl", dir + "/fjord_case_a.pddl");
  EXPECT_FALSE(missing.ok());
  ASSERT_EQ(missing.diagnostics.size(), 1u) << missing.ErrorText();
  const pddl::Diagnostic& unreadable = missing.diagnostics[0];
  EXPECT_EQ(unreadable.severity, pddl::Severity::kError);
  EXPECT_EQ(unreadable.location.file, dir + "/no-such-file.pddl");
  EXPECT_EQ(unreadable.symbol, dir + "/no-such-file.pddl");
  EXPECT_EQ(unreadable.message, "cannot read the file");
  EXPECT_EQ(unreadable.expected, "a readable PDDL file");
}

TEST(GrounderTest, FjordCaseAHasTheHandCountedSize) {
  auto r = MustLoad(ReadTestData("fjord_domain.pddl"), ReadTestData("fjord_case_a.pddl"));
  ASSERT_TRUE(r.task);
  const GroundTask& t = *r.task;
  // Actions: move-ship along 4 routes both ways (8); load/unload of 4 containers at 5 ports
  // (20 + 20); repair and refuel only at port-e where the teams are (1 + 1) = 50.
  EXPECT_EQ(t.actions.size(), 50u) << Names(t);
  // Facts: (at ship0 *) 5, (at cont *) 20, (at team port-e) 2, available, busy, no_rep,
  // repaired, no_fuel, fuel, (loaded cont ship0) 4 = 37.
  EXPECT_EQ(t.facts.size(), 37u);
  EXPECT_EQ(t.numeric_vars.size(), 0u);  // route-length and speed are static
  const Action* move = FindAction(t, "(move-ship ship0 port-a port-a port-b port-b r-ab)");
  ASSERT_NE(move, nullptr);
  ASSERT_TRUE(move->ConstantDuration().has_value());
  EXPECT_NEAR(*move->ConstantDuration(), 52 / 0.18, 1e-9);
  EXPECT_EQ(t.goal.positive.size(), 8u);
}

}  // namespace
}  // namespace seaplan::task
