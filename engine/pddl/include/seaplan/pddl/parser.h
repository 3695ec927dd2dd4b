// PDDL 2.1 (levels 1-3) + timed initial literals: the abstract syntax tree and
// the parser that builds it.
//
// Supported: :strips :typing (hierarchies, `either`) :negative-preconditions
// :disjunctive-preconditions :equality :existential-preconditions
// :universal-preconditions :quantified-preconditions :conditional-effects :adl
// :numeric-fluents/:fluents :durative-actions :duration-inequalities
// :timed-initial-literals, constants, instantaneous `:action`s, `:metric`
// over total-time and fluents. Names are case-insensitive: every name in the
// AST is lower case. Constructs seaplan does not support (:derived,
// preferences, continuous effects with #t, processes/events, :constraints,
// ...) give a kUnsupported diagnostic that names the construct.
//
// The parser never throws and never crashes on malformed input: nesting is
// capped (kMaxNestingDepth), numbers are range-checked, and every problem is
// a Diagnostic with file/line/column. Several independent errors are
// reported by one call.
//
// Every AST node carries the SourceLocation of its opening token.
// Thread-safety: the functions are pure; the AST is a plain value.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/pddl/diagnostic.h"

namespace seaplan::pddl {

// Deeper s-expressions are rejected with a syntax error (guards the stack).
inline constexpr int kMaxNestingDepth = 256;

// `name - type` in a typed list. `types` holds one entry for a plain type,
// several for `(either t1 t2 ...)`; an untyped name gets {"object"}.
struct TypedName {
  std::string name;  // "?x" for variables (with the '?'), "port-a" for objects
  std::vector<std::string> types;
  SourceLocation location;
};

// `sub - parent` in :types. `parents` has several entries for `either`
// (unusual, accepted); an untyped entry has parent "object".
struct TypeDecl {
  std::string name;
  std::vector<std::string> parents;
  SourceLocation location;
};

struct PredicateDecl {
  std::string name;
  std::vector<TypedName> parameters;
  SourceLocation location;
};

struct FunctionDecl {
  std::string name;
  std::vector<TypedName> parameters;
  std::string result_type = "number";
  SourceLocation location;
};

// A variable ("?x") or an object/constant name.
struct Term {
  std::string name;
  SourceLocation location;
  bool IsVariable() const { return !name.empty() && name[0] == '?'; }
};

// (predicate t1 t2 ...); predicate "=" for equality.
struct Atom {
  std::string predicate;
  std::vector<Term> args;
  SourceLocation location;
};

enum class Comparator { kLess, kLessEqual, kEqual, kGreaterEqual, kGreater };
enum class AssignOp { kAssign, kIncrease, kDecrease, kScaleUp, kScaleDown };
// The time specifier of a durative action's condition or effect.
enum class TimeSpec { kNone, kAtStart, kOverAll, kAtEnd };

struct NumExpr {
  enum class Kind {
    kNumber,     // value
    kFluent,     // (function args...) or a 0-ary `function`
    kDuration,   // ?duration
    kTotalTime,  // total-time (metric only)
    kAdd,
    kSub,
    kMul,
    kDiv,  // children[0] op children[1] (+ and * may have more children)
    kNeg,  // -children[0]
  };
  Kind kind = Kind::kNumber;
  double value = 0.0;
  std::string function;    // kFluent
  std::vector<Term> args;  // kFluent
  std::vector<NumExpr> children;
  SourceLocation location;
};

// A goal description (GD).
struct Condition {
  enum class Kind {
    kTrue,     // (and) / empty condition
    kAtom,     // atom (incl. equality "=")
    kNot,      // children[0]
    kAnd,      // children
    kOr,       // children
    kImply,    // children[0] -> children[1]
    kExists,   // variables, children[0]
    kForall,   // variables, children[0]
    kCompare,  // lhs comparator rhs (numeric)
    kTimed,    // time, children[0] (durative-action conditions only)
  };
  Kind kind = Kind::kTrue;
  Atom atom;
  std::vector<Condition> children;
  std::vector<TypedName> variables;
  Comparator comparator = Comparator::kEqual;
  NumExpr lhs;
  NumExpr rhs;
  TimeSpec time = TimeSpec::kNone;
  SourceLocation location;
};

struct Effect {
  enum class Kind {
    kAnd,      // children
    kAdd,      // atom
    kDelete,   // (not atom)
    kForall,   // variables, children[0]
    kWhen,     // condition, children[0]
    kNumeric,  // op fluent value
    kTimed,    // time, children[0] (durative-action effects only)
  };
  Kind kind = Kind::kAnd;
  Atom atom;
  std::vector<Effect> children;
  std::vector<TypedName> variables;
  Condition condition;  // kWhen (may contain kTimed parts for durative actions)
  AssignOp op = AssignOp::kAssign;
  NumExpr fluent;  // kNumeric: the assigned fluent (kind kFluent)
  NumExpr value;   // kNumeric
  TimeSpec time = TimeSpec::kNone;
  SourceLocation location;
};

// ?duration comparator value.
struct DurationConstraint {
  Comparator comparator = Comparator::kEqual;
  NumExpr value;
  SourceLocation location;
};

// An instantaneous `:action` (durative == false) or a `:durative-action`.
struct Action {
  std::string name;
  std::vector<TypedName> parameters;
  bool durative = false;
  std::vector<DurationConstraint> duration;  // durative only; empty = unconstrained
  Condition condition;                       // kTrue when absent
  Effect effect;                             // kAnd with no children when absent
  SourceLocation location;
};

struct Domain {
  std::string name;
  std::vector<std::string> requirements;  // lower case, with ':'
  // Declared types (without the implicit "object"), in declaration order.
  std::vector<TypeDecl> types;
  std::vector<TypedName> constants;
  std::vector<PredicateDecl> predicates;
  std::vector<FunctionDecl> functions;
  std::vector<Action> actions;
  SourceLocation location;

  const PredicateDecl* FindPredicate(std::string_view name) const;
  const FunctionDecl* FindFunction(std::string_view name) const;
  const Action* FindAction(std::string_view name) const;
  // True when `type` is `ancestor` or a (transitive) subtype of it; every type is an "object".
  // Builds a TypeHierarchy (type_hierarchy.h) per call: callers asking many
  // questions build one themselves.
  bool IsSubtype(std::string_view type, std::string_view ancestor) const;
};

// `(= (f args) value)` in :init.
struct NumericInit {
  std::string function;
  std::vector<std::string> args;
  double value = 0.0;
  SourceLocation location;
};

// `(at time literal)` in :init.
struct TimedLiteral {
  double time = 0.0;
  Atom atom;  // ground
  bool positive = true;
  SourceLocation location;
};

// `(at time (= (f args) value))` in :init (timed initial fluent).
struct TimedNumericInit {
  double time = 0.0;
  NumericInit init;
};

struct Metric {
  bool present = false;
  bool minimize = true;
  NumExpr expression;  // may contain kTotalTime and fluents
  SourceLocation location;
};

struct Problem {
  std::string name;
  std::string domain_name;
  std::vector<TypedName> objects;  // deduplicated; constants of the domain not repeated
  std::vector<Atom>
      init;  // ground positive facts (negative literals in :init are dropped with a warning)
  std::vector<NumericInit> numeric_init;
  std::vector<TimedLiteral> timed_literals;
  std::vector<TimedNumericInit> timed_numeric_init;
  Condition goal;
  Metric metric;
  SourceLocation location;
};

struct DomainParseResult {
  // Set when the domain has no errors (warnings allowed). When errors were
  // found, `domain` is empty and `diagnostics` lists every error found.
  std::optional<Domain> domain;
  std::vector<Diagnostic> diagnostics;
};

struct ProblemParseResult {
  // Set when the problem has no errors against the domain.
  std::optional<Problem> problem;
  std::vector<Diagnostic> diagnostics;
};

// Parses and checks a domain: syntax, declared types/predicates/functions,
// variables bound, argument counts and types, requirements of used
// constructs (reported as warnings when undeclared).
DomainParseResult ParseDomain(std::string_view text, std::string_view file_name = "domain");

// Parses a problem and type-checks it against `domain` (objects typed with
// declared types, init facts and goal atoms use declared predicates with
// objects of the right types, the metric uses declared functions).
ProblemParseResult ParseProblem(std::string_view text, const Domain& domain,
                                std::string_view file_name = "problem");

const char* ComparatorSymbol(Comparator comparator);
const char* TimeSpecName(TimeSpec time);  // "at start", "over all", "at end", ""

}  // namespace seaplan::pddl
