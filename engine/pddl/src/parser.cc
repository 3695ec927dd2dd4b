// The second parsing stage: s-expressions -> AST, with name resolution and
// type checking. Errors are collected, not thrown: every check that fails
// adds a Diagnostic and parsing goes on with the next element, so one run
// reports every independent problem.
#include "seaplan/pddl/parser.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "seaplan/pddl/type_hierarchy.h"
#include "sexpr_internal.h"

namespace seaplan::pddl {
namespace {

using internal::SExpr;

bool IsNumberToken(std::string_view s) {
  if (s.empty()) return false;
  std::size_t i = 0;
  if (s[0] == '-' || s[0] == '+') i = 1;
  if (i < s.size() && s[i] == '.') ++i;
  return i < s.size() && s[i] >= '0' && s[i] <= '9';
}

// PDDL names: a letter (digits and '_' tolerated) then letters, digits, '-', '_'.
bool IsValidName(std::string_view s) {
  if (s.empty()) return false;
  auto ok_first = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  };
  auto ok_rest = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  };
  if (!ok_first(s[0])) return false;
  for (char c : s.substr(1)) {
    if (!ok_rest(c)) return false;
  }
  return true;
}

bool IsValidVariable(std::string_view s) {
  return s.size() >= 2 && s[0] == '?' && IsValidName(s.substr(1));
}

// Whether a term with types `have` may stand where `want` is declared.
enum class TypeFit { kOk, kMaybe, kNever };

TypeFit Fit(const TypeHierarchy& graph, const std::vector<std::string>& have,
            const std::vector<std::string>& want) {
  bool all = true;
  bool any = false;
  for (const auto& h : have) {
    bool fits = false;
    bool overlaps = false;
    for (const auto& w : want) {
      if (graph.IsSubtype(h, w)) fits = true;
      if (graph.IsSubtype(w, h)) overlaps = true;
    }
    all = all && fits;
    any = any || fits || overlaps;
  }
  if (all) return TypeFit::kOk;
  return any ? TypeFit::kMaybe : TypeFit::kNever;
}

std::string JoinTypes(const std::vector<std::string>& types) {
  if (types.size() == 1) return types[0];
  std::string out = "(either";
  for (const auto& t : types) out += " " + t;
  return out + ")";
}

struct Signature {
  std::vector<std::vector<std::string>> parameter_types;
  SourceLocation location;
};

// Shared machinery of domain and problem parsing.
class Builder {
 public:
  Builder(std::string file, std::vector<Diagnostic>& diagnostics)
      : file_(std::move(file)), diags_(diagnostics) {}

  SourceLocation Loc(const SExpr& e) const { return {file_, e.line, e.column}; }

  void Error(DiagnosticKind kind, const SExpr& at, std::string message, std::string expected = "",
             std::string symbol = "\x01") {
    if (symbol == "\x01") symbol = at.is_list ? Describe(at) : at.atom;
    diags_.push_back({Severity::kError, kind, Loc(at), std::move(symbol), std::move(message),
                      std::move(expected)});
  }
  void Warn(const SExpr& at, std::string message, std::string expected = "") {
    diags_.push_back({Severity::kWarning, DiagnosticKind::kSemantic, Loc(at),
                      at.is_list ? Describe(at) : at.atom, std::move(message),
                      std::move(expected)});
  }
  void Unsupported(const SExpr& at, const std::string& construct) {
    diags_.push_back({Severity::kError, DiagnosticKind::kUnsupported, Loc(at),
                      at.is_list ? Describe(at) : at.atom,
                      construct + " is not supported by seaplan", ""});
  }

  // "(head" of a list, for messages.
  static std::string Describe(const SExpr& e) {
    if (!e.is_list) return e.atom;
    if (e.items.empty()) return "()";
    return "(" + (e.items[0].is_list ? std::string("(...)") : e.items[0].atom) + " ...)";
  }

  // ---- typed lists -------------------------------------------------------

  // Parses a list of either variables or names with optional `- type`
  // specifiers, starting at items[begin]. Type names are checked when
  // `check_types` is set.
  std::vector<TypedName> TypedList(const std::vector<SExpr>& items, std::size_t begin,
                                   bool variables, bool check_types) {
    std::vector<TypedName> out;
    std::size_t pending_from = 0;
    for (std::size_t i = begin; i < items.size(); ++i) {
      const SExpr& e = items[i];
      if (e.IsAtom("-")) {
        if (i + 1 >= items.size()) {
          Error(DiagnosticKind::kSyntax, e, "'-' without a type after it", "a type name");
          break;
        }
        if (pending_from == out.size()) {
          Error(DiagnosticKind::kSyntax, e, "'-' without names before it",
                variables ? "variables" : "names");
        }
        std::vector<std::string> types = TypeSpec(items[i + 1], check_types);
        for (std::size_t k = pending_from; k < out.size(); ++k) out[k].types = types;
        pending_from = out.size();
        ++i;
        continue;
      }
      if (e.is_list) {
        Error(DiagnosticKind::kSyntax, e, "unexpected list in a typed list",
              variables ? "a variable '?name'" : "a name");
        continue;
      }
      if (variables ? !IsValidVariable(e.atom) : !IsValidName(e.atom)) {
        Error(DiagnosticKind::kSyntax, e, variables ? "invalid variable name" : "invalid name",
              variables ? "'?' followed by a letter, digits, '-' or '_'"
                        : "a letter followed by letters, digits, '-' or '_'");
        continue;
      }
      out.push_back({e.atom, {"object"}, Loc(e)});
    }
    return out;
  }

  std::vector<std::string> TypeSpec(const SExpr& e, bool check) {
    std::vector<std::string> types;
    if (e.is_list) {
      if (e.Head() != "either" || e.items.size() < 2) {
        Error(DiagnosticKind::kSyntax, e, "invalid type", "a type name or (either t1 t2 ...)");
        return {"object"};
      }
      for (std::size_t i = 1; i < e.items.size(); ++i) {
        if (e.items[i].is_list || !IsValidName(e.items[i].atom)) {
          Error(DiagnosticKind::kSyntax, e.items[i], "invalid type name in either", "a type name");
          continue;
        }
        CheckType(e.items[i], check);
        types.push_back(e.items[i].atom);
      }
    } else if (!IsValidName(e.atom)) {
      Error(DiagnosticKind::kSyntax, e, "invalid type name", "a type name");
    } else {
      CheckType(e, check);
      types.push_back(e.atom);
    }
    if (types.empty()) types.push_back("object");
    return types;
  }

  void CheckType(const SExpr& e, bool check) {
    if (check && !types_.Known(e.atom)) {
      Error(DiagnosticKind::kSemantic, e, "undeclared type", "a type declared in :types");
    }
  }

  // ---- scopes --------------------------------------------------------------

  struct Variable {
    std::string name;
    std::vector<std::string> types;
  };

  const Variable* FindVariable(const std::string& name) const {
    for (auto it = scope_.rbegin(); it != scope_.rend(); ++it) {
      if (it->name == name) return &*it;
    }
    return nullptr;
  }

  // A variable in scope the user probably meant: one that differs only by
  // look-alike characters (0/o, 1/l/i), else the only one a single edit away.
  std::string SimilarVariable(const std::string& name) const {
    auto fold = [](char c) { return c == '0' ? 'o' : (c == '1' || c == 'i') ? 'l' : c; };
    std::string unique;
    int candidates = 0;
    for (auto it = scope_.rbegin(); it != scope_.rend(); ++it) {
      const std::string& v = it->name;
      if (v.size() != name.size()) continue;
      int diff = 0;
      bool lookalike = true;
      for (std::size_t i = 0; i < v.size(); ++i) {
        diff += v[i] != name[i];
        lookalike = lookalike && fold(v[i]) == fold(name[i]);
      }
      if (lookalike) return v;
      if (diff == 1) {
        unique = v;
        ++candidates;
      }
    }
    return candidates == 1 ? unique : "";
  }

  // ---- terms and atoms ---------------------------------------------------

  // Resolves a term; returns its types ("" types on failure).
  std::optional<std::vector<std::string>> TermTypes(const SExpr& e) {
    if (e.is_list) {
      Error(DiagnosticKind::kSyntax, e, "unexpected list as an argument",
            "a variable or an object name");
      return std::nullopt;
    }
    if (!e.atom.empty() && e.atom[0] == '?') {
      if (const Variable* v = FindVariable(e.atom)) return v->types;
      std::string similar = SimilarVariable(e.atom);
      Error(DiagnosticKind::kSemantic, e, "undeclared variable",
            similar.empty() ? "a parameter or quantified variable in scope"
                            : "a variable in scope; did you mean '" + similar + "'?");
      return std::nullopt;
    }
    auto it = objects_.find(e.atom);
    if (it != objects_.end()) return it->second.types;
    if (IsNumberToken(e.atom)) {
      Error(DiagnosticKind::kSemantic, e, "number where an object is expected",
            "a variable or an object name");
    } else {
      Error(DiagnosticKind::kSemantic, e, object_scope_message_,
            objects_is_problem_ ? "an object declared in :objects or a domain constant"
                                : "a constant declared in :constants");
    }
    return std::nullopt;
  }

  std::vector<Term> Terms(const SExpr& list, std::size_t begin) {
    std::vector<Term> out;
    for (std::size_t i = begin; i < list.items.size(); ++i) {
      out.push_back(
          {list.items[i].is_list ? std::string() : list.items[i].atom, Loc(list.items[i])});
    }
    return out;
  }

  void CheckArguments(const SExpr& list, const std::string& what_kind, const std::string& name,
                      const Signature& sig) {
    const std::size_t got = list.items.size() - 1;
    if (got != sig.parameter_types.size()) {
      Error(
          DiagnosticKind::kSemantic, list,
          "wrong number of arguments for " + what_kind + " '" + name + "': " + std::to_string(got),
          std::to_string(sig.parameter_types.size()) + " (declared at " + sig.location.ToString() +
              ")",
          name);
    }
    for (std::size_t i = 1; i < list.items.size(); ++i) {
      auto types = TermTypes(list.items[i]);
      if (!types || i - 1 >= sig.parameter_types.size()) continue;
      const auto& want = sig.parameter_types[i - 1];
      TypeFit fit = Fit(types_, *types, want);
      // Built only when reported, so arguments that fit allocate nothing.
      const auto describe_argument = [&] {
        std::string text = "argument ";
        text.append(std::to_string(i)).append(" of ").append(what_kind).append(" '");
        text.append(name).append("' has type ").append(JoinTypes(*types));
        return text;
      };
      if (fit == TypeFit::kNever) {
        Error(DiagnosticKind::kSemantic, list.items[i], "type mismatch: " + describe_argument(),
              "type " + JoinTypes(want));
      } else if (fit == TypeFit::kMaybe && warn_maybe_) {
        std::string message = describe_argument();
        message.append(", wider than the declared ").append(JoinTypes(want));
        message.append("; only objects of the declared type can match");
        Warn(list.items[i], std::move(message));
      }
    }
  }

  // (pred args) or (= a b).
  std::optional<Atom> ParseAtom(const SExpr& e) {
    if (!e.is_list || e.items.empty() || e.items[0].is_list) {
      Error(DiagnosticKind::kSyntax, e, "expected an atom", "(predicate arguments...)");
      return std::nullopt;
    }
    const std::string& name = e.items[0].atom;
    Atom atom{name, Terms(e, 1), Loc(e)};
    if (name == "=") {
      if (e.items.size() != 3) {
        Error(DiagnosticKind::kSyntax, e, "equality needs two arguments", "(= term term)", "=");
      }
      for (std::size_t i = 1; i < e.items.size(); ++i) TermTypes(e.items[i]);
      return atom;
    }
    auto it = predicates_.find(name);
    if (it == predicates_.end()) {
      Error(DiagnosticKind::kSemantic, e.items[0], "undeclared predicate",
            "a predicate declared in :predicates");
      for (std::size_t i = 1; i < e.items.size(); ++i) TermTypes(e.items[i]);
      return std::nullopt;
    }
    CheckArguments(e, "predicate", name, it->second);
    return atom;
  }

  // ---- numeric expressions -------------------------------------------------

  std::optional<NumExpr> ParseNumExpr(const SExpr& e, bool allow_duration, bool allow_total_time) {
    NumExpr out;
    out.location = Loc(e);
    if (!e.is_list) {
      if (IsNumberToken(e.atom)) {
        auto v = Number(e);
        if (!v) return std::nullopt;
        out.kind = NumExpr::Kind::kNumber;
        out.value = *v;
        return out;
      }
      if (e.atom == "?duration") {
        if (!allow_duration) {
          Error(DiagnosticKind::kSemantic, e,
                "?duration outside a durative action's effect or duration", "a number or a fluent");
          return std::nullopt;
        }
        out.kind = NumExpr::Kind::kDuration;
        return out;
      }
      if (e.atom == "total-time") {
        if (!allow_total_time) {
          Error(DiagnosticKind::kSemantic, e, "total-time outside the metric",
                "a number or a fluent");
          return std::nullopt;
        }
        out.kind = NumExpr::Kind::kTotalTime;
        return out;
      }
      if (e.atom == "#t") {
        Unsupported(e, "continuous effect (#t)");
        return std::nullopt;
      }
      if (functions_.count(e.atom) > 0) {  // 0-ary fluent written without parentheses
        out.kind = NumExpr::Kind::kFluent;
        out.function = e.atom;
        CheckFunctionArgs(e, e.atom, 0);
        return out;
      }
      Error(DiagnosticKind::kSemantic, e, "not a numeric expression",
            "a number, ?duration or a declared function");
      return std::nullopt;
    }
    if (e.items.empty() || e.items[0].is_list) {
      Error(DiagnosticKind::kSyntax, e, "expected a numeric expression",
            "a number, (function args) or (op a b)");
      return std::nullopt;
    }
    const std::string& head = e.items[0].atom;
    if (head == "+" || head == "-" || head == "*" || head == "/") {
      const std::size_t n = e.items.size() - 1;
      if (n == 0 || (n == 1 && head != "-") || (n > 2 && (head == "-" || head == "/"))) {
        Error(DiagnosticKind::kSyntax, e, "wrong number of operands for '" + head + "'",
              head == "-" ? "1 or 2" : (head == "/" ? "2" : "2 or more"), head);
        return std::nullopt;
      }
      for (std::size_t i = 1; i < e.items.size(); ++i) {
        auto child = ParseNumExpr(e.items[i], allow_duration, allow_total_time);
        if (!child) return std::nullopt;
        out.children.push_back(std::move(*child));
      }
      out.kind = head == "+"   ? NumExpr::Kind::kAdd
                 : head == "-" ? (n == 1 ? NumExpr::Kind::kNeg : NumExpr::Kind::kSub)
                 : head == "*" ? NumExpr::Kind::kMul
                               : NumExpr::Kind::kDiv;
      return out;
    }
    if (head == "total-time" && e.items.size() == 1) {
      if (!allow_total_time) {
        Error(DiagnosticKind::kSemantic, e, "total-time outside the metric",
              "a number or a fluent");
        return std::nullopt;
      }
      out.kind = NumExpr::Kind::kTotalTime;
      return out;
    }
    if (head == "#t" || ContainsHashT(e)) {
      Unsupported(e, "continuous effect (#t)");
      return std::nullopt;
    }
    if (head == "is-violated") {
      Unsupported(e, "preference metric (is-violated)");
      return std::nullopt;
    }
    if (functions_.count(head) == 0) {
      Error(DiagnosticKind::kSemantic, e.items[0], "undeclared function",
            "a function declared in :functions");
      return std::nullopt;
    }
    out.kind = NumExpr::Kind::kFluent;
    out.function = head;
    out.args = Terms(e, 1);
    CheckArguments(e, "function", head, functions_.at(head));
    return out;
  }

  // Parses the items of `e` after its head with `parse_one` into `children`.
  // Every item is parsed, so one call reports all the bad ones; false if any was.
  template <typename Node, typename ParseOne>
  bool ParseChildren(const SExpr& e, std::vector<Node>& children, ParseOne parse_one) {
    bool ok = true;
    for (std::size_t i = 1; i < e.items.size(); ++i) {
      std::optional<Node> child = parse_one(e.items[i]);
      if (child) {
        children.push_back(std::move(*child));
      } else {
        ok = false;
      }
    }
    return ok;
  }

  static bool ContainsHashT(const SExpr& e) {
    if (!e.is_list) return e.atom == "#t";
    for (const auto& item : e.items) {
      if (ContainsHashT(item)) return true;
    }
    return false;
  }

  void CheckFunctionArgs(const SExpr& e, const std::string& name, std::size_t got) {
    const Signature& sig = functions_.at(name);
    if (sig.parameter_types.size() != got) {
      Error(DiagnosticKind::kSemantic, e, "wrong number of arguments for function '" + name + "'",
            std::to_string(sig.parameter_types.size()));
    }
  }

  std::optional<double> Number(const SExpr& e) {
    if (e.is_list || !IsNumberToken(e.atom)) {
      Error(DiagnosticKind::kSyntax, e, "expected a number", "a number");
      return std::nullopt;
    }
    const char* begin = e.atom.c_str();
    char* end = nullptr;
    double v = std::strtod(begin, &end);
    if (end != begin + e.atom.size()) {
      Error(DiagnosticKind::kSyntax, e, "malformed number", "a decimal number");
      return std::nullopt;
    }
    if (!std::isfinite(v) || std::fabs(v) > 1e300) {
      Error(DiagnosticKind::kSyntax, e, "number out of range", "a finite number");
      return std::nullopt;
    }
    return v;
  }

  static std::optional<Comparator> ComparatorFromHead(std::string_view head) {
    if (head == "<") return Comparator::kLess;
    if (head == "<=") return Comparator::kLessEqual;
    if (head == "=") return Comparator::kEqual;
    if (head == ">=") return Comparator::kGreaterEqual;
    if (head == ">") return Comparator::kGreater;
    return std::nullopt;
  }

  static std::optional<TimeSpec> TimeFromList(const SExpr& e) {
    if (!e.is_list || e.items.size() != 3 || !e.items[2].is_list || e.items[1].is_list)
      return std::nullopt;
    std::string_view head = e.Head();
    if (head == "at" && e.items[1].atom == "start") return TimeSpec::kAtStart;
    if (head == "at" && e.items[1].atom == "end") return TimeSpec::kAtEnd;
    if (head == "over" && e.items[1].atom == "all") return TimeSpec::kOverAll;
    return std::nullopt;
  }

  // ---- conditions ------------------------------------------------------------

  // `durative`: inside a durative action; `timed`: already inside a time specifier.
  std::optional<Condition> ParseCondition(const SExpr& e, bool durative, bool timed) {
    Condition out;
    out.location = Loc(e);
    if (!e.is_list) {
      Error(DiagnosticKind::kSyntax, e, "expected a condition",
            "a list such as (predicate args) or (and ...)");
      return std::nullopt;
    }
    if (e.items.empty()) {
      out.kind = Condition::Kind::kTrue;
      return out;
    }
    if (e.items[0].is_list) {
      Error(DiagnosticKind::kSyntax, e.items[0], "expected a predicate or a connective", "a name");
      return std::nullopt;
    }
    const std::string& head = e.items[0].atom;
    if (auto time = TimeFromList(e)) {
      if (!durative) {
        Error(DiagnosticKind::kSemantic, e, "time specifier outside a durative action",
              "an untimed condition", head + " " + e.items[1].atom);
        return std::nullopt;
      }
      if (timed) {
        Error(DiagnosticKind::kSemantic, e, "nested time specifier", "an untimed condition inside",
              head + " " + e.items[1].atom);
        return std::nullopt;
      }
      auto inner = ParseCondition(e.items[2], durative, true);
      if (!inner) return std::nullopt;
      out.kind = Condition::Kind::kTimed;
      out.time = *time;
      out.children.push_back(std::move(*inner));
      return out;
    }
    if (durative && !timed && head != "and" && head != "forall") {
      Error(DiagnosticKind::kSyntax, e, "durative action condition without a time specifier",
            "(at start ...), (over all ...) or (at end ...)");
      return std::nullopt;
    }
    if (head == "and" || head == "or") {
      out.kind = head == "and" ? Condition::Kind::kAnd : Condition::Kind::kOr;
      if (!ParseChildren(e, out.children, [&](const SExpr& item) {
            return ParseCondition(item, durative, timed);
          })) {
        return std::nullopt;
      }
      return out;
    }
    if (head == "not") {
      if (e.items.size() != 2) {
        Error(DiagnosticKind::kSyntax, e, "'not' takes one condition", "(not condition)", "not");
        return std::nullopt;
      }
      auto child = ParseCondition(e.items[1], durative, timed);
      if (!child) return std::nullopt;
      out.kind = Condition::Kind::kNot;
      out.children.push_back(std::move(*child));
      return out;
    }
    if (head == "imply") {
      if (e.items.size() != 3) {
        Error(DiagnosticKind::kSyntax, e, "'imply' takes two conditions",
              "(imply condition condition)", "imply");
        return std::nullopt;
      }
      auto a = ParseCondition(e.items[1], durative, timed);
      auto b = ParseCondition(e.items[2], durative, timed);
      if (!a || !b) return std::nullopt;
      out.kind = Condition::Kind::kImply;
      out.children.push_back(std::move(*a));
      out.children.push_back(std::move(*b));
      return out;
    }
    if (head == "exists" || head == "forall") {
      if (e.items.size() != 3 || !e.items[1].is_list) {
        Error(DiagnosticKind::kSyntax, e, "malformed quantifier",
              "(" + head + " (?x - type ...) condition)", head);
        return std::nullopt;
      }
      out.kind = head == "exists" ? Condition::Kind::kExists : Condition::Kind::kForall;
      out.variables = TypedList(e.items[1].items, 0, true, true);
      const std::size_t mark = scope_.size();
      for (const auto& v : out.variables) scope_.push_back({v.name, v.types});
      auto body = ParseCondition(e.items[2], durative, timed);
      scope_.resize(mark);
      if (!body) return std::nullopt;
      out.children.push_back(std::move(*body));
      return out;
    }
    if (head == "preference") {
      Unsupported(e, "preference");
      return std::nullopt;
    }
    if (auto cmp = ComparatorFromHead(head)) {
      if (e.items.size() != 3) {
        Error(DiagnosticKind::kSyntax, e, "comparison takes two operands", "(" + head + " a b)",
              head);
        return std::nullopt;
      }
      // (= a b) between two terms is equality of objects.
      if (*cmp == Comparator::kEqual && IsTermLike(e.items[1]) && IsTermLike(e.items[2])) {
        auto atom = ParseAtom(e);
        if (!atom) return std::nullopt;
        out.kind = Condition::Kind::kAtom;
        out.atom = std::move(*atom);
        return out;
      }
      auto lhs = ParseNumExpr(e.items[1], durative, false);
      auto rhs = ParseNumExpr(e.items[2], durative, false);
      if (!lhs || !rhs) return std::nullopt;
      out.kind = Condition::Kind::kCompare;
      out.comparator = *cmp;
      out.lhs = std::move(*lhs);
      out.rhs = std::move(*rhs);
      return out;
    }
    auto atom = ParseAtom(e);
    if (!atom) return std::nullopt;
    out.kind = Condition::Kind::kAtom;
    out.atom = std::move(*atom);
    return out;
  }

  // A symbol that is not a number and not a 0-ary function: an object or variable.
  bool IsTermLike(const SExpr& e) const {
    return !e.is_list && !IsNumberToken(e.atom) && e.atom != "?duration" &&
           functions_.count(e.atom) == 0;
  }

  // ---- effects -----------------------------------------------------------------

  std::optional<Effect> ParseEffect(const SExpr& e, bool durative, bool timed) {
    Effect out;
    out.location = Loc(e);
    if (!e.is_list) {
      Error(DiagnosticKind::kSyntax, e, "expected an effect",
            "(predicate args), (not ...), (and ...)");
      return std::nullopt;
    }
    if (e.items.empty()) {
      out.kind = Effect::Kind::kAnd;
      return out;
    }
    if (e.items[0].is_list) {
      Error(DiagnosticKind::kSyntax, e.items[0], "expected a predicate or an effect keyword",
            "a name");
      return std::nullopt;
    }
    const std::string& head = e.items[0].atom;
    if (auto time = TimeFromList(e)) {
      if (!durative || timed || *time == TimeSpec::kOverAll) {
        Error(DiagnosticKind::kSemantic, e,
              *time == TimeSpec::kOverAll ? "'over all' is not allowed on effects"
                                          : (durative ? "nested time specifier"
                                                      : "time specifier outside a durative action"),
              "(at start effect) or (at end effect) in a durative action",
              head + " " + e.items[1].atom);
        return std::nullopt;
      }
      auto inner = ParseEffect(e.items[2], durative, true);
      if (!inner) return std::nullopt;
      out.kind = Effect::Kind::kTimed;
      out.time = *time;
      out.children.push_back(std::move(*inner));
      return out;
    }
    if (durative && !timed && head != "and" && head != "forall" && head != "when") {
      if (ContainsHashT(e)) {
        Unsupported(e, "continuous effect (#t)");
        return std::nullopt;
      }
      Error(DiagnosticKind::kSyntax, e, "durative action effect without a time specifier",
            "(at start ...) or (at end ...)");
      return std::nullopt;
    }
    if (head == "and") {
      out.kind = Effect::Kind::kAnd;
      if (!ParseChildren(e, out.children,
                         [&](const SExpr& item) { return ParseEffect(item, durative, timed); })) {
        return std::nullopt;
      }
      return out;
    }
    if (head == "not") {
      if (e.items.size() != 2) {
        Error(DiagnosticKind::kSyntax, e, "'not' takes one atom", "(not (predicate args))", "not");
        return std::nullopt;
      }
      auto atom = ParseAtom(e.items[1]);
      if (!atom) return std::nullopt;
      if (atom->predicate == "=") {
        Error(DiagnosticKind::kSemantic, e.items[1], "equality cannot be an effect",
              "(predicate args)", "=");
        return std::nullopt;
      }
      out.kind = Effect::Kind::kDelete;
      out.atom = std::move(*atom);
      return out;
    }
    if (head == "forall") {
      if (e.items.size() != 3 || !e.items[1].is_list) {
        Error(DiagnosticKind::kSyntax, e, "malformed forall", "(forall (?x - type ...) effect)",
              head);
        return std::nullopt;
      }
      out.kind = Effect::Kind::kForall;
      out.variables = TypedList(e.items[1].items, 0, true, true);
      const std::size_t mark = scope_.size();
      for (const auto& v : out.variables) scope_.push_back({v.name, v.types});
      auto body = ParseEffect(e.items[2], durative, timed);
      scope_.resize(mark);
      if (!body) return std::nullopt;
      out.children.push_back(std::move(*body));
      return out;
    }
    if (head == "when") {
      if (e.items.size() != 3) {
        Error(DiagnosticKind::kSyntax, e, "malformed when", "(when condition effect)", head);
        return std::nullopt;
      }
      // In a durative action the condition and effect carry their own times:
      // (when (at start c) (at end e)).
      auto cond = ParseCondition(e.items[1], durative, timed);
      auto body = ParseEffect(e.items[2], durative, timed);
      if (!cond || !body) return std::nullopt;
      out.kind = Effect::Kind::kWhen;
      out.condition = std::move(*cond);
      out.children.push_back(std::move(*body));
      return out;
    }
    static const std::pair<const char*, AssignOp> kOps[] = {{"assign", AssignOp::kAssign},
                                                            {"increase", AssignOp::kIncrease},
                                                            {"decrease", AssignOp::kDecrease},
                                                            {"scale-up", AssignOp::kScaleUp},
                                                            {"scale-down", AssignOp::kScaleDown}};
    for (const auto& [name, op] : kOps) {
      if (head != name) continue;
      if (e.items.size() != 3) {
        Error(DiagnosticKind::kSyntax, e, "malformed numeric effect",
              "(" + head + " (function args) expression)", head);
        return std::nullopt;
      }
      if (ContainsHashT(e.items[2])) {
        Unsupported(e, "continuous effect (#t)");
        return std::nullopt;
      }
      auto fluent = ParseNumExpr(e.items[1], false, false);
      if (!fluent) return std::nullopt;
      if (fluent->kind != NumExpr::Kind::kFluent) {
        Error(DiagnosticKind::kSemantic, e.items[1],
              "the target of a numeric effect must be a fluent", "(function args)");
        return std::nullopt;
      }
      auto value = ParseNumExpr(e.items[2], durative, false);
      if (!value) return std::nullopt;
      out.kind = Effect::Kind::kNumeric;
      out.op = op;
      out.fluent = std::move(*fluent);
      out.value = std::move(*value);
      return out;
    }
    auto atom = ParseAtom(e);
    if (!atom) return std::nullopt;
    if (atom->predicate == "=") {
      Error(DiagnosticKind::kSemantic, e, "equality cannot be an effect", "(predicate args)", "=");
      return std::nullopt;
    }
    out.kind = Effect::Kind::kAdd;
    out.atom = std::move(*atom);
    return out;
  }

  // The file's one top-level form, `(define (<kind> name) ...)`. Reports an
  // empty file, text after the form and a file of the `other` kind (domain
  // vs problem); returns nullptr when there is no usable definition.
  const SExpr* Definition(const std::vector<SExpr>& top, const internal::ReadResult& read,
                          const std::string& kind, const std::string& other) {
    const std::string form = "(define (" + kind + " name) ...)";
    if (top.empty()) {
      diags_.push_back({Severity::kError,
                        DiagnosticKind::kSyntax,
                        {file_, read.eof_line, read.eof_column},
                        "end of file",
                        "empty " + kind,
                        form});
      return nullptr;
    }
    for (std::size_t i = 1; i < top.size(); ++i) {
      Error(DiagnosticKind::kSyntax, top[i], "text after the " + kind + " definition",
            "end of file");
    }
    const SExpr& def = top[0];
    if (def.Head() != "define" || def.items.size() < 2 || def.items[1].Head() != kind ||
        def.items[1].items.size() != 2 || def.items[1].items[1].is_list) {
      if (def.Head() == "define" && def.items.size() >= 2 && def.items[1].Head() == other) {
        Error(DiagnosticKind::kSyntax, def, "this is a " + other + ", not a " + kind, form);
      } else {
        Error(DiagnosticKind::kSyntax, def, "expected a " + kind + " definition", form);
      }
      return nullptr;
    }
    return &def;
  }

  // ---- state -------------------------------------------------------------------

  std::string file_;
  std::vector<Diagnostic>& diags_;
  TypeHierarchy types_;  // rebuilt after each :types section
  std::unordered_map<std::string, Signature> predicates_;
  std::unordered_map<std::string, Signature> functions_;
  struct ObjectInfo {
    std::vector<std::string> types;
    SourceLocation location;
    bool is_constant = false;
  };
  std::unordered_map<std::string, ObjectInfo> objects_;
  bool objects_is_problem_ = false;
  std::string object_scope_message_ = "undeclared constant";
  bool warn_maybe_ = true;
  std::vector<Variable> scope_;
};

Signature MakeSignature(const std::vector<TypedName>& params, const SourceLocation& loc) {
  Signature sig;
  sig.location = loc;
  for (const auto& p : params) sig.parameter_types.push_back(p.types);
  return sig;
}

// Requirements seaplan does not support: using them is reported when found in
// :requirements, since a domain declaring them almost always uses them.
const char* UnsupportedRequirement(std::string_view r) {
  if (r == ":derived-predicates") return "derived predicates (:derived-predicates)";
  if (r == ":preferences") return "preferences (:preferences)";
  if (r == ":constraints") return "state trajectory constraints (:constraints)";
  if (r == ":continuous-effects") return "continuous effects (:continuous-effects)";
  if (r == ":time") return "PDDL+ processes and events (:time)";
  if (r == ":object-fluents") return "object fluents (:object-fluents)";
  return nullptr;
}

bool KnownRequirement(std::string_view r) {
  static const char* kKnown[] = {":strips",
                                 ":typing",
                                 ":negative-preconditions",
                                 ":disjunctive-preconditions",
                                 ":equality",
                                 ":existential-preconditions",
                                 ":universal-preconditions",
                                 ":quantified-preconditions",
                                 ":conditional-effects",
                                 ":adl",
                                 ":numeric-fluents",
                                 ":fluents",
                                 ":durative-actions",
                                 ":duration-inequalities",
                                 ":timed-initial-literals",
                                 ":action-costs"};
  for (const char* k : kKnown) {
    if (r == k) return true;
  }
  return false;
}

class DomainBuilder : public Builder {
 public:
  using Builder::Builder;

  std::optional<Domain> Build(const std::vector<SExpr>& top, const internal::ReadResult& read) {
    const SExpr* definition = Definition(top, read, "domain", "problem");
    if (definition == nullptr) return std::nullopt;
    const SExpr& def = *definition;
    Domain domain;
    domain.name = def.items[1].items[1].atom;
    domain.location = Loc(def);
    // Pass 1: declarations (types, constants, predicates, functions) in any
    // order, so actions can be checked against all of them.
    std::vector<const SExpr*> actions;
    for (std::size_t i = 2; i < def.items.size(); ++i) {
      const SExpr& section = def.items[i];
      std::string_view head = section.Head();
      if (head == ":requirements") {
        for (std::size_t k = 1; k < section.items.size(); ++k) {
          const SExpr& r = section.items[k];
          if (r.is_list) {
            Error(DiagnosticKind::kSyntax, r, "unexpected list in :requirements",
                  "a requirement such as :typing");
            continue;
          }
          if (const char* what = UnsupportedRequirement(r.atom)) {
            Unsupported(r, what);
          } else if (!KnownRequirement(r.atom)) {
            Warn(r, "unknown requirement (ignored)", "a PDDL 2.1 requirement such as :typing");
          }
          domain.requirements.push_back(r.atom);
        }
      } else if (head == ":types") {
        ParseTypes(section, domain);
      } else if (head == ":constants") {
        pending_constants_ = &section;
      } else if (head == ":predicates") {
        ParsePredicates(section, domain);
      } else if (head == ":functions") {
        ParseFunctions(section, domain);
      } else if (head == ":action" || head == ":durative-action") {
        actions.push_back(&section);
      } else if (head == ":derived") {
        Unsupported(section, "derived predicate (:derived)");
      } else if (head == ":constraints") {
        Unsupported(section, "state trajectory constraints (:constraints)");
      } else if (head == ":process" || head == ":event") {
        Unsupported(section, std::string("PDDL+ ") + std::string(head.substr(1)) + " (" +
                                 std::string(head) + ")");
      } else {
        Error(DiagnosticKind::kSyntax, section, "unknown domain section",
              ":requirements, :types, :constants, :predicates, :functions, :action or "
              ":durative-action");
      }
    }
    if (std::string cycle = types_.FindCycle(); !cycle.empty()) {
      diags_.push_back({Severity::kError, DiagnosticKind::kSemantic, domain.location, cycle,
                        "type hierarchy has a cycle", "a tree of types below object"});
    }
    // Constants after types, whatever the section order.
    if (pending_constants_ != nullptr) {
      domain.constants = TypedList(pending_constants_->items, 1, false, true);
      for (const auto& c : domain.constants) AddObject(c, true, *pending_constants_);
    }
    std::unordered_map<std::string, SourceLocation> action_names;
    for (const SExpr* a : actions) {
      if (a->items.size() > 1 && a->items[1].IsAtom()) {
        auto [it, fresh] = action_names.emplace(a->items[1].atom, Loc(*a));
        if (!fresh) {
          Error(DiagnosticKind::kSemantic, a->items[1], "action declared twice",
                "a unique action name (first at " + it->second.ToString() + ")");
        }
      }
      if (auto action = ParseAction(*a)) domain.actions.push_back(std::move(*action));
    }
    return domain;
  }

  void AddObject(const TypedName& object, bool constant, const SExpr& at) {
    auto [it, inserted] =
        objects_.try_emplace(object.name, ObjectInfo{object.types, object.location, constant});
    if (inserted) return;
    SExpr where = at;
    where.is_list = false;
    where.atom = object.name;
    where.line = object.location.line;
    where.column = object.location.column;
    if (it->second.types == object.types) {
      Warn(where,
           std::string(it->second.is_constant ? "repeats the domain constant" : "declared twice") +
               " (first at " + it->second.location.ToString() + ")");
    } else {
      Error(DiagnosticKind::kSemantic, where,
            "declared again with a different type " + JoinTypes(object.types) + " (first as " +
                JoinTypes(it->second.types) + " at " + it->second.location.ToString() + ")",
            "each object declared once, with one type");
    }
  }

  void ParseTypes(const SExpr& section, Domain& domain) {
    auto list = TypedList(section.items, 1, false, false);
    std::unordered_set<std::string> seen;
    for (auto& t : list) {
      if (t.name == "object") continue;
      if (!seen.insert(t.name).second) {
        // `a - b` then `a - c` again: merge parents.
        for (auto& existing : domain.types) {
          if (existing.name == t.name) {
            for (const auto& p : t.types) existing.parents.push_back(p);
          }
        }
      } else {
        domain.types.push_back({t.name, t.types, t.location});
      }
    }
    // Parents used without their own declaration are implicitly declared (as
    // subtypes of object), as most planners accept.
    for (const auto& t : list) {
      for (const auto& p : t.types) {
        if (!types_.Known(p) && seen.insert(p).second) {
          domain.types.push_back({p, {"object"}, t.location});
        }
      }
    }
    types_ = TypeHierarchy(domain.types);
  }

  void ParsePredicates(const SExpr& section, Domain& domain) {
    for (std::size_t i = 1; i < section.items.size(); ++i) {
      const SExpr& p = section.items[i];
      if (!p.is_list || p.items.empty() || p.items[0].is_list || !IsValidName(p.items[0].atom)) {
        Error(DiagnosticKind::kSyntax, p, "malformed predicate declaration",
              "(name ?x - type ...)");
        continue;
      }
      PredicateDecl decl{p.items[0].atom, TypedList(p.items, 1, true, true), Loc(p)};
      if (predicates_.count(decl.name) > 0) {
        Error(DiagnosticKind::kSemantic, p.items[0], "predicate declared twice",
              "a unique predicate name (first at " + predicates_[decl.name].location.ToString() +
                  ")");
        continue;
      }
      predicates_[decl.name] = MakeSignature(decl.parameters, decl.location);
      domain.predicates.push_back(std::move(decl));
    }
  }

  void ParseFunctions(const SExpr& section, Domain& domain) {
    std::size_t first_pending = domain.functions.size();
    for (std::size_t i = 1; i < section.items.size(); ++i) {
      const SExpr& f = section.items[i];
      if (f.IsAtom("-")) {
        if (i + 1 >= section.items.size() || section.items[i + 1].is_list) {
          Error(DiagnosticKind::kSyntax, f, "'-' without a result type", "number");
          break;
        }
        const SExpr& type = section.items[i + 1];
        if (type.atom != "number") {
          if (type.atom == "object" || types_.Known(type.atom)) {
            Unsupported(type, "object fluent (function of type " + type.atom + ")");
          } else {
            Error(DiagnosticKind::kSemantic, type, "unknown function type", "number");
          }
        }
        for (std::size_t k = first_pending; k < domain.functions.size(); ++k)
          domain.functions[k].result_type = type.atom;
        first_pending = domain.functions.size();
        ++i;
        continue;
      }
      if (!f.is_list || f.items.empty() || f.items[0].is_list || !IsValidName(f.items[0].atom)) {
        Error(DiagnosticKind::kSyntax, f, "malformed function declaration", "(name ?x - type ...)");
        continue;
      }
      FunctionDecl decl{f.items[0].atom, TypedList(f.items, 1, true, true), "number", Loc(f)};
      if (functions_.count(decl.name) > 0 || predicates_.count(decl.name) > 0) {
        Error(DiagnosticKind::kSemantic, f.items[0], "function name declared twice",
              "a unique name");
        continue;
      }
      functions_[decl.name] = MakeSignature(decl.parameters, decl.location);
      domain.functions.push_back(std::move(decl));
    }
  }

  std::optional<Action> ParseAction(const SExpr& a) {
    const bool durative = a.Head() == ":durative-action";
    if (a.items.size() < 2 || a.items[1].is_list || !IsValidName(a.items[1].atom)) {
      Error(DiagnosticKind::kSyntax, a, "action without a valid name",
            "(" + std::string(a.Head()) + " name ...)");
      return std::nullopt;
    }
    Action action;
    action.name = a.items[1].atom;
    action.durative = durative;
    action.location = Loc(a);
    action.effect.kind = Effect::Kind::kAnd;
    bool ok = true;
    bool has_effect = false;
    scope_.clear();
    std::size_t i = 2;
    // Keyword/value pairs in any order.
    const SExpr* parameters = nullptr;
    const SExpr* duration = nullptr;
    const SExpr* condition = nullptr;
    const SExpr* effect = nullptr;
    for (; i < a.items.size(); ++i) {
      const SExpr& key = a.items[i];
      if (key.is_list || key.atom.empty() || key.atom[0] != ':') {
        Error(DiagnosticKind::kSyntax, key, "expected an action keyword",
              durative ? ":parameters, :duration, :condition or :effect"
                       : ":parameters, :precondition or :effect");
        ok = false;
        continue;
      }
      if (i + 1 >= a.items.size()) {
        Error(DiagnosticKind::kSyntax, key, "keyword without a value", "a value after " + key.atom);
        ok = false;
        break;
      }
      const SExpr* value = &a.items[++i];
      if (key.atom == ":parameters") {
        parameters = value;
      } else if (key.atom == ":duration" && durative) {
        duration = value;
      } else if ((key.atom == ":condition" && durative) ||
                 (key.atom == ":precondition" && !durative)) {
        condition = value;
      } else if (key.atom == ":effect") {
        effect = value;
      } else {
        Error(DiagnosticKind::kSyntax, key, "unexpected keyword in " + std::string(a.Head()),
              durative ? ":parameters, :duration, :condition or :effect"
                       : ":parameters, :precondition or :effect");
        ok = false;
      }
    }
    if (parameters != nullptr) {
      if (!parameters->is_list) {
        Error(DiagnosticKind::kSyntax, *parameters, "parameters must be a list", "(?x - type ...)");
        ok = false;
      } else {
        action.parameters = TypedList(parameters->items, 0, true, true);
        for (std::size_t k = 0; k < action.parameters.size(); ++k) {
          for (std::size_t m = 0; m < k; ++m) {
            if (action.parameters[m].name == action.parameters[k].name) {
              diags_.push_back({Severity::kError, DiagnosticKind::kSemantic,
                                action.parameters[k].location, action.parameters[k].name,
                                "parameter declared twice", "unique parameter names"});
              ok = false;
            }
          }
        }
      }
    }
    for (const auto& p : action.parameters) scope_.push_back({p.name, p.types});
    if (durative) {
      if (duration == nullptr) {
        Warn(a, "durative action without :duration; any duration is allowed",
             ":duration (= ?duration ...)");
      } else if (!ParseDuration(*duration, action.duration)) {
        ok = false;
      }
    }
    if (condition != nullptr) {
      auto c = ParseCondition(*condition, durative, false);
      if (c) {
        action.condition = std::move(*c);
      } else {
        ok = false;
      }
    }
    if (effect != nullptr) {
      has_effect = true;
      auto e = ParseEffect(*effect, durative, false);
      if (e) {
        action.effect = std::move(*e);
      } else {
        ok = false;
      }
    }
    if (!has_effect) {
      Warn(a.items[1], std::string(durative ? "durative action" : "action") + " has no :effect",
           ":effect");
    }
    scope_.clear();
    if (!ok) return std::nullopt;
    return action;
  }

  bool ParseDuration(const SExpr& e, std::vector<DurationConstraint>& out) {
    if (!e.is_list) {
      Error(DiagnosticKind::kSyntax, e, "malformed duration", "(= ?duration expression)");
      return false;
    }
    if (e.items.empty()) return true;  // () = unconstrained
    if (e.Head() == "and") {
      bool ok = true;
      for (std::size_t i = 1; i < e.items.size(); ++i) ok = ParseDuration(e.items[i], out) && ok;
      return ok;
    }
    if (TimeFromList(e)) {
      Unsupported(e, "timed duration constraint (at start/at end on ?duration)");
      return false;
    }
    auto cmp = ComparatorFromHead(e.Head());
    if (!cmp || e.items.size() != 3 || !e.items[1].IsAtom("?duration")) {
      Error(DiagnosticKind::kSyntax, e, "malformed duration constraint",
            "(= ?duration expression), (<= ?duration e), (>= ?duration e) or (and ...)");
      return false;
    }
    auto value = ParseNumExpr(e.items[2], false, false);
    if (!value) return false;
    out.push_back({*cmp, std::move(*value), Loc(e)});
    return true;
  }

 private:
  const SExpr* pending_constants_ = nullptr;
};

class ProblemBuilder : public Builder {
 public:
  ProblemBuilder(std::string file, std::vector<Diagnostic>& diagnostics, const Domain& domain)
      : Builder(std::move(file), diagnostics), domain_(domain) {
    types_ = TypeHierarchy(domain.types);
    for (const auto& p : domain.predicates)
      predicates_[p.name] = MakeSignature(p.parameters, p.location);
    for (const auto& f : domain.functions)
      functions_[f.name] = MakeSignature(f.parameters, f.location);
    for (const auto& c : domain.constants) objects_[c.name] = {c.types, c.location, true};
    objects_is_problem_ = true;
    object_scope_message_ = "undeclared object";
  }

  std::optional<Problem> Build(const std::vector<SExpr>& top, const internal::ReadResult& read) {
    const SExpr* definition = Definition(top, read, "problem", "domain");
    if (definition == nullptr) return std::nullopt;
    const SExpr& def = *definition;
    Problem problem;
    problem.name = def.items[1].items[1].atom;
    problem.location = Loc(def);
    const SExpr* objects = nullptr;
    const SExpr* init = nullptr;
    const SExpr* goal = nullptr;
    const SExpr* metric = nullptr;
    for (std::size_t i = 2; i < def.items.size(); ++i) {
      const SExpr& section = def.items[i];
      std::string_view head = section.Head();
      if (head == ":domain") {
        if (section.items.size() != 2 || section.items[1].is_list) {
          Error(DiagnosticKind::kSyntax, section, "malformed :domain", "(:domain name)");
          continue;
        }
        problem.domain_name = section.items[1].atom;
        if (problem.domain_name != domain_.name) {
          Warn(section.items[1], "problem names domain '" + problem.domain_name +
                                     "' but the domain is '" + domain_.name + "'");
        }
      } else if (head == ":requirements") {
        for (std::size_t k = 1; k < section.items.size(); ++k) {
          if (!section.items[k].is_list) {
            if (const char* what = UnsupportedRequirement(section.items[k].atom))
              Unsupported(section.items[k], what);
          }
        }
      } else if (head == ":objects") {
        objects = &section;
      } else if (head == ":init") {
        init = &section;
      } else if (head == ":goal") {
        goal = &section;
      } else if (head == ":metric") {
        metric = &section;
      } else if (head == ":constraints") {
        Unsupported(section, "state trajectory constraints (:constraints)");
      } else if (head == ":length") {
        Warn(section, "(:length ...) is ignored");
      } else {
        Error(DiagnosticKind::kSyntax, section, "unknown problem section",
              ":domain, :requirements, :objects, :init, :goal or :metric");
      }
    }
    if (objects != nullptr) {
      auto list = TypedList(objects->items, 1, false, true);
      for (auto& o : list) {
        auto it = objects_.find(o.name);
        if (it == objects_.end()) {
          objects_[o.name] = {o.types, o.location, false};
          problem.objects.push_back(std::move(o));
          continue;
        }
        SExpr where;
        where.atom = o.name;
        where.line = o.location.line;
        where.column = o.location.column;
        if (it->second.types == o.types) {
          Warn(where, std::string(it->second.is_constant ? "object repeats the domain constant"
                                                         : "object declared twice") +
                          " (first at " + it->second.location.ToString() + ")");
        } else {
          Error(DiagnosticKind::kSemantic, where,
                "object declared again with a different type " + JoinTypes(o.types) +
                    " (first as " + JoinTypes(it->second.types) + " at " +
                    it->second.location.ToString() + ")",
                "each object declared once, with one type");
        }
      }
    }
    if (init != nullptr) ParseInit(*init, problem);
    if (goal == nullptr) {
      Error(DiagnosticKind::kSyntax, def, "problem without :goal", "(:goal condition)",
            problem.name);
    } else if (goal->items.size() != 2) {
      Error(DiagnosticKind::kSyntax, *goal, "malformed :goal", "(:goal condition)");
    } else if (auto g = ParseCondition(goal->items[1], false, false)) {
      problem.goal = std::move(*g);
    }
    if (metric != nullptr) {
      if (metric->items.size() != 3 || metric->items[1].is_list ||
          (metric->items[1].atom != "minimize" && metric->items[1].atom != "maximize")) {
        Error(DiagnosticKind::kSyntax, *metric, "malformed :metric",
              "(:metric minimize|maximize expression)");
      } else if (auto m = ParseNumExpr(metric->items[2], false, true)) {
        problem.metric.present = true;
        problem.metric.minimize = metric->items[1].atom == "minimize";
        problem.metric.expression = std::move(*m);
        problem.metric.location = Loc(*metric);
      }
    }
    return problem;
  }

  void ParseInit(const SExpr& section, Problem& problem) {
    warn_maybe_ = false;
    for (std::size_t i = 1; i < section.items.size(); ++i) {
      const SExpr& e = section.items[i];
      if (!e.is_list || e.items.empty() || e.items[0].is_list) {
        Error(DiagnosticKind::kSyntax, e, "malformed initial element",
              "(predicate objects), (= (f objects) number) or (at time literal)");
        continue;
      }
      const std::string& head = e.items[0].atom;
      if (head == "at" && e.items.size() == 3 && !e.items[1].is_list &&
          IsNumberToken(e.items[1].atom) && e.items[2].is_list) {
        auto time = Number(e.items[1]);
        if (!time) continue;
        if (*time < 0) {
          Error(DiagnosticKind::kSemantic, e.items[1], "timed initial literal at a negative time",
                "a time >= 0");
          continue;
        }
        const SExpr& lit = e.items[2];
        if (lit.Head() == "=") {
          if (auto n = NumericInitOf(lit))
            problem.timed_numeric_init.push_back({*time, std::move(*n)});
          continue;
        }
        bool positive = true;
        const SExpr* atom_e = &lit;
        if (lit.Head() == "not" && lit.items.size() == 2) {
          positive = false;
          atom_e = &lit.items[1];
        }
        if (auto atom = GroundAtom(*atom_e)) {
          problem.timed_literals.push_back({*time, std::move(*atom), positive, Loc(e)});
        }
        continue;
      }
      if (head == "=") {
        if (auto n = NumericInitOf(e)) problem.numeric_init.push_back(std::move(*n));
        continue;
      }
      if (head == "not") {
        Warn(e, "negative literal in :init is redundant (closed world) and ignored");
        continue;
      }
      if (auto atom = GroundAtom(e)) problem.init.push_back(std::move(*atom));
    }
    warn_maybe_ = true;
  }

  std::optional<Atom> GroundAtom(const SExpr& e) {
    if (!e.is_list || e.items.empty() || e.items[0].is_list) {
      Error(DiagnosticKind::kSyntax, e, "expected a ground atom", "(predicate objects)");
      return std::nullopt;
    }
    for (std::size_t i = 1; i < e.items.size(); ++i) {
      if (!e.items[i].is_list && !e.items[i].atom.empty() && e.items[i].atom[0] == '?') {
        Error(DiagnosticKind::kSemantic, e.items[i], "variable in a ground atom", "an object name");
        return std::nullopt;
      }
    }
    auto atom = ParseAtom(e);
    if (atom && atom->predicate == "=") {
      Error(DiagnosticKind::kSemantic, e, "equality in :init",
            "(predicate objects) or (= (function objects) number)", "=");
      return std::nullopt;
    }
    return atom;
  }

  std::optional<NumericInit> NumericInitOf(const SExpr& e) {
    if (e.items.size() != 3) {
      Error(DiagnosticKind::kSyntax, e, "malformed numeric initialisation",
            "(= (function objects) number)", "=");
      return std::nullopt;
    }
    const SExpr& head = e.items[1];
    NumericInit out;
    out.location = Loc(e);
    if (!head.is_list) {
      if (functions_.count(head.atom) == 0) {
        Error(DiagnosticKind::kSemantic, head, "undeclared function",
              "a function declared in :functions");
        return std::nullopt;
      }
      out.function = head.atom;
    } else {
      if (head.items.empty() || head.items[0].is_list) {
        Error(DiagnosticKind::kSyntax, head, "malformed function term", "(function objects)");
        return std::nullopt;
      }
      out.function = head.items[0].atom;
      auto it = functions_.find(out.function);
      if (it == functions_.end()) {
        if (predicates_.count(out.function) > 0) {
          Error(DiagnosticKind::kSemantic, head.items[0], "a predicate used as a function",
                "a function declared in :functions");
        } else {
          Error(DiagnosticKind::kSemantic, head.items[0], "undeclared function",
                "a function declared in :functions");
        }
        return std::nullopt;
      }
      for (std::size_t i = 1; i < head.items.size(); ++i) {
        if (!head.items[i].is_list && !head.items[i].atom.empty() && head.items[i].atom[0] == '?') {
          Error(DiagnosticKind::kSemantic, head.items[i], "variable in :init", "an object name");
          return std::nullopt;
        }
        out.args.push_back(head.items[i].atom);
      }
      CheckArguments(head, "function", out.function, it->second);
    }
    // The value: a number, possibly written (- 5).
    const SExpr& v = e.items[2];
    if (v.is_list && v.Head() == "-" && v.items.size() == 2) {
      auto n = Number(v.items[1]);
      if (!n) return std::nullopt;
      out.value = -*n;
    } else {
      auto n = Number(v);
      if (!n) return std::nullopt;
      out.value = *n;
    }
    return out;
  }

 private:
  const Domain& domain_;
};

// Reading order, so a user fixes them top to bottom.
void SortByPosition(std::vector<Diagnostic>& diagnostics) {
  std::stable_sort(diagnostics.begin(), diagnostics.end(),
                   [](const Diagnostic& a, const Diagnostic& b) {
                     return std::tie(a.location.line, a.location.column) <
                            std::tie(b.location.line, b.location.column);
                   });
}

}  // namespace

const PredicateDecl* Domain::FindPredicate(std::string_view wanted) const {
  for (const auto& p : predicates) {
    if (p.name == wanted) return &p;
  }
  return nullptr;
}

const FunctionDecl* Domain::FindFunction(std::string_view wanted) const {
  for (const auto& f : functions) {
    if (f.name == wanted) return &f;
  }
  return nullptr;
}

const Action* Domain::FindAction(std::string_view wanted) const {
  for (const auto& a : actions) {
    if (a.name == wanted) return &a;
  }
  return nullptr;
}

bool Domain::IsSubtype(std::string_view type, std::string_view ancestor) const {
  return TypeHierarchy(types).IsSubtype(type, ancestor);
}

DomainParseResult ParseDomain(std::string_view text, std::string_view file_name) {
  DomainParseResult result;
  std::string file(file_name);
  auto read = internal::ReadSExprs(text, file, result.diagnostics);
  if (!read.ok) return result;
  DomainBuilder builder(file, result.diagnostics);
  auto domain = builder.Build(read.top_level, read);
  if (domain && !HasErrors(result.diagnostics)) result.domain = std::move(domain);
  SortByPosition(result.diagnostics);
  return result;
}

ProblemParseResult ParseProblem(std::string_view text, const Domain& domain,
                                std::string_view file_name) {
  ProblemParseResult result;
  std::string file(file_name);
  auto read = internal::ReadSExprs(text, file, result.diagnostics);
  if (!read.ok) return result;
  ProblemBuilder builder(file, result.diagnostics, domain);
  auto problem = builder.Build(read.top_level, read);
  if (problem && !HasErrors(result.diagnostics)) result.problem = std::move(problem);
  SortByPosition(result.diagnostics);
  return result;
}

const char* ComparatorSymbol(Comparator comparator) {
  switch (comparator) {
    case Comparator::kLess:
      return "<";
    case Comparator::kLessEqual:
      return "<=";
    case Comparator::kEqual:
      return "=";
    case Comparator::kGreaterEqual:
      return ">=";
    case Comparator::kGreater:
      return ">";
  }
  return "?";
}

const char* TimeSpecName(TimeSpec time) {
  switch (time) {
    case TimeSpec::kNone:
      return "";
    case TimeSpec::kAtStart:
      return "at start";
    case TimeSpec::kOverAll:
      return "over all";
    case TimeSpec::kAtEnd:
      return "at end";
  }
  return "";
}

}  // namespace seaplan::pddl
