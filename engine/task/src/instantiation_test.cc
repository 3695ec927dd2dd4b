#include <gtest/gtest.h>

#include <string>

#include "grounding_test_util.h"
#include "instantiation_internal.h"

namespace seaplan::task::internal {
namespace {

constexpr const char* kDomain = R"(
(define (domain lamp) (:requirements :adl :typing :fluents)
 (:types room)
 (:predicates (in ?r - room) (door ?a ?b - room) (on ?r - room) (dark ?r - room) (wired ?r - room))
 (:functions (energy) (cost ?r - room))
 (:action walk :parameters (?a ?b - room)
   :precondition (and (in ?a) (or (door ?a ?b) (door ?b ?a)))
   :effect (and (not (in ?a)) (in ?b)))
 (:action switch :parameters (?r - room)
   :precondition (and (in ?r) (>= (energy) (cost ?r)))
   :effect (and (on ?r) (decrease (energy) (cost ?r))
                (forall (?o - room) (when (wired ?o) (not (dark ?o)))))))
)";

constexpr const char* kProblem = R"(
(define (problem p) (:domain lamp)
 (:objects hall kitchen cellar - room)
 (:init (in hall) (door hall kitchen) (wired kitchen) (dark kitchen) (dark cellar)
        (= (energy) 5) (= (cost hall) 1) (= (cost kitchen) 2))
 (:goal (and (on kitchen) (on cellar)))))";

struct Grounded {
  std::optional<SymbolTable> symbols;
  std::optional<CompiledSchemas> schemas;
  InstantiatedTask instantiated;
};

// Runs the four stages; `before_instantiation` runs between reachability and instantiation.
template <typename Hook>
Grounded GroundAll(StageFixture& f, Hook before_instantiation) {
  Grounded out;
  out.symbols = BuildSymbols(f.domain(), f.problem(), f.context());
  if (!out.symbols) return out;
  out.schemas = CompileSchemas(f.domain(), f.problem(), *out.symbols, f.context());
  if (!out.schemas) return out;
  auto reachable = ExploreReachability(*out.symbols, *out.schemas, f.problem(), f.context());
  if (!reachable) return out;
  before_instantiation();
  out.instantiated = Instantiate(f.domain(), f.problem(), *out.symbols, *out.schemas,
                                 std::move(*reachable), f.context());
  return out;
}

std::vector<std::string> FactNames(const GroundTask& task) {
  std::vector<std::string> names;
  for (const auto& fact : task.facts) names.push_back(fact.DisplayName());
  return names;
}

TEST(InstantiationTest, FactsAreNumberedInAtomOrderWithUnreachableGoalsLast) {
  StageFixture f(kDomain, kProblem);
  Grounded g = GroundAll(f, [] {});
  ASSERT_TRUE(g.instantiated.task) << f.DiagnosticText();
  const GroundTask& task = *g.instantiated.task;
  // :init's fluent atoms first, then what the fixpoint reached, then the goal
  // fact nothing reaches ((on cellar): nobody can walk into the cellar).
  EXPECT_EQ(FactNames(task),
            (std::vector<std::string>{"(in hall)", "(dark kitchen)", "(dark cellar)",
                                      "(in kitchen)", "(on hall)", "(on kitchen)", "(on cellar)"}));
  EXPECT_EQ(task.initial_facts, (std::vector<FactId>{0, 1, 2}));
  EXPECT_EQ(task.goal.positive, (std::vector<FactId>{5, 6}));
  EXPECT_NE(f.DiagnosticText().find("goal fact is unreachable"), std::string::npos);
  // Only (energy) changes; the costs are folded into constants.
  ASSERT_EQ(task.numeric_vars.size(), 1u);
  EXPECT_EQ(task.initial_values[0], 5.0);
  EXPECT_EQ(g.instantiated.atoms_seen, 9u);  // 2 static (door, wired), 6 reached, (on cellar)
}

TEST(InstantiationTest, ActionsAreGroundedAndSimplified) {
  StageFixture f(kDomain, kProblem);
  Grounded g = GroundAll(f, [] {});
  ASSERT_TRUE(g.instantiated.task);
  const GroundTask& task = *g.instantiated.task;
  std::vector<std::string> names;
  for (const auto& a : task.actions)
    names.push_back(a.DisplayName() + "#" + std::to_string(a.variant));
  // In the order the fixpoint reached them: (in hall) triggers walk (by the
  // first disjunct) and switch; (in kitchen) then walk back (by the second
  // disjunct, whose trigger comes first) and switch. Nobody gets to the cellar.
  EXPECT_EQ(names, (std::vector<std::string>{"(walk hall kitchen)#0", "(switch hall)#0",
                                             "(walk kitchen hall)#0", "(switch kitchen)#0"}));
  const Action& switch_hall = task.actions[1];
  // (>= (energy) (cost hall)) keeps the variable and folds the cost to 1.
  ASSERT_EQ(switch_hall.at_start.numeric.size(), 1u);
  EXPECT_TRUE(switch_hall.at_start.numeric[0].rhs.IsConstant());
  EXPECT_EQ(switch_hall.at_start.numeric[0].rhs.ConstantValue(), 1.0);
  // The forall/when: only kitchen is wired (static), so the effect is an
  // unconditional delete of (dark kitchen); cellar's never applies.
  EXPECT_EQ(switch_hall.start_effects.del, (std::vector<FactId>{1}));
  EXPECT_TRUE(switch_hall.start_effects.conditional.empty());
  ASSERT_EQ(switch_hall.start_effects.numeric.size(), 1u);
  EXPECT_EQ(switch_hall.start_effects.numeric[0].op, AssignOp::kDecrease);
}

TEST(InstantiationTest, AStopRequestBeforeInstantiationLeavesNoTask) {
  auto stop = StopToken::WithTimeout(std::chrono::seconds(3600));
  StageFixture f(kDomain, kProblem, {}, stop);
  Grounded g = GroundAll(f, [&] { stop.Cancel(); });
  EXPECT_EQ(g.instantiated.task, nullptr);
  EXPECT_EQ(f.context().stop_reason(), StopReason::kCancelled);
}

TEST(InstantiationTest, GroundDnfMultipliesOutConjunctionsOfDisjunctions) {
  GroundFormula a, b, c;
  a.kind = b.kind = c.kind = GroundFormula::Kind::kLiteral;
  a.fact = 0;
  b.fact = 1;
  c.fact = 2;
  GroundFormula either;
  either.kind = GroundFormula::Kind::kOr;
  either.children = {b, c};
  GroundFormula root;
  root.kind = GroundFormula::Kind::kAnd;
  root.children = {a, either};
  std::vector<GroundConjunction> dnf;
  ASSERT_TRUE(ToGroundDnf(root, dnf));
  ASSERT_EQ(dnf.size(), 2u);  // (a and b) or (a and c)
  ASSERT_EQ(dnf[0].leaves.size(), 2u);
  EXPECT_EQ(dnf[0].leaves[0]->fact, 0);
  EXPECT_EQ(dnf[0].leaves[1]->fact, 1);
  EXPECT_EQ(dnf[1].leaves[1]->fact, 2);
}

}  // namespace
}  // namespace seaplan::task::internal
