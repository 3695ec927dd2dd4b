#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "grounding_test_util.h"
#include "reachability_internal.h"

namespace seaplan::task::internal {
namespace {

constexpr const char* kNav = R"(
(define (domain nav) (:requirements :strips :typing :negative-preconditions :timed-initial-literals)
 (:types place robot)
 (:predicates (at ?r - robot ?p - place) (road ?a ?b - place) (visited ?p - place)
              (blocked ?p - place) (lit ?p - place))
 (:action move :parameters (?r - robot ?a ?b - place)
   :precondition (and (at ?r ?a) (road ?a ?b) (not (blocked ?b)))
   :effect (and (not (at ?r ?a)) (at ?r ?b) (visited ?b)))
 (:action shine :parameters (?r - robot ?p - place)
   :precondition (and (at ?r ?p) (lit ?p))
   :effect (visited ?p)))
)";

// Roads p1->p2, p2->p3, p3->p2, p3->p4 (p4 blocked), p5->p1 (p5 never reached).
constexpr const char* kNavProblem = R"(
(define (problem p) (:domain nav)
 (:objects p1 p2 p3 p4 p5 - place r1 - robot)
 (:init (at r1 p1) (road p1 p2) (road p2 p3) (road p3 p2) (road p3 p4) (road p5 p1) (blocked p4)
        (at 10 (lit p3)))
 (:goal (visited p3))))";

struct Explored {
  std::optional<SymbolTable> symbols;
  std::optional<CompiledSchemas> schemas;
  std::optional<ReachableTask> reachable;
};

Explored Explore(StageFixture& f) {
  Explored out;
  out.symbols = BuildSymbols(f.domain(), f.problem(), f.context());
  if (!out.symbols) return out;
  out.schemas = CompileSchemas(f.domain(), f.problem(), *out.symbols, f.context());
  if (!out.schemas) return out;
  out.reachable = ExploreReachability(*out.symbols, *out.schemas, f.problem(), f.context());
  return out;
}

bool Reached(Explored& e, const std::string& predicate, const std::vector<std::string>& args) {
  std::vector<ObjectId> objects;
  objects.reserve(args.size());
  for (const auto& a : args) objects.push_back(e.symbols->FindObject(a));
  return e.reachable->atoms.IsReached(
      e.reachable->atoms.Find(e.symbols->FindPredicate(predicate), objects));
}

TEST(ReachabilityTest, TheFixpointReachesExactlyWhatTheRelaxedTaskCan) {
  StageFixture f(kNav, kNavProblem);
  Explored e = Explore(f);
  ASSERT_TRUE(e.reachable) << f.DiagnosticText();
  EXPECT_TRUE(Reached(e, "at", {"r1", "p1"}));
  EXPECT_TRUE(Reached(e, "at", {"r1", "p3"}));
  EXPECT_TRUE(Reached(e, "visited", {"p3"}));
  EXPECT_FALSE(Reached(e, "at", {"r1", "p4"}));   // (not (blocked p4)) is statically false
  EXPECT_FALSE(Reached(e, "at", {"r1", "p5"}));   // no road into p5
  EXPECT_TRUE(Reached(e, "lit", {"p3"}));         // a timed literal adds it
  EXPECT_TRUE(Reached(e, "road", {"p1", "p2"}));  // static atoms are reached from the start
  EXPECT_EQ(e.reachable->static_true_atoms, 6u);  // five roads and (blocked p4)
  // move r1 p1 p2, p2 p3, p3 p2; shine r1 p3. Not move r1 p3 p4 nor r1 p5 p1.
  EXPECT_EQ(e.reachable->instances.size(), 4u);
  EXPECT_EQ(e.reachable->initial_atoms.size(), 1u);
  EXPECT_EQ(e.reachable->timed_literal_atoms.size(), 1u);
}

TEST(ReachabilityTest, InstancesBindEveryParameter) {
  StageFixture f(kNav, kNavProblem);
  Explored e = Explore(f);
  ASSERT_TRUE(e.reachable);
  std::vector<std::string> moves;
  for (std::size_t i = 0; i < e.reachable->instances.size(); ++i) {
    const PreconditionDisjunct& d = e.schemas->disjunct(e.reachable->instances.disjunct(i));
    if (e.schemas->schema_of(d).action->name != "move") continue;
    std::string text;
    for (ObjectId o : e.reachable->instances.binding(i)) text += e.symbols->Name(o) + " ";
    moves.push_back(text);
  }
  std::sort(moves.begin(), moves.end());
  EXPECT_EQ(moves, (std::vector<std::string>{"r1 p1 p2 ", "r1 p2 p3 ", "r1 p3 p2 "}));
}

TEST(ReachabilityTest, AStopRequestEndsTheStageWithoutAnError) {
  auto stop = StopToken::WithTimeout(std::chrono::seconds(3600));
  stop.Cancel();
  StageFixture f(kNav, kNavProblem, {}, stop);
  Explored e = Explore(f);
  EXPECT_FALSE(e.reachable);
  EXPECT_EQ(f.context().stop_reason(), StopReason::kCancelled);
  EXPECT_TRUE(f.diagnostics().empty()) << f.DiagnosticText();
}

TEST(ReachabilityTest, TheFactBudgetEndsTheStageWithADiagnostic) {
  GroundingOptions options;
  options.max_facts = 2;
  StageFixture f(kNav, kNavProblem, options);
  Explored e = Explore(f);
  EXPECT_FALSE(e.reachable);
  EXPECT_NE(f.DiagnosticText().find("fact budget of 2 atoms"), std::string::npos)
      << f.DiagnosticText();
}

TEST(ReachabilityTest, StaticFunctionsAreEvaluatedUnderABinding) {
  StageFixture f(R"(
(define (domain d) (:requirements :typing :fluents)
 (:types item)
 (:predicates (ok ?x - item))
 (:functions (size ?x - item))
 (:action a :parameters (?x - item) :precondition (> (size ?x) 1) :effect (ok ?x)))
)",
                 R"(
(define (problem p) (:domain d) (:objects a b c - item)
 (:init (= (size a) 2) (= (size b) 1)) (:goal (ok a))))");
  Explored e = Explore(f);
  ASSERT_TRUE(e.reachable);
  // a: 2 > 1 holds; b: 1 > 1 fails; c: undefined, so never applicable.
  EXPECT_TRUE(Reached(e, "ok", {"a"}));
  EXPECT_FALSE(Reached(e, "ok", {"b"}));
  EXPECT_FALSE(Reached(e, "ok", {"c"}));
  const auto& condition = e.schemas->schema(SchemaId(0)).condition;
  const Binding b{e.symbols->FindObject("a")};
  EXPECT_EQ(EvaluateStatic(condition.lhs, b, e.reachable->function_terms), 2.0);
  EXPECT_TRUE(std::isnan(EvaluateStatic(condition.lhs, Binding{e.symbols->FindObject("c")},
                                        e.reachable->function_terms)));
}

}  // namespace
}  // namespace seaplan::task::internal
