#include <gtest/gtest.h>

#include <string>

#include "grounding_test_util.h"
#include "schema_internal.h"

namespace seaplan::task::internal {
namespace {

using Kind = SchemaCondition::Kind;

constexpr const char* kProblem = R"(
(define (problem p) (:domain d)
 (:objects a b c - item)
 (:init (red a) (link a b))
 (:goal (done a))))";

std::string Domain(const std::string& parameters, const std::string& precondition,
                   const std::string& effect) {
  return R"(
(define (domain d) (:requirements :adl :fluents)
 (:types item)
 (:predicates (red ?x - item) (blue ?x - item) (green ?x - item) (done ?x - item)
              (link ?x ?y - item))
 (:functions (weight ?x - item))
 (:action act :parameters ()" +
         parameters + ")\n   :precondition " + precondition + "\n   :effect " + effect + "))";
}

struct Compiled {
  std::optional<SymbolTable> symbols;
  std::optional<CompiledSchemas> schemas;
};

Compiled Compile(StageFixture& f) {
  Compiled out;
  out.symbols = BuildSymbols(f.domain(), f.problem(), f.context());
  EXPECT_TRUE(out.symbols) << f.DiagnosticText();
  if (out.symbols) out.schemas = CompileSchemas(f.domain(), f.problem(), *out.symbols, f.context());
  return out;
}

TEST(SchemaTest, ConditionsAreInNegationNormalForm) {
  // not (red and (blue -> green))  ==  (not red) or (blue and not green)
  StageFixture f(
      Domain("?x - item", "(not (and (red ?x) (imply (blue ?x) (green ?x))))", "(done ?x)"),
      kProblem);
  Compiled c = Compile(f);
  ASSERT_TRUE(c.schemas) << f.DiagnosticText();
  const SchemaCondition& root = c.schemas->schema(SchemaId(0)).condition;
  ASSERT_EQ(root.kind, Kind::kOr);
  ASSERT_EQ(root.children.size(), 2u);
  EXPECT_EQ(root.children[0].kind, Kind::kAtom);
  EXPECT_FALSE(root.children[0].positive);
  EXPECT_EQ(c.symbols->Name(root.children[0].predicate), "red");
  const SchemaCondition& conjunction = root.children[1];
  ASSERT_EQ(conjunction.kind, Kind::kAnd);
  EXPECT_TRUE(conjunction.children[0].positive);   // blue
  EXPECT_FALSE(conjunction.children[1].positive);  // not green
  // Parameter ?x is slot 0 in every atom.
  EXPECT_TRUE(conjunction.children[1].args[0].is_variable());
  EXPECT_EQ(conjunction.children[1].args[0].slot(), VariableSlot(0));
  // Two DNF disjuncts: {not red} and {blue, not green}; only blue joins.
  const Schema& s = c.schemas->schema(SchemaId(0));
  ASSERT_EQ(s.disjuncts.size(), 2u);
  EXPECT_TRUE(c.schemas->disjunct(s.disjuncts[0]).join_atoms.empty());
  EXPECT_EQ(c.schemas->disjunct(s.disjuncts[1]).join_atoms, (std::vector<int>{0}));
  // No effect changes blue: a static atom, so the disjunct fires once, unprompted.
  EXPECT_FALSE(c.schemas->disjunct(s.disjuncts[1]).has_fluent_atom);
}

TEST(SchemaTest, ExistsVariablesBecomeFreeVariablesOfTheDisjunct) {
  StageFixture f(
      Domain("?x - item", "(and (red ?x) (exists (?y - item) (link ?x ?y)))", "(done ?x)"),
      kProblem);
  Compiled c = Compile(f);
  ASSERT_TRUE(c.schemas);
  const Schema& s = c.schemas->schema(SchemaId(0));
  ASSERT_EQ(s.disjuncts.size(), 1u);
  const PreconditionDisjunct& d = c.schemas->disjunct(s.disjuncts[0]);
  EXPECT_EQ(d.items.size(), 2u);
  EXPECT_EQ(d.free_variables, (std::vector<VariableSlot>{VariableSlot(0), VariableSlot(1)}));
  EXPECT_EQ(s.variables[1].name, "?y");
  EXPECT_EQ(s.variables[1].objects.size(), 3u);
  // red and link are static (no effect touches them): nothing to trigger on.
  EXPECT_FALSE(d.has_fluent_atom);
}

TEST(SchemaTest, EffectsAreFlattenedWithTheirForallsAndConditions) {
  StageFixture f(Domain("?x - item", "(red ?x)",
                        "(and (done ?x) (forall (?y - item) (when (link ?x ?y) (not (blue ?y)))) "
                        "(increase (weight ?x) 2))"),
                 kProblem);
  Compiled c = Compile(f);
  ASSERT_TRUE(c.schemas);
  const auto& effects = c.schemas->schema(SchemaId(0)).effects;
  ASSERT_EQ(effects.size(), 3u);
  EXPECT_EQ(effects[0].kind, SchemaEffect::Kind::kAdd);
  EXPECT_EQ(effects[0].condition.kind, Kind::kTrue);
  EXPECT_EQ(effects[1].kind, SchemaEffect::Kind::kDelete);
  EXPECT_EQ(effects[1].forall_variables, (std::vector<VariableSlot>{VariableSlot(1)}));
  ASSERT_EQ(effects[1].condition.kind, Kind::kAnd);
  EXPECT_EQ(c.symbols->Name(effects[1].condition.children[0].predicate), "link");
  EXPECT_EQ(effects[2].kind, SchemaEffect::Kind::kNumeric);
  EXPECT_EQ(effects[2].value.kind, SchemaExpression::Kind::kNumber);
  EXPECT_EQ(effects[2].value.number, 2.0);
}

TEST(SchemaTest, NegatedNumericEqualityIsLessOrGreater) {
  StageFixture f(Domain("?x - item", "(not (= (weight ?x) 1))", "(done ?x)"), kProblem);
  Compiled c = Compile(f);
  ASSERT_TRUE(c.schemas);
  const SchemaCondition& root = c.schemas->schema(SchemaId(0)).condition;
  ASSERT_EQ(root.kind, Kind::kOr);
  EXPECT_EQ(root.children[0].comparator, pddl::Comparator::kLess);
  EXPECT_EQ(root.children[1].comparator, pddl::Comparator::kGreater);
  // No effect changes weight here, so the comparison can be evaluated while grounding.
  EXPECT_TRUE(IsStaticExpression(root.children[0].lhs, *c.symbols));
}

TEST(SchemaTest, ADnfBeyondTheCapIsUnsupported) {
  // 9 binary disjunctions in a conjunction: 512 disjuncts > 256.
  std::string precondition = "(and";
  for (int i = 0; i < 9; ++i) precondition += " (or (red ?x) (blue ?x))";
  precondition += ")";
  StageFixture f(Domain("?x - item", precondition, "(done ?x)"), kProblem);
  Compiled c = Compile(f);
  EXPECT_FALSE(c.schemas);
  EXPECT_NE(f.DiagnosticText().find("more than 256 disjuncts"), std::string::npos)
      << f.DiagnosticText();
}

TEST(SchemaTest, GoalAndMetricAreCompiledToo) {
  StageFixture f(Domain("?x - item", "(red ?x)", "(done ?x)"), R"(
(define (problem p) (:domain d)
 (:objects a b - item)
 (:init (red a) (= (weight a) 1))
 (:goal (forall (?z - item) (done ?z)))
 (:metric minimize (+ (weight a) 2))))");
  Compiled c = Compile(f);
  ASSERT_TRUE(c.schemas);
  EXPECT_EQ(c.schemas->goal->condition.kind, Kind::kForall);
  EXPECT_EQ(c.schemas->goal->variables.size(), 1u);
  ASSERT_TRUE(c.schemas->metric);
  EXPECT_EQ(c.schemas->metric->kind, SchemaExpression::Kind::kAdd);
}

}  // namespace
}  // namespace seaplan::task::internal
