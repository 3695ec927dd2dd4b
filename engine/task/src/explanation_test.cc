#include <gtest/gtest.h>

#include <string>

#include "explanation_internal.h"
#include "grounding_test_util.h"

namespace seaplan::task::internal {
namespace {

constexpr const char* kDomain = R"(
(define (domain ferry) (:requirements :typing :negative-preconditions :fluents :equality)
 (:types place car)
 (:predicates (at ?c - car ?p - place) (route ?a ?b - place) (closed ?p - place))
 (:functions (length ?a ?b - place))
 (:action carry :parameters (?c - car ?a ?b - place)
   :precondition (and (at ?c ?a) (route ?a ?b) (not (closed ?b)) (not (= ?a ?b))
                      (< (length ?a ?b) 10))
   :effect (and (not (at ?c ?a)) (at ?c ?b))))
)";

constexpr const char* kProblem = R"(
(define (problem p) (:domain ferry)
 (:objects c1 - car north south east west - place)
 (:init (at c1 north) (route north south) (route south east) (route north west)
        (route west north) (closed east) (= (length north south) 3) (= (length north west) 30))
 (:goal (at c1 south))))";

// Runs stages 1-3 and explains (carry args...) from their values.
std::string Explain(const std::vector<std::string>& args) {
  StageFixture f(kDomain, kProblem);
  auto symbols = BuildSymbols(f.domain(), f.problem(), f.context());
  auto schemas = CompileSchemas(f.domain(), f.problem(), *symbols, f.context());
  auto reachable = ExploreReachability(*symbols, *schemas, f.problem(), f.context());
  EXPECT_TRUE(reachable) << f.DiagnosticText();
  if (!reachable) return "";
  std::vector<ObjectId> objects;
  std::string call = "(carry";
  for (const auto& a : args) {
    objects.push_back(symbols->FindObject(a));
    call += " " + a;
  }
  call += ")";
  return ExplainInstance(*symbols, *schemas, *reachable, SchemaId(0), objects, call, false);
}

TEST(ExplanationTest, NamesTheFirstFalsePrecondition) {
  EXPECT_EQ(Explain({"c1", "east", "north"}),
            "(carry c1 east north): the precondition (at c1 east) can never become true "
            "(unreachable from the initial state)");
  // (at c1 south) and (route south east) hold: the third precondition is the reason.
  EXPECT_EQ(Explain({"c1", "south", "east"}),
            "(carry c1 south east): the precondition (not (closed east)) is false and never "
            "changes (static)");
  EXPECT_EQ(Explain({"c1", "north", "east"}),
            "(carry c1 north east): the precondition (route north east) is false and never "
            "changes (static)");
  EXPECT_EQ(Explain({"c1", "north", "north"}),
            "(carry c1 north north): the precondition (route north north) is false and never "
            "changes (static)");
  EXPECT_EQ(Explain({"c1", "north", "west"}),
            "(carry c1 north west): a numeric precondition over static functions is false "
            "(30.000000 < 10.000000)");
}

TEST(ExplanationTest, SaysSoWhenNoReasonIsFound) {
  EXPECT_EQ(Explain({"c1", "north", "south"}),
            "(carry c1 north south): no reason found: its static preconditions hold and its fact "
            "preconditions are reachable");
}

TEST(ExplanationTest, ThePublicEntryChecksNamesArityAndTypesFirst) {
  StageFixture f(kDomain, kProblem);
  const std::vector<std::string> two{"c1", "north"};
  EXPECT_NE(
      ExplainMissingAction(f.domain(), f.problem(), "sail", two).find("unknown action 'sail'"),
      std::string::npos);
  EXPECT_NE(ExplainMissingAction(f.domain(), f.problem(), "carry", two)
                .find("wrong number of arguments: 2 given"),
            std::string::npos);
  const std::vector<std::string> swapped{"north", "c1", "south"};
  EXPECT_EQ(ExplainMissingAction(f.domain(), f.problem(), "CARRY", swapped),
            "(carry north c1 south): type mismatch: argument 1 'north' is a place, but ?c must be "
            "a car");
  const std::vector<std::string> unknown{"c1", "north", "mars"};
  EXPECT_EQ(ExplainMissingAction(f.domain(), f.problem(), "carry", unknown),
            "(carry c1 north mars): unknown object 'mars'");
}

}  // namespace
}  // namespace seaplan::task::internal
