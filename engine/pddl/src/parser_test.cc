#include "seaplan/pddl/parser.h"

#include <gtest/gtest.h>

#include <string>

#include "seaplan/testing/shared_data.h"

namespace seaplan::pddl {
namespace {

// Finds the first diagnostic whose message contains `text`.
const Diagnostic* FindDiag(const std::vector<Diagnostic>& diags, const std::string& text) {
  for (const auto& d : diags) {
    if (d.message.find(text) != std::string::npos) return &d;
  }
  return nullptr;
}

int CountDiag(const std::vector<Diagnostic>& diags, const std::string& text) {
  int n = 0;
  for (const auto& d : diags) n += d.message.find(text) != std::string::npos;
  return n;
}

constexpr const char* kLogistics = R"(
; a comment
(define (domain Logi)   ; names are case-insensitive
  (:requirements :strips :typing :negative-preconditions :equality :fluents :durative-actions
                 :conditional-effects :disjunctive-preconditions :duration-inequalities)
  (:types truck plane - vehicle
          vehicle package - locatable
          city-loc airport - place)
  (:constants hq - city-loc)
  (:predicates (at ?x - locatable ?p - place) (in ?p - package ?v - vehicle)
               (road ?a ?b - place) (owned ?x - (either truck package)))
  (:functions (dist ?a ?b - place) (fuel ?v - vehicle) - number (total-cost))
  (:action Load
    :parameters (?p - package ?v - vehicle ?l - place)
    :precondition (and (at ?p ?l) (at ?v ?l) (not (in ?p ?v)) (or (owned ?p) (= ?l hq)))
    :effect (and (not (at ?p ?l)) (in ?p ?v) (increase (total-cost) 1)))
  (:durative-action drive
    :parameters (?t - truck ?a ?b - place)
    :duration (= ?duration (/ (dist ?a ?b) 10))
    :condition (and (at start (at ?t ?a)) (at start (road ?a ?b)) (over all (>= (fuel ?t) 1))
                    (at start (not (= ?a ?b))))
    :effect (and (at start (not (at ?t ?a))) (at end (at ?t ?b))
                 (at end (decrease (fuel ?t) (* 0.5 ?duration)))
                 (forall (?p - package) (when (at start (in ?p ?t)) (at end (at ?p ?b))))))
  (:durative-action wait
    :parameters (?t - truck)
    :duration (and (>= ?duration 2) (<= ?duration 5))
    :condition (at start (exists (?l - place) (at ?t ?l)))
    :effect (at end (forall (?q - package) (when (in ?q ?t) (owned ?q))))))
)";

constexpr const char* kLogisticsProblem = R"(
(define (problem p1) (:domain logi)
  (:objects t1 - truck pk1 pk2 - package a b - city-loc)
  (:init (at t1 a) (at pk1 a) (road a b) (road b a) (road a hq) (owned pk1)
         (= (dist a b) 30) (= (dist b a) 30) (= (fuel t1) 5) (= (total-cost) 0)
         (at 10.5 (at pk2 b)) (at 20 (not (road a b))) (at 5 (= (fuel t1) 9))
         (not (owned pk2)))
  (:goal (and (at pk1 b) (forall (?p - package) (imply (owned ?p) (at ?p b)))))
  (:metric minimize (+ (* 2 (total-time)) (total-cost))))
)";

TEST(ParseDomainTest, ParsesEveryFeature) {
  auto result = ParseDomain(kLogistics);
  ASSERT_TRUE(result.domain.has_value()) << FormatDiagnostics(result.diagnostics);
  EXPECT_FALSE(HasErrors(result.diagnostics));
  const Domain& d = *result.domain;
  EXPECT_EQ(d.name, "logi");
  EXPECT_EQ(d.requirements.size(), 9u);
  EXPECT_TRUE(d.IsSubtype("truck", "locatable"));
  EXPECT_TRUE(d.IsSubtype("airport", "place"));
  EXPECT_FALSE(d.IsSubtype("truck", "package"));
  ASSERT_EQ(d.constants.size(), 1u);
  EXPECT_EQ(d.constants[0].types, std::vector<std::string>{"city-loc"});
  const PredicateDecl* owned = d.FindPredicate("owned");
  ASSERT_NE(owned, nullptr);
  EXPECT_EQ(owned->parameters[0].types, (std::vector<std::string>{"truck", "package"}));
  ASSERT_EQ(d.functions.size(), 3u);
  EXPECT_EQ(d.functions[1].result_type, "number");

  const Action* load = d.FindAction("load");
  ASSERT_NE(load, nullptr);
  EXPECT_FALSE(load->durative);
  ASSERT_EQ(load->condition.kind, Condition::Kind::kAnd);
  ASSERT_EQ(load->condition.children.size(), 4u);
  EXPECT_EQ(load->condition.children[2].kind, Condition::Kind::kNot);
  EXPECT_EQ(load->condition.children[3].kind, Condition::Kind::kOr);
  EXPECT_EQ(load->condition.children[3].children[1].atom.predicate, "=");
  EXPECT_EQ(load->effect.children[2].kind, Effect::Kind::kNumeric);
  EXPECT_EQ(load->effect.children[2].op, AssignOp::kIncrease);
  EXPECT_EQ(load->location.line, 13);  // the raw string starts with a newline

  const Action* drive = d.FindAction("drive");
  ASSERT_NE(drive, nullptr);
  EXPECT_TRUE(drive->durative);
  ASSERT_EQ(drive->duration.size(), 1u);
  EXPECT_EQ(drive->duration[0].value.kind, NumExpr::Kind::kDiv);
  EXPECT_EQ(drive->condition.children[2].kind, Condition::Kind::kTimed);
  EXPECT_EQ(drive->condition.children[2].time, TimeSpec::kOverAll);
  EXPECT_EQ(drive->condition.children[2].children[0].kind, Condition::Kind::kCompare);
  // (at start (not (= ?a ?b))): equality, not a numeric comparison.
  EXPECT_EQ(drive->condition.children[3].children[0].children[0].kind, Condition::Kind::kAtom);
  const Effect& forall = drive->effect.children[3];
  EXPECT_EQ(forall.kind, Effect::Kind::kForall);
  EXPECT_EQ(forall.children[0].kind, Effect::Kind::kWhen);
  EXPECT_EQ(drive->effect.children[2].children[0].value.children[1].kind, NumExpr::Kind::kDuration);

  const Action* wait = d.FindAction("wait");
  ASSERT_NE(wait, nullptr);
  ASSERT_EQ(wait->duration.size(), 2u);
  EXPECT_EQ(wait->duration[0].comparator, Comparator::kGreaterEqual);
  EXPECT_EQ(wait->duration[1].comparator, Comparator::kLessEqual);
  EXPECT_EQ(wait->condition.children[0].kind, Condition::Kind::kExists);
}

TEST(ParseProblemTest, ParsesInitTimedLiteralsGoalAndMetric) {
  auto d = ParseDomain(kLogistics);
  ASSERT_TRUE(d.domain);
  auto result = ParseProblem(kLogisticsProblem, *d.domain);
  ASSERT_TRUE(result.problem.has_value()) << FormatDiagnostics(result.diagnostics);
  const Problem& p = *result.problem;
  EXPECT_EQ(p.objects.size(), 5u);
  EXPECT_EQ(p.init.size(), 6u);
  EXPECT_EQ(p.numeric_init.size(), 4u);
  ASSERT_EQ(p.timed_literals.size(), 2u);
  EXPECT_DOUBLE_EQ(p.timed_literals[0].time, 10.5);
  EXPECT_TRUE(p.timed_literals[0].positive);
  EXPECT_FALSE(p.timed_literals[1].positive);
  ASSERT_EQ(p.timed_numeric_init.size(), 1u);
  EXPECT_DOUBLE_EQ(p.timed_numeric_init[0].init.value, 9);
  EXPECT_EQ(p.goal.kind, Condition::Kind::kAnd);
  EXPECT_EQ(p.goal.children[1].kind, Condition::Kind::kForall);
  EXPECT_TRUE(p.metric.present);
  EXPECT_TRUE(p.metric.minimize);
  EXPECT_EQ(p.metric.expression.children[0].children[1].kind, NumExpr::Kind::kTotalTime);
  // The negative init literal is dropped with a warning, not an error.
  EXPECT_NE(FindDiag(result.diagnostics, "negative literal"), nullptr);
}

TEST(ParseDomainTest, ReportsEveryErrorWithPosition) {
  const char* text =
      "(define (domain d) (:types a b)\n"
      "(:predicates (p ?x - a) (q ?y - b))\n"
      "(:action act :parameters (?x - a ?y - b)\n"
      " :precondition (and (r ?x) (p ?y) (s))\n"
      " :effect (and (q ?z) (undeclared-too ?x))))\n";
  auto result = ParseDomain(text);
  EXPECT_FALSE(result.domain.has_value());
  const Diagnostic* r = FindDiag(result.diagnostics, "undeclared predicate");
  ASSERT_NE(r, nullptr);
  EXPECT_EQ(r->location.line, 4);
  EXPECT_EQ(r->location.column, 22);
  EXPECT_EQ(r->symbol, "r");
  EXPECT_EQ(CountDiag(result.diagnostics, "undeclared predicate"), 3);  // r, s, undeclared-too
  const Diagnostic* mismatch = FindDiag(result.diagnostics, "type mismatch");
  ASSERT_NE(mismatch, nullptr);
  EXPECT_EQ(mismatch->location.line, 4);
  EXPECT_EQ(mismatch->location.column, 31);
  EXPECT_EQ(mismatch->symbol, "?y");
  EXPECT_NE(mismatch->expected.find('a'), std::string::npos);
  const Diagnostic* var = FindDiag(result.diagnostics, "undeclared variable");
  ASSERT_NE(var, nullptr);
  EXPECT_EQ(var->location.line, 5);
  EXPECT_EQ(var->location.column, 18);
  EXPECT_EQ(var->ToString().rfind("domain:5:18: error: undeclared variable (found '?z'", 0), 0u)
      << var->ToString();
}

TEST(ParseDomainTest, ToleratesByteOrderMarkCrlfAndTabs) {
  auto result = ParseDomain("\xEF\xBB\xBF(define (domain D)\r\n\t(:predicates (P ?X)))\r\n");
  ASSERT_TRUE(result.domain.has_value()) << FormatDiagnostics(result.diagnostics);
  ASSERT_NE(result.domain->FindPredicate("p"), nullptr);
  EXPECT_EQ(result.domain->predicates[0].location.line, 2);
  EXPECT_EQ(result.domain->predicates[0].parameters[0].name, "?x");
}

TEST(ParseDomainTest, SemanticDeclarationErrors) {
  auto cycle = ParseDomain("(define (domain d) (:types a - b b - a))");
  EXPECT_FALSE(cycle.domain);
  EXPECT_NE(FindDiag(cycle.diagnostics, "cycle"), nullptr);

  auto twice = ParseDomain(
      "(define (domain d) (:predicates (p) (p))\n"
      "(:action a :parameters (?x ?x) :precondition (p) :effect (p))\n"
      "(:action a :parameters () :precondition (p) :effect (not (p))))");
  EXPECT_FALSE(twice.domain);
  EXPECT_NE(FindDiag(twice.diagnostics, "predicate declared twice"), nullptr);
  EXPECT_NE(FindDiag(twice.diagnostics, "parameter declared twice"), nullptr);
  const Diagnostic* dup = FindDiag(twice.diagnostics, "action declared twice");
  ASSERT_NE(dup, nullptr);
  EXPECT_EQ(dup->location.line, 3);

  auto arity = ParseDomain(
      "(define (domain d) (:types t) (:predicates (p ?x - t)) (:functions (f ?x - t))\n"
      "(:action a :parameters (?x - t) :precondition (and (p ?x ?x) (> (f) 1)) :effect (p)))");
  EXPECT_FALSE(arity.domain);
  EXPECT_EQ(CountDiag(arity.diagnostics, "wrong number of arguments"), 3)
      << FormatDiagnostics(arity.diagnostics);

  auto either_parent = ParseDomain(
      "(define (domain d) (:types car - (either vehicle asset)) (:predicates (p ?c - car)))");
  ASSERT_TRUE(either_parent.domain) << FormatDiagnostics(either_parent.diagnostics);
  EXPECT_TRUE(either_parent.domain->IsSubtype("car", "asset"));
  EXPECT_TRUE(either_parent.domain->IsSubtype("car", "vehicle"));
}

TEST(ParseDomainTest, SyntaxErrorsHaveClearPositions) {
  auto unmatched = ParseDomain("(define (domain d))\n)");
  const Diagnostic* d = FindDiag(unmatched.diagnostics, "unmatched ')'");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->location.line, 2);
  EXPECT_EQ(d->location.column, 1);

  auto unknown_section = ParseDomain("(define (domain d) (:predicate (p)))");
  d = FindDiag(unknown_section.diagnostics, "unknown domain section");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->location.column, 20);
  EXPECT_EQ(d->kind, DiagnosticKind::kSyntax);

  auto untimed = ParseDomain(
      "(define (domain d) (:predicates (p)) (:durative-action a :parameters () :duration (= "
      "?duration 1)"
      " :condition (p) :effect (at end (p))))");
  EXPECT_NE(FindDiag(untimed.diagnostics, "without a time specifier"), nullptr);

  auto problem_as_domain = ParseDomain("(define (problem x) (:domain d))");
  EXPECT_NE(FindDiag(problem_as_domain.diagnostics, "this is a problem"), nullptr);
}

TEST(ParseDomainTest, UnsupportedConstructsNameTheConstruct) {
  struct Case {
    const char* text;
    const char* construct;
  };
  const Case cases[] = {
      {"(define (domain d) (:requirements :derived-predicates) (:predicates (p)))",
       "derived predicates"},
      {"(define (domain d) (:predicates (p) (q)) (:derived (p) (q)))", "derived predicate"},
      {"(define (domain d) (:predicates (p)) (:action a :parameters () :precondition (preference x "
       "(p))"
       " :effect (p)))",
       "preference"},
      {"(define (domain d) (:functions (f)) (:durative-action a :parameters () :duration (= "
       "?duration 1)"
       " :condition () :effect (increase (f) (* #t 2))))",
       "continuous effect"},
      {"(define (domain d) (:predicates (p)) (:process flow :parameters () :precondition (p) "
       ":effect ()))",
       "process"},
      {"(define (domain d) (:predicates (p)) (:constraints (always (p))))", "constraints"},
  };
  {
    auto d = ParseDomain("(define (domain d) (:predicates (p)))");
    ASSERT_TRUE(d.domain);
    auto p = ParseProblem(
        "(define (problem q) (:domain d) (:goal (p)) (:metric minimize (is-violated pref1)))",
        *d.domain);
    EXPECT_TRUE(HasUnsupported(p.diagnostics)) << FormatDiagnostics(p.diagnostics);
    EXPECT_NE(FindDiag(p.diagnostics, "is-violated"), nullptr);
  }
  for (const auto& c : cases) {
    auto result = ParseDomain(c.text);
    EXPECT_FALSE(result.domain.has_value()) << c.text;
    EXPECT_TRUE(HasUnsupported(result.diagnostics)) << c.text << "\n"
                                                    << FormatDiagnostics(result.diagnostics);
    bool named = false;
    for (const auto& d : result.diagnostics) {
      if (d.kind == DiagnosticKind::kUnsupported &&
          d.message.find(c.construct) != std::string::npos)
        named = true;
    }
    EXPECT_TRUE(named) << c.construct << "\n" << FormatDiagnostics(result.diagnostics);
  }
}

TEST(ParseDomainTest, MalformedInputEndsInDiagnosticNotCrash) {
  std::string deep(100000, '(');
  auto r1 = ParseDomain(deep);
  EXPECT_FALSE(r1.domain);
  EXPECT_NE(FindDiag(r1.diagnostics, "nesting deeper"), nullptr);

  auto r2 = ParseDomain("(define (domain d) (:predicates (p ?x");
  EXPECT_FALSE(r2.domain);
  EXPECT_NE(FindDiag(r2.diagnostics, "unexpected end of file"), nullptr);

  std::string junk = "(define (domain d)";
  for (int i = 0; i < 300; ++i) junk += static_cast<char>((i * 37) & 0xff);
  auto r3 = ParseDomain(junk);
  EXPECT_FALSE(r3.domain);
  EXPECT_TRUE(HasErrors(r3.diagnostics));

  auto r4 = ParseDomain(
      "(define (domain d) (:functions (f)) (:action a :parameters () :precondition (> (f) 1e999) "
      ":effect ()))");
  EXPECT_FALSE(r4.domain);
  EXPECT_NE(FindDiag(r4.diagnostics, "number out of range"), nullptr);

  auto r5 = ParseDomain("");
  EXPECT_FALSE(r5.domain);
  EXPECT_NE(FindDiag(r5.diagnostics, "empty domain"), nullptr);
}

constexpr const char* kSmallDomain =
    "(define (domain d) (:types thing place)\n"
    "  (:constants home - place)\n"
    "  (:predicates (at ?t - thing ?p - place)))\n";

// Domain and problem files share the top-level check; each kind names itself
// and recognises the other.
TEST(ParseProblemTest, TopLevelFormIsCheckedForBothKinds) {
  auto d = ParseDomain(kSmallDomain);
  ASSERT_TRUE(d.domain) << FormatDiagnostics(d.diagnostics);

  auto problem_as_domain = ParseDomain("(define (problem p) (:domain d))");
  EXPECT_FALSE(problem_as_domain.domain);
  EXPECT_NE(FindDiag(problem_as_domain.diagnostics, "this is a problem, not a domain"), nullptr);
  auto domain_as_problem = ParseProblem(kSmallDomain, *d.domain);
  EXPECT_FALSE(domain_as_problem.problem);
  EXPECT_NE(FindDiag(domain_as_problem.diagnostics, "this is a domain, not a problem"), nullptr);

  auto not_define = ParseProblem("(problem p)", *d.domain);
  EXPECT_FALSE(not_define.problem);
  EXPECT_NE(FindDiag(not_define.diagnostics, "expected a problem definition"), nullptr);
  auto empty = ParseProblem("", *d.domain);
  EXPECT_NE(FindDiag(empty.diagnostics, "empty problem"), nullptr);

  auto trailing = ParseDomain(std::string(kSmallDomain) + "(extra)");
  EXPECT_FALSE(trailing.domain);
  const Diagnostic* after = FindDiag(trailing.diagnostics, "text after the domain definition");
  ASSERT_NE(after, nullptr);
  EXPECT_EQ(after->location.line, 4);
}

TEST(ParseProblemTest, ForgivingOnRepeatedDeclarationsStrictOnConflicts) {
  auto d = ParseDomain(kSmallDomain);
  ASSERT_TRUE(d.domain) << FormatDiagnostics(d.diagnostics);
  auto repeated = ParseProblem(
      "(define (problem p) (:domain d) (:objects home - place box box - thing) (:init (at box "
      "home)) (:goal (at box home)))",
      *d.domain);
  EXPECT_TRUE(repeated.problem.has_value()) << FormatDiagnostics(repeated.diagnostics);
  EXPECT_EQ(CountDiag(repeated.diagnostics, "repeats the domain constant"), 1);
  EXPECT_EQ(CountDiag(repeated.diagnostics, "declared twice"), 1);
  EXPECT_EQ(repeated.problem->objects.size(), 1u);

  auto conflict = ParseProblem(
      "(define (problem p) (:domain d) (:objects box - thing\n box - place) (:goal (at box home)))",
      *d.domain);
  EXPECT_FALSE(conflict.problem.has_value());
  const Diagnostic* diag = FindDiag(conflict.diagnostics, "different type");
  ASSERT_NE(diag, nullptr);
  EXPECT_EQ(diag->location.line, 2);
  EXPECT_EQ(diag->location.column, 2);
}

TEST(ParseProblemTest, TypeChecksAgainstTheDomain) {
  auto d = ParseDomain(kSmallDomain);
  ASSERT_TRUE(d.domain);
  auto result = ParseProblem(
      "(define (problem p) (:domain d) (:objects box - thing room - place)\n"
      "(:init (at room box) (at box nowhere) (near box room))\n"
      "(:goal (and (at box room) (gone box))))",
      *d.domain);
  EXPECT_FALSE(result.problem.has_value());
  EXPECT_EQ(CountDiag(result.diagnostics, "type mismatch"), 2);  // both arguments of (at room box)
  const Diagnostic* undeclared = FindDiag(result.diagnostics, "undeclared object");
  ASSERT_NE(undeclared, nullptr);
  EXPECT_EQ(undeclared->symbol, "nowhere");
  EXPECT_EQ(undeclared->location.line, 2);
  EXPECT_EQ(CountDiag(result.diagnostics, "undeclared predicate"), 2);  // near, gone
}

// ---- the paper's verbatim domain (Appendix A of paper 000) ----------------

std::string PaperDomain() {
  // SEAPLAN_PDDL_TESTDATA is set by CMake (the test does not depend on the working directory).
  return seaplan::testing::ReadFile(std::filesystem::path(SEAPLAN_PDDL_TESTDATA) /
                                    "paper000_domain_verbatim.pddl");
}

const Diagnostic* DiagAt(const std::vector<Diagnostic>& diags, const std::string& text, int line,
                         int column) {
  for (const auto& d : diags) {
    if (d.message.find(text) != std::string::npos && d.location.line == line &&
        d.location.column == column)
      return &d;
  }
  return nullptr;
}

TEST(PaperDomainTest, VehicleWhereAtExpectsSubjectIsATypeError) {
  auto result = ParseDomain(PaperDomain());
  EXPECT_FALSE(result.domain.has_value());
  // move-ship line 34: "  (at start (at ?V ?O))", ?V is a vehicle, at wants a subject.
  const Diagnostic* d = DiagAt(result.diagnostics, "type mismatch", 34, 17);
  ASSERT_NE(d, nullptr) << FormatDiagnostics(result.diagnostics);
  EXPECT_EQ(d->kind, DiagnosticKind::kSemantic);
  EXPECT_EQ(d->symbol, "?v");
  EXPECT_NE(d->expected.find("subject"), std::string::npos);
  EXPECT_NE(d->message.find("vehicle"), std::string::npos);
  // Every use is reported, not only the first: move-ship (3), move-fueling-ship (3), load, unload,
  // repair, refuel.
  EXPECT_EQ(CountDiag(result.diagnostics, "type mismatch"), 10);
  EXPECT_NE(DiagAt(result.diagnostics, "type mismatch", 114, 19),
            nullptr);  // refuel-ship's (at ?V ?L)
}

TEST(PaperDomainTest, ZeroForOIsAnUndeclaredVariable) {
  auto result = ParseDomain(PaperDomain());
  // move-fueling-ship lines 52, 53, 60 use ?0 (zero) for ?O.
  const Diagnostic* d = DiagAt(result.diagnostics, "undeclared variable", 52, 22);
  ASSERT_NE(d, nullptr) << FormatDiagnostics(result.diagnostics);
  EXPECT_EQ(d->symbol, "?0");
  EXPECT_NE(d->expected.find("'?o'"), std::string::npos);  // suggests the look-alike
  EXPECT_NE(DiagAt(result.diagnostics, "undeclared variable", 53, 24), nullptr);
  EXPECT_NE(DiagAt(result.diagnostics, "undeclared variable", 60, 27), nullptr);
  EXPECT_EQ(CountDiag(result.diagnostics, "undeclared variable"), 3);
}

TEST(PaperDomainTest, MissingRefuelEffectsAreASyntaxErrorWhereTheTextIsCutOff) {
  const std::string text = PaperDomain();
  auto result = ParseDomain(text);
  const Diagnostic* d = FindDiag(result.diagnostics, "unexpected end of file");
  ASSERT_NE(d, nullptr);
  EXPECT_EQ(d->kind, DiagnosticKind::kSyntax);
  EXPECT_EQ(d->location.line, 118);  // just after the last line of the text
  EXPECT_NE(d->message.find("refuel-ship"), std::string::npos);
  EXPECT_NE(d->message.find("110:1"), std::string::npos);
  // And the action itself is flagged as having no :effect.
  const Diagnostic* w = FindDiag(result.diagnostics, "has no :effect");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->symbol, "refuel-ship");
  EXPECT_EQ(w->location.line, 110);
}

TEST(PaperDomainTest, RefuelGoalNamesNoPredicate) {
  // The corrected domain with the paper's Table 2 goal (refuel ship0).
  const char* domain =
      "(define (domain mass) (:requirements :typing :durative-actions)\n"
      "(:types ship - vehicle port - location vehicle - subject)\n"
      "(:predicates (at ?x - subject ?l - location) (no_fuel ?v - vehicle) (fuel ?v - vehicle))\n"
      "(:durative-action refuel-ship :parameters (?v - ship ?l - port) :duration (= ?duration 80)\n"
      " :condition (and (at start (at ?v ?l)) (at start (no_fuel ?v)))\n"
      " :effect (and (at end (not (no_fuel ?v))) (at end (fuel ?v)))))\n";
  auto d = ParseDomain(domain);
  ASSERT_TRUE(d.domain) << FormatDiagnostics(d.diagnostics);
  const char* problem =
      "(define (problem case-a) (:domain mass)\n"
      "(:objects ship0 - ship port-e - port)\n"
      "(:init (at ship0 port-e) (no_fuel ship0))\n"
      "(:goal (and (at ship0 port-e)\n"
      "            (refuel ship0))))\n";
  auto p = ParseProblem(problem, *d.domain);
  EXPECT_FALSE(p.problem.has_value());
  const Diagnostic* diag = FindDiag(p.diagnostics, "undeclared predicate");
  ASSERT_NE(diag, nullptr);
  EXPECT_EQ(diag->location.file, "problem");
  EXPECT_EQ(diag->location.line, 5);
  EXPECT_EQ(diag->location.column, 14);
  EXPECT_EQ(diag->symbol, "refuel");
}

}  // namespace
}  // namespace seaplan::pddl
