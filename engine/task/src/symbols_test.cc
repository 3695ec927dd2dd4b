#include <gtest/gtest.h>

#include "grounding_test_util.h"
#include "symbols_internal.h"

namespace seaplan::task::internal {
namespace {

constexpr const char* kFleetDomain = R"(
(define (domain fleet) (:requirements :typing :fluents :durative-actions :timed-initial-literals)
 (:types vehicle port - object ship ferry - vehicle)
 (:constants depot - port)
 (:predicates (at ?v - vehicle ?p - port) (link ?a ?b - port) (open ?p - port))
 (:functions (fuel ?v - vehicle) (distance ?a ?b - port))
 (:durative-action sail :parameters (?v - vehicle ?a ?b - port)
   :duration (= ?duration (distance ?a ?b))
   :condition (and (at start (at ?v ?a)) (at start (link ?a ?b)) (over all (open ?b)))
   :effect (and (at start (not (at ?v ?a))) (at end (at ?v ?b))
                (at end (decrease (fuel ?v) (distance ?a ?b))))))
)";

constexpr const char* kFleetProblem = R"(
(define (problem p) (:domain fleet)
 (:objects s1 - ship f1 - ferry p1 p2 - port)
 (:init (at s1 p1) (at f1 p2) (link p1 p2) (link p2 p1) (link depot p1)
        (= (fuel s1) 10) (= (fuel f1) 5) (= (distance p1 p2) 3) (= (distance p2 p1) 3)
        (at 5 (open p2)))
 (:goal (at s1 p2))))";

std::vector<std::string> NamesOf(const SymbolTable& symbols, const std::vector<ObjectId>& objects) {
  std::vector<std::string> names;
  names.reserve(objects.size());
  for (ObjectId o : objects) names.push_back(symbols.Name(o));
  return names;
}

TEST(SymbolsTest, ObjectsOfEachTypeFollowTheHierarchyInIdOrder) {
  StageFixture f(kFleetDomain, kFleetProblem);
  auto symbols = BuildSymbols(f.domain(), f.problem(), f.context());
  ASSERT_TRUE(symbols) << f.DiagnosticText();
  // Constants come first, then the problem's objects.
  EXPECT_EQ(symbols->Name(ObjectId(0)), "depot");
  const auto of = [&](const std::string& type) {
    return NamesOf(*symbols, symbols->objects_of_type[symbols->FindType(type).index()]);
  };
  EXPECT_EQ(of("vehicle"), (std::vector<std::string>{"s1", "f1"}));
  EXPECT_EQ(of("ship"), (std::vector<std::string>{"s1"}));
  EXPECT_EQ(of("port"), (std::vector<std::string>{"depot", "p1", "p2"}));
  EXPECT_EQ(of("object").size(), 5u);
  const ObjectId s1 = symbols->FindObject("s1");
  EXPECT_TRUE(symbols->HasType(s1, symbols->FindType("vehicle")));
  EXPECT_FALSE(symbols->HasType(s1, symbols->FindType("ferry")));
  EXPECT_FALSE(symbols->FindObject("nowhere").valid());
}

TEST(SymbolsTest, StaticsAreWhatNoEffectOrTimedLiteralChanges) {
  StageFixture f(kFleetDomain, kFleetProblem);
  auto symbols = BuildSymbols(f.domain(), f.problem(), f.context());
  ASSERT_TRUE(symbols);
  EXPECT_FALSE(symbols->IsStatic(symbols->FindPredicate("at")));    // effects
  EXPECT_TRUE(symbols->IsStatic(symbols->FindPredicate("link")));   // read only
  EXPECT_FALSE(symbols->IsStatic(symbols->FindPredicate("open")));  // a timed literal
  EXPECT_FALSE(symbols->IsStatic(symbols->FindFunction("fuel")));   // decreased
  EXPECT_TRUE(symbols->IsStatic(symbols->FindFunction("distance")));
}

TEST(SymbolsTest, AnEditedProblemThatNoLongerMatchesIsADiagnosticNotACrash) {
  StageFixture f(kFleetDomain, kFleetProblem);
  pddl::Problem& problem = f.mutable_problem();
  problem.init[0].predicate = "docked";         // not a predicate of the domain
  problem.init[1].args[0].name = "s9";          // not an object
  problem.numeric_init[0].args.push_back("x");  // wrong arity
  EXPECT_FALSE(BuildSymbols(f.domain(), problem, f.context()));
  const std::string text = f.DiagnosticText();
  EXPECT_NE(text.find("initial atom does not match a predicate"), std::string::npos) << text;
  EXPECT_NE(text.find("unknown object"), std::string::npos) << text;
  EXPECT_NE(text.find("numeric initialisation does not match"), std::string::npos) << text;
}

}  // namespace
}  // namespace seaplan::task::internal
