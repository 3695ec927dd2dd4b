// The grounder: relaxed-reachability-driven instantiation of a PDDL domain
// and problem into a GroundTask (see grounder.h for the contract).
//
// Pipeline:
//   1. intern objects, types, predicates and functions to ints; find static
//      predicates (no effect and no timed literal touches them) and static
//      functions (no numeric effect, no timed fluent);
//   2. compile each action schema's condition into NNF, then into schema-level
//      DNF "specs" (conjunctions of literals, equalities, comparisons and
//      opaque forall items; exists variables become extra spec variables);
//   3. relaxed exploration (Datalog-style, as Fast Downward's translator): a
//      queue of reached atoms; popping an atom triggers every spec with a
//      positive atom of that predicate, which is joined with the other
//      positive atoms reached so far (most selective first: bound positions
//      are looked up in per-argument indexes). Static atoms are reached from
//      the start, so static preconditions act as filters. Negative fluent
//      literals and numeric conditions over changing fluents are optimistic;
//      static ones are evaluated. Every add effect of a reached instance
//      (conditional ones included) is reached;
//   4. instantiation: each reached instance's condition and effects are
//      grounded, simplified against the static facts and the reachable set,
//      foralls expanded, and turned into ground DNF variants.
#include "seaplan/task/grounder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "seaplan/pddl/type_hierarchy.h"
#include "tuple_set_internal.h"

namespace seaplan::task {
namespace {

using internal::TupleSet;
using pddl::TimeSpec;
using Obj = std::int32_t;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Cap on DNF sizes (schema level and ground level): beyond it the input is
// reported as unsupported rather than exploding.
constexpr std::size_t kMaxDisjuncts = 256;

// An argument: >= 0 is an object, < 0 is variable slot (-1 - arg).
inline bool IsVar(std::int32_t arg) {
  return arg < 0;
}
inline int Slot(std::int32_t arg) {
  return -1 - arg;
}
inline std::int32_t VarArg(int slot) {
  return -1 - slot;
}

struct NExpr {
  enum class K { kNum, kFluent, kDuration, kTotalTime, kAdd, kSub, kMul, kDiv, kNeg };
  K k = K::kNum;
  double value = 0.0;
  int func = -1;
  std::vector<std::int32_t> args;
  std::vector<NExpr> kids;
};

struct F {
  enum class K { kTrue, kFalse, kAtom, kEq, kCmp, kAnd, kOr, kForall, kExists };
  K k = K::kTrue;
  bool positive = true;  // kAtom, kEq
  int pred = -1;
  std::vector<std::int32_t> args;
  TimeSpec time = TimeSpec::kNone;
  pddl::Comparator cmp = pddl::Comparator::kEqual;
  NExpr lhs, rhs;
  std::vector<F> kids;
  std::vector<int> vars;  // quantified slots
};

struct EffItem {
  enum class K { kAdd, kDel, kNum };
  K k = K::kAdd;
  TimeSpec time = TimeSpec::kNone;
  std::vector<int> forall_vars;
  F cond;  // kTrue when unconditional
  int pred = -1;
  std::vector<std::int32_t> args;
  pddl::AssignOp op = pddl::AssignOp::kAssign;
  int func = -1;
  std::vector<std::int32_t> fargs;
  NExpr value;
  pddl::SourceLocation location;
};

struct VarInfo {
  std::string name;
  std::vector<Obj> objects;           // objects of the variable's type(s)
  std::vector<std::uint8_t> allowed;  // per object
};

struct DurItem {
  pddl::Comparator cmp = pddl::Comparator::kEqual;
  NExpr value;
};

struct Spec {
  int schema = -1;
  std::vector<const F*> items;  // conjunction
  std::vector<int> atoms;       // indexes of positive kAtom items (join atoms)
  std::vector<int> free_vars;   // slots to bind (params + top-level exists vars)
  bool has_fluent_atom = false;
};

struct Schema {
  const pddl::Action* action = nullptr;
  int n_params = 0;
  std::vector<VarInfo> vars;
  F cond;
  std::vector<EffItem> effects;
  std::vector<DurItem> duration;
  std::vector<int> specs;
};

// A ground formula after simplification.
struct GF {
  enum class K { kTrue, kFalse, kLit, kCmp, kAnd, kOr };
  K k = K::kTrue;
  FactId fact = -1;
  bool positive = true;
  TimeSpec time = TimeSpec::kNone;
  NumericCondition cmp;
  std::vector<GF> kids;
};

struct GroundLits {
  std::vector<const GF*> leaves;
};

Comparator ToTask(pddl::Comparator c) {
  switch (c) {
    case pddl::Comparator::kLess:
      return Comparator::kLess;
    case pddl::Comparator::kLessEqual:
      return Comparator::kLessEqual;
    case pddl::Comparator::kEqual:
      return Comparator::kEqual;
    case pddl::Comparator::kGreaterEqual:
      return Comparator::kGreaterEqual;
    case pddl::Comparator::kGreater:
      return Comparator::kGreater;
  }
  return Comparator::kEqual;
}

AssignOp ToTask(pddl::AssignOp op) {
  switch (op) {
    case pddl::AssignOp::kAssign:
      return AssignOp::kAssign;
    case pddl::AssignOp::kIncrease:
      return AssignOp::kIncrease;
    case pddl::AssignOp::kDecrease:
      return AssignOp::kDecrease;
    case pddl::AssignOp::kScaleUp:
      return AssignOp::kScaleUp;
    case pddl::AssignOp::kScaleDown:
      return AssignOp::kScaleDown;
  }
  return AssignOp::kAssign;
}

double Millis(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
      .count();
}

class Grounder {
 public:
  Grounder(const pddl::Domain& domain, const pddl::Problem& problem,
           const GroundingOptions& options, std::vector<pddl::Diagnostic>& diagnostics)
      : domain_(domain), problem_(problem), options_(options), diags_(diagnostics) {}

  // Steps 1-3. False when grounding cannot go on (diagnostics say why).
  bool Explore() {
    InternSymbols();
    if (!CheckProblemMatchesDomain()) return false;
    FindStatics();
    if (!LoadInit()) return false;
    for (const auto& action : domain_.actions) {
      if (!BuildSchema(action)) return false;
    }
    return RunExploration();
  }

  std::shared_ptr<GroundTask> Build();

  std::string Explain(std::string_view name, std::span<const std::string> args,
                      const GroundTask* task);

  std::size_t reachable_atoms() const { return atoms_.size(); }
  std::size_t static_atoms() const { return static_true_; }

 private:
  // ---- diagnostics -----------------------------------------------------------
  void Error(pddl::DiagnosticKind kind, const pddl::SourceLocation& at, std::string symbol,
             std::string message, std::string expected = "") {
    diags_.push_back({pddl::Severity::kError, kind, at, std::move(symbol), std::move(message),
                      std::move(expected)});
  }
  void Warn(const pddl::SourceLocation& at, std::string symbol, std::string message) {
    diags_.push_back({pddl::Severity::kWarning, pddl::DiagnosticKind::kSemantic, at,
                      std::move(symbol), std::move(message), ""});
  }

  // Counts one elementary step; false once the work budget is spent.
  bool Tick() {
    if (++work_ <= options_.max_work) return true;
    if (!budget_exceeded_) {
      Error(pddl::DiagnosticKind::kSemantic, problem_.location, "",
            "grounding exceeds the work budget of " + std::to_string(options_.max_work) + " steps",
            "a smaller problem or a larger GroundingOptions::max_work");
    }
    budget_exceeded_ = true;
    return false;
  }

  // ---- step 1: symbols ---------------------------------------------------------
  int TypeId(const std::string& name) const { return types_.Id(name); }

  void InternSymbols() {
    types_ = pddl::TypeHierarchy(domain_.types);
    auto add_object = [&](const pddl::TypedName& o) {
      auto [it, inserted] = object_index_.emplace(o.name, static_cast<Obj>(object_names_.size()));
      if (inserted) {
        object_names_.push_back(o.name);
        object_types_.push_back(o.types);
      }
    };
    for (const auto& c : domain_.constants) add_object(c);
    for (const auto& o : problem_.objects) add_object(o);
    // Each object's membership from its declared types and the hierarchy's
    // ancestors: linear in objects.
    const auto n_types = static_cast<std::size_t>(types_.size());
    objects_of_type_.assign(n_types, {});
    type_member_.assign(n_types, std::vector<std::uint8_t>(object_names_.size(), 0));
    for (std::size_t o = 0; o < object_names_.size(); ++o) {
      for (const auto& declared : object_types_[o]) {
        const int d = TypeId(declared);
        if (d < 0) continue;
        for (std::size_t t = 0; t < n_types; ++t) {
          if (types_.IsSubtype(d, static_cast<int>(t)) && !type_member_[t][o]) {
            type_member_[t][o] = 1;
            objects_of_type_[t].push_back(static_cast<Obj>(o));
          }
        }
      }
    }
    for (const auto& p : domain_.predicates) {
      pred_index_[p.name] = static_cast<int>(pred_names_.size());
      pred_names_.push_back(p.name);
      pred_arity_.push_back(static_cast<int>(p.parameters.size()));
    }
    pred_static_.assign(pred_names_.size(), true);
    for (const auto& f : domain_.functions) {
      func_index_[f.name] = static_cast<int>(func_names_.size());
      func_names_.push_back(f.name);
    }
    func_static_.assign(func_names_.size(), true);
    by_pred_.assign(pred_names_.size(), {});
    by_arg_.assign(pred_names_.size(), {});
  }

  // Ground() accepts ASTs built or edited by code (e.g. a replanning loop
  // updating :init), not only parser output: check what the grounder indexes
  // by, so a mismatch is a diagnostic rather than an out-of-range access.
  bool CheckProblemMatchesDomain() {
    bool ok = true;
    auto check_atom = [&](const pddl::Atom& atom) {
      auto it = pred_index_.find(atom.predicate);
      if (it == pred_index_.end() ||
          pred_arity_[static_cast<std::size_t>(it->second)] != static_cast<int>(atom.args.size())) {
        Error(pddl::DiagnosticKind::kSemantic, atom.location, atom.predicate,
              "initial atom does not match a predicate of the domain",
              "a declared predicate with its arity");
        ok = false;
        return;
      }
      for (const auto& t : atom.args) {
        if (ObjectId(t.name) < 0) {
          Error(pddl::DiagnosticKind::kSemantic, t.location, t.name, "unknown object",
                "a declared object");
          ok = false;
        }
      }
    };
    auto check_numeric = [&](const pddl::NumericInit& n) {
      auto it = func_index_.find(n.function);
      if (it == func_index_.end() ||
          domain_.functions[static_cast<std::size_t>(it->second)].parameters.size() !=
              n.args.size()) {
        Error(pddl::DiagnosticKind::kSemantic, n.location, n.function,
              "numeric initialisation does not match a function of the domain",
              "a declared function");
        ok = false;
        return;
      }
      for (const auto& a : n.args) {
        if (ObjectId(a) < 0) {
          Error(pddl::DiagnosticKind::kSemantic, n.location, a, "unknown object",
                "a declared object");
          ok = false;
        }
      }
    };
    for (const auto& atom : problem_.init) check_atom(atom);
    for (const auto& til : problem_.timed_literals) check_atom(til.atom);
    // Goal and metric: names must exist (variables are bound by quantifiers).
    std::vector<const pddl::NumExpr*> exprs;
    std::vector<const pddl::Condition*> todo{&problem_.goal};
    if (problem_.metric.present) exprs.push_back(&problem_.metric.expression);
    while (!todo.empty()) {
      const pddl::Condition* c = todo.back();
      todo.pop_back();
      if (c->kind == pddl::Condition::Kind::kAtom) {
        if (c->atom.predicate != "=" && pred_index_.count(c->atom.predicate) == 0) {
          Error(pddl::DiagnosticKind::kSemantic, c->atom.location, c->atom.predicate,
                "goal uses an unknown predicate", "a declared predicate");
          ok = false;
        }
        for (const auto& t : c->atom.args) {
          if (!t.IsVariable() && ObjectId(t.name) < 0) {
            Error(pddl::DiagnosticKind::kSemantic, t.location, t.name, "unknown object",
                  "a declared object");
            ok = false;
          }
        }
      } else if (c->kind == pddl::Condition::Kind::kCompare) {
        exprs.push_back(&c->lhs);
        exprs.push_back(&c->rhs);
      }
      for (const auto& kid : c->children) todo.push_back(&kid);
    }
    while (!exprs.empty()) {
      const pddl::NumExpr* e = exprs.back();
      exprs.pop_back();
      if (e->kind == pddl::NumExpr::Kind::kFluent && func_index_.count(e->function) == 0) {
        Error(pddl::DiagnosticKind::kSemantic, e->location, e->function, "unknown function",
              "a declared function");
        ok = false;
      }
      for (const auto& kid : e->children) exprs.push_back(&kid);
    }
    for (const auto& n : problem_.numeric_init) check_numeric(n);
    for (const auto& n : problem_.timed_numeric_init) check_numeric(n.init);
    return ok;
  }

  Obj ObjectId(const std::string& name) const {
    auto it = object_index_.find(name);
    return it == object_index_.end() ? -1 : it->second;
  }

  void MarkEffects(const pddl::Effect& e) {
    switch (e.kind) {
      case pddl::Effect::Kind::kAdd:
      case pddl::Effect::Kind::kDelete: {
        auto it = pred_index_.find(e.atom.predicate);
        if (it != pred_index_.end()) pred_static_[static_cast<std::size_t>(it->second)] = false;
        break;
      }
      case pddl::Effect::Kind::kNumeric: {
        auto it = func_index_.find(e.fluent.function);
        if (it != func_index_.end()) func_static_[static_cast<std::size_t>(it->second)] = false;
        break;
      }
      default:
        break;
    }
    for (const auto& kid : e.children) MarkEffects(kid);
  }

  void FindStatics() {
    for (const auto& a : domain_.actions) MarkEffects(a.effect);
    for (const auto& til : problem_.timed_literals) {
      auto it = pred_index_.find(til.atom.predicate);
      if (it != pred_index_.end()) pred_static_[static_cast<std::size_t>(it->second)] = false;
    }
    for (const auto& tif : problem_.timed_numeric_init) {
      auto it = func_index_.find(tif.init.function);
      if (it != func_index_.end()) func_static_[static_cast<std::size_t>(it->second)] = false;
    }
  }

  // ---- atoms and the reached set ------------------------------------------------

  std::int32_t InternAtom(int pred, std::span<const Obj> args, bool* inserted = nullptr) {
    key_.clear();
    key_.push_back(pred);
    key_.insert(key_.end(), args.begin(), args.end());
    auto [id, fresh] = atoms_.Insert(key_);
    if (fresh) {
      atom_popped_.push_back(0);
      atom_queued_.push_back(0);
    }
    if (inserted != nullptr) *inserted = fresh;
    return id;
  }

  std::int32_t FindAtom(int pred, std::span<const Obj> args) {
    key_.clear();
    key_.push_back(pred);
    key_.insert(key_.end(), args.begin(), args.end());
    return atoms_.Find(key_);
  }

  // Makes an atom reachable (queued for the fixpoint).
  bool Reach(int pred, std::span<const Obj> args) {
    std::int32_t id = InternAtom(pred, args);
    if (atom_queued_[static_cast<std::size_t>(id)]) return true;
    if (atoms_.size() > options_.max_facts) {
      if (!budget_exceeded_) {
        Error(
            pddl::DiagnosticKind::kSemantic, problem_.location, "",
            "grounding exceeds the fact budget of " + std::to_string(options_.max_facts) + " atoms",
            "a smaller problem or a larger GroundingOptions::max_facts");
      }
      budget_exceeded_ = true;
      return false;
    }
    atom_queued_[static_cast<std::size_t>(id)] = 1;
    queue_.push_back(id);
    return true;
  }

  // Adds a queued atom to the indexes the joins read.
  void Pop(std::int32_t id) {
    atom_popped_[static_cast<std::size_t>(id)] = 1;
    auto key = atoms_.Get(id);
    const auto pred = static_cast<std::size_t>(key[0]);
    by_pred_[pred].push_back(id);
    auto& index = by_arg_[pred];
    if (index.empty() && key.size() > 1) {
      // The per-argument index costs (arity x objects) cells per predicate;
      // bounded by the fact budget so that many predicates over many objects
      // end in a diagnostic instead of exhausting memory.
      index_cells_ += (key.size() - 1) * object_names_.size();
      if (index_cells_ > 4 * options_.max_facts + (1u << 20)) {
        if (!budget_exceeded_) {
          Error(pddl::DiagnosticKind::kSemantic, problem_.location, "",
                "grounding index exceeds the fact budget (" + std::to_string(index_cells_) +
                    " cells)",
                "fewer predicates or objects, or a larger GroundingOptions::max_facts");
        }
        budget_exceeded_ = true;
        return;
      }
      index.assign(key.size() - 1, std::vector<std::vector<std::int32_t>>(object_names_.size()));
    }
    for (std::size_t i = 1; i < key.size(); ++i)
      index[i - 1][static_cast<std::size_t>(key[i])].push_back(id);
  }

  bool LoadInit() {
    std::vector<Obj> args;
    for (const auto& atom : problem_.init) {
      int pred = pred_index_.at(atom.predicate);
      args.clear();
      for (const auto& t : atom.args) args.push_back(ObjectId(t.name));
      if (pred_static_[static_cast<std::size_t>(pred)]) {
        bool fresh = false;
        std::int32_t id = InternAtom(pred, args, &fresh);
        if (fresh) {
          atom_queued_[static_cast<std::size_t>(id)] = 1;
          Pop(id);
          if (budget_exceeded_) return false;
          ++static_true_;
        }
      } else {
        init_atoms_.push_back(InternAtom(pred, args));
        if (!Reach(pred, args)) return false;
      }
    }
    for (const auto& til : problem_.timed_literals) {
      int pred = pred_index_.at(til.atom.predicate);
      args.clear();
      for (const auto& t : til.atom.args) args.push_back(ObjectId(t.name));
      til_atoms_.push_back(InternAtom(pred, args));
      if (til.positive && !Reach(pred, args)) return false;
    }
    for (const auto& n : problem_.numeric_init) SetInitValue(n);
    return true;
  }

  void SetInitValue(const pddl::NumericInit& n) {
    key_.clear();
    key_.push_back(func_index_.at(n.function));
    for (const auto& a : n.args) key_.push_back(ObjectId(a));
    auto [id, fresh] = fterms_.Insert(key_);
    if (fresh) {
      fterm_value_.push_back(n.value);
      fterm_var_.push_back(-1);
    } else {
      fterm_value_[static_cast<std::size_t>(id)] = n.value;
    }
  }

  // ---- step 2: schemas ----------------------------------------------------------

  int AddVar(Schema& s, const pddl::TypedName& v) {
    VarInfo info;
    info.name = v.name;
    info.allowed.assign(object_names_.size(), 0);
    for (const auto& t : v.types) {
      int type = TypeId(t);
      if (type < 0) continue;
      for (Obj o : objects_of_type_[static_cast<std::size_t>(type)]) {
        if (!info.allowed[static_cast<std::size_t>(o)]) {
          info.allowed[static_cast<std::size_t>(o)] = 1;
          info.objects.push_back(o);
        }
      }
    }
    std::sort(info.objects.begin(), info.objects.end());
    s.vars.push_back(std::move(info));
    const int slot = static_cast<int>(s.vars.size()) - 1;
    scope_.push_back({v.name, slot});
    return slot;
  }

  std::int32_t ArgOf(const pddl::Term& t) const {
    if (t.IsVariable()) {
      for (auto it = scope_.rbegin(); it != scope_.rend(); ++it) {
        if (it->first == t.name) return VarArg(it->second);
      }
      return VarArg(0);  // unreachable for checked input
    }
    return ObjectId(t.name);
  }

  NExpr ConvertExpr(const pddl::NumExpr& e) {
    NExpr out;
    switch (e.kind) {
      case pddl::NumExpr::Kind::kNumber:
        out.k = NExpr::K::kNum;
        out.value = e.value;
        return out;
      case pddl::NumExpr::Kind::kDuration:
        out.k = NExpr::K::kDuration;
        return out;
      case pddl::NumExpr::Kind::kTotalTime:
        out.k = NExpr::K::kTotalTime;
        return out;
      case pddl::NumExpr::Kind::kFluent:
        out.k = NExpr::K::kFluent;
        out.func = func_index_.at(e.function);
        for (const auto& a : e.args) out.args.push_back(ArgOf(a));
        return out;
      case pddl::NumExpr::Kind::kNeg:
        out.k = NExpr::K::kNeg;
        out.kids.push_back(ConvertExpr(e.children[0]));
        return out;
      case pddl::NumExpr::Kind::kAdd:
      case pddl::NumExpr::Kind::kSub:
      case pddl::NumExpr::Kind::kMul:
      case pddl::NumExpr::Kind::kDiv: {
        const NExpr::K k = e.kind == pddl::NumExpr::Kind::kAdd   ? NExpr::K::kAdd
                           : e.kind == pddl::NumExpr::Kind::kSub ? NExpr::K::kSub
                           : e.kind == pddl::NumExpr::Kind::kMul ? NExpr::K::kMul
                                                                 : NExpr::K::kDiv;
        // n-ary + and * become a balanced tree (depth log n, so recursion
        // stays shallow on inputs with thousands of operands).
        std::vector<NExpr> level;
        for (const auto& child : e.children) level.push_back(ConvertExpr(child));
        while (level.size() > 1) {
          std::vector<NExpr> next;
          for (std::size_t i = 0; i + 1 < level.size(); i += 2) {
            NExpr parent;
            parent.k = k;
            parent.kids.push_back(std::move(level[i]));
            parent.kids.push_back(std::move(level[i + 1]));
            next.push_back(std::move(parent));
          }
          if (level.size() % 2 == 1) next.push_back(std::move(level.back()));
          level = std::move(next);
        }
        out = std::move(level[0]);
        return out;
      }
    }
    return out;
  }

  static pddl::Comparator Negate(pddl::Comparator c) {
    switch (c) {
      case pddl::Comparator::kLess:
        return pddl::Comparator::kGreaterEqual;
      case pddl::Comparator::kLessEqual:
        return pddl::Comparator::kGreater;
      case pddl::Comparator::kGreaterEqual:
        return pddl::Comparator::kLess;
      case pddl::Comparator::kGreater:
        return pddl::Comparator::kLessEqual;
      case pddl::Comparator::kEqual:
        return pddl::Comparator::kEqual;  // handled by the caller
    }
    return c;
  }

  // pddl::Condition -> F in negation normal form; `time` is the enclosing time specifier.
  F ConvertCondition(Schema& s, const pddl::Condition& c, bool negated, TimeSpec time) {
    F out;
    out.time = time;
    using CK = pddl::Condition::Kind;
    switch (c.kind) {
      case CK::kTrue:
        out.k = negated ? F::K::kFalse : F::K::kTrue;
        return out;
      case CK::kAtom:
        if (c.atom.predicate == "=") {
          out.k = F::K::kEq;
        } else {
          out.k = F::K::kAtom;
          out.pred = pred_index_.at(c.atom.predicate);
        }
        out.positive = !negated;
        for (const auto& a : c.atom.args) out.args.push_back(ArgOf(a));
        return out;
      case CK::kNot:
        return ConvertCondition(s, c.children[0], !negated, time);
      case CK::kAnd:
      case CK::kOr:
        out.k = ((c.kind == CK::kAnd) != negated) ? F::K::kAnd : F::K::kOr;
        for (const auto& kid : c.children)
          out.kids.push_back(ConvertCondition(s, kid, negated, time));
        return out;
      case CK::kImply:
        // a -> b  ==  (not a) or b;  not (a -> b)  ==  a and (not b)
        out.k = negated ? F::K::kAnd : F::K::kOr;
        out.kids.push_back(ConvertCondition(s, c.children[0], !negated, time));
        out.kids.push_back(ConvertCondition(s, c.children[1], negated, time));
        return out;
      case CK::kExists:
      case CK::kForall: {
        out.k = ((c.kind == CK::kExists) != negated) ? F::K::kExists : F::K::kForall;
        const std::size_t mark = scope_.size();
        for (const auto& v : c.variables) out.vars.push_back(AddVar(s, v));
        out.kids.push_back(ConvertCondition(s, c.children[0], negated, time));
        scope_.resize(mark);
        return out;
      }
      case CK::kCompare: {
        NExpr lhs = ConvertExpr(c.lhs);
        NExpr rhs = ConvertExpr(c.rhs);
        if (negated && c.comparator == pddl::Comparator::kEqual) {
          out.k = F::K::kOr;
          F less;
          less.k = F::K::kCmp;
          less.time = time;
          less.cmp = pddl::Comparator::kLess;
          less.lhs = lhs;
          less.rhs = rhs;
          F greater = less;
          greater.cmp = pddl::Comparator::kGreater;
          out.kids.push_back(std::move(less));
          out.kids.push_back(std::move(greater));
          return out;
        }
        out.k = F::K::kCmp;
        out.cmp = negated ? Negate(c.comparator) : c.comparator;
        out.lhs = std::move(lhs);
        out.rhs = std::move(rhs);
        return out;
      }
      case CK::kTimed:
        return ConvertCondition(s, c.children[0], negated, c.time);
    }
    return out;
  }

  void FlattenEffect(Schema& s, const pddl::Effect& e, TimeSpec time, std::vector<int>& forall_vars,
                     std::vector<const pddl::Condition*>& conds,
                     std::vector<TimeSpec>& cond_times) {
    using EK = pddl::Effect::Kind;
    switch (e.kind) {
      case EK::kAnd:
        for (const auto& kid : e.children)
          FlattenEffect(s, kid, time, forall_vars, conds, cond_times);
        return;
      case EK::kTimed:
        FlattenEffect(s, e.children[0], e.time, forall_vars, conds, cond_times);
        return;
      case EK::kForall: {
        const std::size_t mark = scope_.size();
        const std::size_t vmark = forall_vars.size();
        for (const auto& v : e.variables) forall_vars.push_back(AddVar(s, v));
        FlattenEffect(s, e.children[0], time, forall_vars, conds, cond_times);
        forall_vars.resize(vmark);
        scope_.resize(mark);
        return;
      }
      case EK::kWhen:
        conds.push_back(&e.condition);
        cond_times.push_back(time);
        FlattenEffect(s, e.children[0], time, forall_vars, conds, cond_times);
        conds.pop_back();
        cond_times.pop_back();
        return;
      case EK::kAdd:
      case EK::kDelete:
      case EK::kNumeric: {
        EffItem item;
        item.time = time;
        item.forall_vars = forall_vars;
        item.location = e.location;
        if (!conds.empty()) {
          item.cond.k = F::K::kAnd;
          for (std::size_t i = 0; i < conds.size(); ++i) {
            item.cond.kids.push_back(ConvertCondition(s, *conds[i], false, cond_times[i]));
          }
        }
        if (e.kind == EK::kNumeric) {
          item.k = EffItem::K::kNum;
          item.op = e.op;
          item.func = func_index_.at(e.fluent.function);
          for (const auto& a : e.fluent.args) item.fargs.push_back(ArgOf(a));
          item.value = ConvertExpr(e.value);
        } else {
          item.k = e.kind == EK::kAdd ? EffItem::K::kAdd : EffItem::K::kDel;
          item.pred = pred_index_.at(e.atom.predicate);
          for (const auto& a : e.atom.args) item.args.push_back(ArgOf(a));
        }
        s.effects.push_back(std::move(item));
        return;
      }
    }
  }

  // Schema-level DNF: each disjunct a list of items; exists variables are
  // recorded as extra variables to bind.
  struct Disjunct {
    std::vector<const F*> items;
    std::vector<int> exists_vars;
  };

  bool Dnf(const F& f, std::vector<Disjunct>& out) {
    switch (f.k) {
      case F::K::kTrue:
        out.push_back({});
        return true;
      case F::K::kFalse:
        return true;
      case F::K::kAtom:
      case F::K::kEq:
      case F::K::kCmp:
      case F::K::kForall:
        out.push_back({{&f}, {}});
        return true;
      case F::K::kExists: {
        std::vector<Disjunct> body;
        if (!Dnf(f.kids[0], body)) return false;
        for (auto& d : body)
          d.exists_vars.insert(d.exists_vars.end(), f.vars.begin(), f.vars.end());
        out.insert(out.end(), body.begin(), body.end());
        return true;
      }
      case F::K::kOr:
        for (const auto& kid : f.kids) {
          if (!Dnf(kid, out)) return false;
          if (out.size() > kMaxDisjuncts) return false;
        }
        return true;
      case F::K::kAnd: {
        std::vector<Disjunct> acc(1);
        for (const auto& kid : f.kids) {
          std::vector<Disjunct> part;
          if (!Dnf(kid, part)) return false;
          std::vector<Disjunct> next;
          for (const auto& a : acc) {
            for (const auto& b : part) {
              Disjunct d = a;
              d.items.insert(d.items.end(), b.items.begin(), b.items.end());
              d.exists_vars.insert(d.exists_vars.end(), b.exists_vars.begin(), b.exists_vars.end());
              next.push_back(std::move(d));
            }
          }
          if (next.size() > kMaxDisjuncts) return false;
          acc = std::move(next);
        }
        out.insert(out.end(), acc.begin(), acc.end());
        return true;
      }
    }
    return true;
  }

  bool BuildSchema(const pddl::Action& action) {
    auto schema = std::make_unique<Schema>();
    Schema& s = *schema;
    s.action = &action;
    scope_.clear();
    for (const auto& p : action.parameters) AddVar(s, p);
    s.n_params = static_cast<int>(action.parameters.size());
    s.cond = ConvertCondition(s, action.condition, false, TimeSpec::kNone);
    std::vector<int> forall_vars;
    std::vector<const pddl::Condition*> conds;
    std::vector<TimeSpec> cond_times;
    FlattenEffect(s, action.effect, TimeSpec::kNone, forall_vars, conds, cond_times);
    for (const auto& d : action.duration)
      s.duration.push_back({d.comparator, ConvertExpr(d.value)});
    scope_.clear();

    std::vector<Disjunct> disjuncts;
    if (!Dnf(s.cond, disjuncts)) {
      Error(pddl::DiagnosticKind::kUnsupported, action.location, action.name,
            "the precondition's disjunctive normal form has more than " +
                std::to_string(kMaxDisjuncts) + " disjuncts");
      return false;
    }
    const int schema_id = static_cast<int>(schemas_.size());
    for (auto& d : disjuncts) {
      Spec spec;
      spec.schema = schema_id;
      spec.items = std::move(d.items);
      for (int v = 0; v < s.n_params; ++v) spec.free_vars.push_back(v);
      for (int v : d.exists_vars) spec.free_vars.push_back(v);
      for (std::size_t i = 0; i < spec.items.size(); ++i) {
        const F& item = *spec.items[i];
        if (item.k == F::K::kAtom && item.positive) {
          spec.atoms.push_back(static_cast<int>(i));
          if (!pred_static_[static_cast<std::size_t>(item.pred)]) spec.has_fluent_atom = true;
        }
      }
      s.specs.push_back(static_cast<int>(specs_.size()));
      specs_.push_back(std::move(spec));
    }
    schemas_.push_back(std::move(schema));
    return true;
  }

  // ---- numeric evaluation over static fluents --------------------------------------

  // Value of a ground function term from :init (NaN when undefined).
  double InitValue(int func, std::span<const Obj> args) {
    key_.clear();
    key_.push_back(func);
    key_.insert(key_.end(), args.begin(), args.end());
    std::int32_t id = fterms_.Find(key_);
    return id < 0 ? kNaN : fterm_value_[static_cast<std::size_t>(id)];
  }

  // True when the expression reads only numbers and static fluents.
  bool IsStaticExpr(const NExpr& e) const {
    if (e.k == NExpr::K::kFluent) return func_static_[static_cast<std::size_t>(e.func)];
    if (e.k == NExpr::K::kDuration || e.k == NExpr::K::kTotalTime) return false;
    for (const auto& kid : e.kids) {
      if (!IsStaticExpr(kid)) return false;
    }
    return true;
  }

  double EvalStatic(const NExpr& e, const std::vector<Obj>& binding) {
    switch (e.k) {
      case NExpr::K::kNum:
        return e.value;
      case NExpr::K::kFluent: {
        fargs_scratch_.clear();
        for (auto a : e.args)
          fargs_scratch_.push_back(IsVar(a) ? binding[static_cast<std::size_t>(Slot(a))] : a);
        std::vector<Obj> args = fargs_scratch_;
        return InitValue(e.func, args);
      }
      case NExpr::K::kDuration:
      case NExpr::K::kTotalTime:
        return kNaN;
      case NExpr::K::kNeg:
        return -EvalStatic(e.kids[0], binding);
      case NExpr::K::kAdd:
        return EvalStatic(e.kids[0], binding) + EvalStatic(e.kids[1], binding);
      case NExpr::K::kSub:
        return EvalStatic(e.kids[0], binding) - EvalStatic(e.kids[1], binding);
      case NExpr::K::kMul:
        return EvalStatic(e.kids[0], binding) * EvalStatic(e.kids[1], binding);
      case NExpr::K::kDiv: {
        const double d = EvalStatic(e.kids[1], binding);
        return d == 0.0 ? kNaN : EvalStatic(e.kids[0], binding) / d;
      }
    }
    return kNaN;
  }

  // ---- step 3: exploration -----------------------------------------------------------

  // Checks the filters of a complete binding (equalities, static literals,
  // static numeric conditions, a static duration that must be defined).
  bool PassesFilters(const Spec& spec, const std::vector<Obj>& b) {
    for (const F* item : spec.items) {
      switch (item->k) {
        case F::K::kEq: {
          Obj x = IsVar(item->args[0]) ? b[static_cast<std::size_t>(Slot(item->args[0]))]
                                       : item->args[0];
          Obj y = IsVar(item->args[1]) ? b[static_cast<std::size_t>(Slot(item->args[1]))]
                                       : item->args[1];
          if ((x == y) != item->positive) return false;
          break;
        }
        case F::K::kAtom:
          if (!item->positive && pred_static_[static_cast<std::size_t>(item->pred)]) {
            args_scratch_.clear();
            for (auto a : item->args)
              args_scratch_.push_back(IsVar(a) ? b[static_cast<std::size_t>(Slot(a))] : a);
            std::vector<Obj> args = args_scratch_;
            std::int32_t id = FindAtom(item->pred, args);
            if (id >= 0 && atom_popped_[static_cast<std::size_t>(id)]) return false;
          }
          break;
        case F::K::kCmp:
          if (IsStaticExpr(item->lhs) && IsStaticExpr(item->rhs)) {
            const double l = EvalStatic(item->lhs, b);
            const double r = EvalStatic(item->rhs, b);
            if (std::isnan(l) || std::isnan(r) || !Compare(l, ToTask(item->cmp), r)) return false;
          }
          break;
        default:
          break;
      }
    }
    const Schema& s = *schemas_[static_cast<std::size_t>(spec.schema)];
    for (const auto& d : s.duration) {
      if (IsStaticExpr(d.value) && std::isnan(EvalStatic(d.value, b))) return false;
    }
    return true;
  }

  // Binds `item`'s arguments against atom `id`; false on a clash or a type
  // mismatch. `bound` records which slots this call bound (for undoing).
  bool Unify(const Schema& s, const F& item, std::int32_t id, std::vector<Obj>& b,
             std::vector<int>& bound) {
    auto key = atoms_.Get(id);
    for (std::size_t i = 0; i < item.args.size(); ++i) {
      const Obj value = key[i + 1];
      const std::int32_t a = item.args[i];
      if (!IsVar(a)) {
        if (a != value) return false;
        continue;
      }
      const auto slot = static_cast<std::size_t>(Slot(a));
      if (b[slot] >= 0) {
        if (b[slot] != value) return false;
        continue;
      }
      if (!s.vars[slot].allowed[static_cast<std::size_t>(value)]) return false;
      b[slot] = value;
      bound.push_back(static_cast<int>(slot));
    }
    return true;
  }

  void Unbind(std::vector<Obj>& b, std::vector<int>& bound, std::size_t mark) {
    while (bound.size() > mark) {
      b[static_cast<std::size_t>(bound.back())] = -1;
      bound.pop_back();
    }
  }

  // Joins the remaining atoms of `spec` (bit i of `done` set = atom i handled).
  bool Join(const Spec& spec, std::vector<Obj>& b, std::vector<int>& bound,
            std::vector<std::uint8_t>& done, std::size_t remaining) {
    const Schema& s = *schemas_[static_cast<std::size_t>(spec.schema)];
    if (remaining == 0) return EnumerateFree(spec, b, 0);
    // Pick the most selective remaining atom.
    int best = -1;
    std::size_t best_count = std::numeric_limits<std::size_t>::max();
    const std::vector<std::int32_t>* best_list = nullptr;
    for (std::size_t i = 0; i < spec.atoms.size(); ++i) {
      if (done[i]) continue;
      const F& item = *spec.items[static_cast<std::size_t>(spec.atoms[i])];
      const auto pred = static_cast<std::size_t>(item.pred);
      const std::vector<std::int32_t>* list = &by_pred_[pred];
      bool all_bound = true;
      for (std::size_t k = 0; k < item.args.size(); ++k) {
        const std::int32_t a = item.args[k];
        const Obj value = IsVar(a) ? b[static_cast<std::size_t>(Slot(a))] : a;
        if (value < 0) {
          all_bound = false;
          continue;
        }
        if (by_arg_[pred].empty()) {
          list = &by_pred_[pred];  // nothing reached for this predicate
          break;
        }
        const auto& candidates = by_arg_[pred][k][static_cast<std::size_t>(value)];
        if (candidates.size() < list->size()) list = &candidates;
      }
      const std::size_t count = all_bound ? 1 : list->size();
      if (count < best_count) {
        best_count = count;
        best = static_cast<int>(i);
        best_list = all_bound ? nullptr : list;
      }
    }
    const F& item =
        *spec.items[static_cast<std::size_t>(spec.atoms[static_cast<std::size_t>(best)])];
    done[static_cast<std::size_t>(best)] = 1;
    bool ok = true;
    if (best_list == nullptr) {
      std::vector<Obj> args;
      for (auto a : item.args) args.push_back(IsVar(a) ? b[static_cast<std::size_t>(Slot(a))] : a);
      std::int32_t id = FindAtom(item.pred, args);
      if (id >= 0 && atom_popped_[static_cast<std::size_t>(id)])
        ok = Join(spec, b, bound, done, remaining - 1);
    } else {
      // The list may grow while we iterate (Pop during effects is deferred,
      // so it does not); iterate by index for safety.
      for (std::size_t j = 0; j < best_list->size() && ok; ++j) {
        if (!Tick()) {
          ok = false;
          break;
        }
        const std::size_t mark = bound.size();
        if (Unify(s, item, (*best_list)[j], b, bound))
          ok = Join(spec, b, bound, done, remaining - 1);
        Unbind(b, bound, mark);
      }
    }
    done[static_cast<std::size_t>(best)] = 0;
    return ok;
  }

  bool EnumerateFree(const Spec& spec, std::vector<Obj>& b, std::size_t i) {
    while (i < spec.free_vars.size() && b[static_cast<std::size_t>(spec.free_vars[i])] >= 0) ++i;
    if (i == spec.free_vars.size()) return Emit(spec, b);
    const Schema& s = *schemas_[static_cast<std::size_t>(spec.schema)];
    const auto slot = static_cast<std::size_t>(spec.free_vars[i]);
    for (Obj o : s.vars[slot].objects) {
      b[slot] = o;
      if (!Tick() || !EnumerateFree(spec, b, i + 1)) {
        b[slot] = -1;
        return false;
      }
    }
    b[slot] = -1;
    return true;
  }

  // A complete binding: filter, record, and reach its add effects.
  bool Emit(const Spec& spec, std::vector<Obj>& b) {
    if (!PassesFilters(spec, b)) return true;
    const auto spec_id = static_cast<std::int32_t>(&spec - specs_.data());
    key_.clear();
    key_.push_back(spec_id);
    key_.insert(key_.end(), b.begin(), b.end());
    auto [id, fresh] = instances_.Insert(key_);
    (void)id;
    if (!fresh) return true;
    if (instances_.size() > options_.max_actions) {
      Error(pddl::DiagnosticKind::kSemantic, problem_.location, "",
            "grounding exceeds the action budget of " + std::to_string(options_.max_actions) +
                " actions",
            "a smaller problem or a larger GroundingOptions::max_actions");
      budget_exceeded_ = true;
      return false;
    }
    const Schema& s = *schemas_[static_cast<std::size_t>(spec.schema)];
    std::vector<Obj> eb = b;
    for (const auto& eff : s.effects) {
      if (eff.k != EffItem::K::kAdd) continue;
      if (!ReachEffect(s, eff, eb, 0)) return false;
    }
    return true;
  }

  bool ReachEffect(const Schema& s, const EffItem& eff, std::vector<Obj>& b, std::size_t i) {
    if (i == eff.forall_vars.size()) {
      std::vector<Obj> args;
      args.reserve(eff.args.size());
      for (auto a : eff.args) args.push_back(IsVar(a) ? b[static_cast<std::size_t>(Slot(a))] : a);
      for (Obj o : args) {
        if (o < 0) return true;  // unbound (exists variable used in an effect): ignore
      }
      return Reach(eff.pred, args);
    }
    const auto slot = static_cast<std::size_t>(eff.forall_vars[i]);
    for (Obj o : s.vars[slot].objects) {
      b[slot] = o;
      if (!Tick() || !ReachEffect(s, eff, b, i + 1)) return false;
    }
    b[slot] = -1;
    return true;
  }

  bool RunExploration() {
    // Specs without fluent atoms fire once, against the static atoms.
    std::vector<std::vector<std::pair<int, int>>> triggers(
        pred_names_.size());  // pred -> (spec, atom index)
    for (std::size_t si = 0; si < specs_.size(); ++si) {
      const Spec& spec = specs_[si];
      const Schema& s = *schemas_[static_cast<std::size_t>(spec.schema)];
      if (!spec.has_fluent_atom) {
        std::vector<Obj> b(s.vars.size(), -1);
        std::vector<int> bound;
        std::vector<std::uint8_t> done(spec.atoms.size(), 0);
        if (!Join(spec, b, bound, done, spec.atoms.size())) return false;
        continue;
      }
      for (std::size_t i = 0; i < spec.atoms.size(); ++i) {
        const F& item = *spec.items[static_cast<std::size_t>(spec.atoms[i])];
        if (!pred_static_[static_cast<std::size_t>(item.pred)]) {
          triggers[static_cast<std::size_t>(item.pred)].push_back(
              {static_cast<int>(si), static_cast<int>(i)});
        }
      }
    }
    std::vector<Obj> b;
    std::vector<int> bound;
    std::vector<std::uint8_t> done;
    for (std::size_t head = 0; head < queue_.size(); ++head) {
      const std::int32_t id = queue_[head];
      Pop(id);
      if (budget_exceeded_) return false;
      const auto pred = static_cast<std::size_t>(atoms_.Get(id)[0]);
      for (const auto& [si, ai] : triggers[pred]) {
        const Spec& spec = specs_[static_cast<std::size_t>(si)];
        const Schema& s = *schemas_[static_cast<std::size_t>(spec.schema)];
        b.assign(s.vars.size(), -1);
        bound.clear();
        const F& item =
            *spec.items[static_cast<std::size_t>(spec.atoms[static_cast<std::size_t>(ai)])];
        if (!Unify(s, item, id, b, bound)) continue;
        done.assign(spec.atoms.size(), 0);
        done[static_cast<std::size_t>(ai)] = 1;
        if (!Join(spec, b, bound, done, spec.atoms.size() - 1)) return false;
      }
    }
    return !budget_exceeded_;
  }

  // ---- step 4: instantiation ------------------------------------------------------------

  FactId FactOf(std::int32_t atom) const { return atom_fact_[static_cast<std::size_t>(atom)]; }

  // A fact for an atom that no action can reach (goals, timed deletes).
  FactId ForceFact(int pred, std::span<const Obj> args) {
    std::int32_t id = InternAtom(pred, args);
    if (static_cast<std::size_t>(id) >= atom_fact_.size()) atom_fact_.resize(atoms_.size(), -1);
    FactId& fact = atom_fact_[static_cast<std::size_t>(id)];
    if (fact < 0) {
      fact = static_cast<FactId>(task_->facts.size());
      Fact f;
      f.predicate = pred_names_[static_cast<std::size_t>(pred)];
      for (Obj o : args) f.args.push_back(object_names_[static_cast<std::size_t>(o)]);
      task_->facts.push_back(std::move(f));
    }
    return fact;
  }

  NumericVarId VarOf(int func, std::span<const Obj> args) {
    key_.clear();
    key_.push_back(func);
    key_.insert(key_.end(), args.begin(), args.end());
    auto [id, fresh] = fterms_.Insert(key_);
    if (fresh) {
      fterm_value_.push_back(kNaN);
      fterm_var_.push_back(-1);
    }
    NumericVarId& var = fterm_var_[static_cast<std::size_t>(id)];
    if (var < 0) {
      var = static_cast<NumericVarId>(task_->numeric_vars.size());
      NumericVar v;
      v.function = func_names_[static_cast<std::size_t>(func)];
      for (Obj o : args) v.args.push_back(object_names_[static_cast<std::size_t>(o)]);
      task_->numeric_vars.push_back(std::move(v));
      task_->initial_values.push_back(fterm_value_[static_cast<std::size_t>(id)]);
    }
    return var;
  }

  // Emits `e` into `out` (children first), folding constants; false when a
  // static fluent it reads is undefined or a constant division is by zero.
  bool EmitExpr(const NExpr& e, const std::vector<Obj>& b, NumericExpr& out) {
    using Op = NumericExpr::Op;
    NumericExpr::Node node;
    switch (e.k) {
      case NExpr::K::kNum:
        node.op = Op::kConstant;
        node.value = e.value;
        break;
      case NExpr::K::kDuration:
        node.op = Op::kDuration;
        break;
      case NExpr::K::kTotalTime:
        node.op = Op::kTotalTime;
        break;
      case NExpr::K::kFluent: {
        std::vector<Obj> args;
        for (auto a : e.args) args.push_back(IsVar(a) ? b[static_cast<std::size_t>(Slot(a))] : a);
        if (func_static_[static_cast<std::size_t>(e.func)]) {
          const double v = InitValue(e.func, args);
          if (std::isnan(v)) return false;
          node.op = Op::kConstant;
          node.value = v;
        } else {
          node.op = Op::kVariable;
          node.var = VarOf(e.func, args);
        }
        break;
      }
      case NExpr::K::kNeg: {
        if (!EmitExpr(e.kids[0], b, out)) return false;
        auto& last = out.nodes.back();
        if (last.op == Op::kConstant) {
          last.value = -last.value;
          return true;
        }
        node.op = Op::kNeg;
        node.lhs = static_cast<std::int32_t>(out.nodes.size()) - 1;
        break;
      }
      default: {
        if (!EmitExpr(e.kids[0], b, out)) return false;
        const auto lhs = static_cast<std::int32_t>(out.nodes.size()) - 1;
        if (!EmitExpr(e.kids[1], b, out)) return false;
        const auto rhs = static_cast<std::int32_t>(out.nodes.size()) - 1;
        node.op = e.k == NExpr::K::kAdd   ? Op::kAdd
                  : e.k == NExpr::K::kSub ? Op::kSub
                  : e.k == NExpr::K::kMul ? Op::kMul
                                          : Op::kDiv;
        node.lhs = lhs;
        node.rhs = rhs;
        const auto& l = out.nodes[static_cast<std::size_t>(lhs)];
        const auto& r = out.nodes[static_cast<std::size_t>(rhs)];
        if (l.op == Op::kConstant && r.op == Op::kConstant) {
          double v = 0;
          switch (node.op) {
            case Op::kAdd:
              v = l.value + r.value;
              break;
            case Op::kSub:
              v = l.value - r.value;
              break;
            case Op::kMul:
              v = l.value * r.value;
              break;
            default:
              if (r.value == 0.0) return false;
              v = l.value / r.value;
              break;
          }
          out.nodes.pop_back();
          out.nodes.pop_back();
          node = {};
          node.op = Op::kConstant;
          node.value = v;
        }
        break;
      }
    }
    out.nodes.push_back(node);
    return true;
  }

  // Grounds a formula under binding `b`. In goal mode, atoms no action can
  // reach become facts (so the goal stays visibly unreachable) instead of false.
  GF GroundF(const F& f, std::vector<Obj>& b, const Schema& s, bool goal_mode) {
    GF out;
    out.time = f.time;
    switch (f.k) {
      case F::K::kTrue:
        out.k = GF::K::kTrue;
        return out;
      case F::K::kFalse:
        out.k = GF::K::kFalse;
        return out;
      case F::K::kEq: {
        Obj x = IsVar(f.args[0]) ? b[static_cast<std::size_t>(Slot(f.args[0]))] : f.args[0];
        Obj y = IsVar(f.args[1]) ? b[static_cast<std::size_t>(Slot(f.args[1]))] : f.args[1];
        out.k = ((x == y) == f.positive) ? GF::K::kTrue : GF::K::kFalse;
        return out;
      }
      case F::K::kAtom: {
        std::vector<Obj> args;
        for (auto a : f.args) args.push_back(IsVar(a) ? b[static_cast<std::size_t>(Slot(a))] : a);
        std::int32_t id = FindAtom(f.pred, args);
        bool known_true = false;
        FactId fact = -1;
        if (pred_static_[static_cast<std::size_t>(f.pred)]) {
          known_true = id >= 0 && atom_popped_[static_cast<std::size_t>(id)];
          if (goal_mode && f.positive && !known_true) {
            fact = ForceFact(f.pred, args);
            out.k = GF::K::kLit;
            out.fact = fact;
            out.positive = true;
            return out;
          }
          out.k = (known_true == f.positive) ? GF::K::kTrue : GF::K::kFalse;
          return out;
        }
        if (id >= 0 && static_cast<std::size_t>(id) < atom_fact_.size()) fact = FactOf(id);
        if (fact < 0) {
          if (goal_mode && f.positive) {
            out.k = GF::K::kLit;
            out.fact = ForceFact(f.pred, args);
            out.positive = true;
            return out;
          }
          // Never reachable: false as a positive literal, true as a negative one.
          out.k = f.positive ? GF::K::kFalse : GF::K::kTrue;
          return out;
        }
        out.k = GF::K::kLit;
        out.fact = fact;
        out.positive = f.positive;
        return out;
      }
      case F::K::kCmp: {
        NumericCondition c;
        c.comparator = ToTask(f.cmp);
        if (!EmitExpr(f.lhs, b, c.lhs) || !EmitExpr(f.rhs, b, c.rhs)) {
          out.k = GF::K::kFalse;  // reads an undefined static fluent
          return out;
        }
        if (c.lhs.IsConstant() && c.rhs.IsConstant()) {
          out.k = Compare(c.lhs.ConstantValue(), c.comparator, c.rhs.ConstantValue())
                      ? GF::K::kTrue
                      : GF::K::kFalse;
          return out;
        }
        out.k = GF::K::kCmp;
        out.cmp = std::move(c);
        return out;
      }
      case F::K::kAnd:
      case F::K::kOr: {
        const bool is_and = f.k == F::K::kAnd;
        out.k = is_and ? GF::K::kAnd : GF::K::kOr;
        for (const auto& kid : f.kids) {
          GF g = GroundF(kid, b, s, goal_mode);
          if (!AddKid(out, std::move(g), is_and)) break;
        }
        return Collapse(std::move(out), is_and);
      }
      case F::K::kForall:
      case F::K::kExists: {
        const bool is_and = f.k == F::K::kForall;
        out.k = is_and ? GF::K::kAnd : GF::K::kOr;
        Quantify(f, 0, b, s, goal_mode, out, is_and);
        for (int v : f.vars) b[static_cast<std::size_t>(v)] = -1;
        return Collapse(std::move(out), is_and);
      }
    }
    return out;
  }

  // Adds a child to an and/or node; false once the node is decided
  // (a false child of an and, a true child of an or).
  static bool AddKid(GF& node, GF kid, bool is_and) {
    if (node.kids.size() == 1 && node.kids[0].k == (is_and ? GF::K::kFalse : GF::K::kTrue))
      return false;
    if (kid.k == (is_and ? GF::K::kTrue : GF::K::kFalse)) return true;  // neutral
    if (kid.k == (is_and ? GF::K::kFalse : GF::K::kTrue)) {
      node.kids.clear();
      node.kids.push_back(std::move(kid));
      return false;
    }
    if (kid.k == node.k) {
      for (auto& g : kid.kids) node.kids.push_back(std::move(g));
    } else {
      node.kids.push_back(std::move(kid));
    }
    return true;
  }

  static GF Collapse(GF node, bool is_and) {
    if (node.kids.empty()) {
      GF out;
      out.k = is_and ? GF::K::kTrue : GF::K::kFalse;
      return out;
    }
    if (node.kids.size() == 1) return std::move(node.kids[0]);
    return node;
  }

  bool Quantify(const F& f, std::size_t i, std::vector<Obj>& b, const Schema& s, bool goal_mode,
                GF& out, bool is_and) {
    if (i == f.vars.size()) return AddKid(out, GroundF(f.kids[0], b, s, goal_mode), is_and);
    const auto slot = static_cast<std::size_t>(f.vars[i]);
    for (Obj o : s.vars[slot].objects) {
      b[slot] = o;
      if (!Tick() || !Quantify(f, i + 1, b, s, goal_mode, out, is_and)) return false;
    }
    return true;
  }

  // Ground DNF; false when it would have more than kMaxDisjuncts disjuncts.
  static bool GroundDnf(const GF& g, std::vector<GroundLits>& out) {
    switch (g.k) {
      case GF::K::kTrue:
        out.push_back({});
        return true;
      case GF::K::kFalse:
        return true;
      case GF::K::kLit:
      case GF::K::kCmp:
        out.push_back({{&g}});
        return true;
      case GF::K::kOr:
        for (const auto& kid : g.kids) {
          if (!GroundDnf(kid, out) || out.size() > kMaxDisjuncts) return false;
        }
        return true;
      case GF::K::kAnd: {
        std::vector<GroundLits> acc(1);
        for (const auto& kid : g.kids) {
          std::vector<GroundLits> part;
          if (!GroundDnf(kid, part)) return false;
          if (part.size() == 1) {
            for (auto& a : acc)
              a.leaves.insert(a.leaves.end(), part[0].leaves.begin(), part[0].leaves.end());
            continue;
          }
          std::vector<GroundLits> next;
          for (const auto& a : acc) {
            for (const auto& p : part) {
              GroundLits d = a;
              d.leaves.insert(d.leaves.end(), p.leaves.begin(), p.leaves.end());
              next.push_back(std::move(d));
            }
          }
          if (next.size() > kMaxDisjuncts) return false;
          acc = std::move(next);
        }
        out.insert(out.end(), acc.begin(), acc.end());
        return true;
      }
    }
    return true;
  }

  static void AddLeaf(Condition& c, const GF& leaf) {
    if (leaf.k == GF::K::kLit) {
      auto& list = leaf.positive ? c.positive : c.negative;
      if (std::find(list.begin(), list.end(), leaf.fact) == list.end()) list.push_back(leaf.fact);
    } else {
      c.numeric.push_back(leaf.cmp);
    }
  }

  // Fills the action's conditions from one ground disjunct; false when it is
  // contradictory (p and not p at the same time point).
  static bool FillConditions(Action& a, const GroundLits& lits) {
    for (const GF* leaf : lits.leaves) {
      switch (leaf->time) {
        case TimeSpec::kNone:
        case TimeSpec::kAtStart:
          AddLeaf(a.at_start, *leaf);
          break;
        case TimeSpec::kOverAll:
          AddLeaf(a.over_all, *leaf);
          break;
        case TimeSpec::kAtEnd:
          AddLeaf(a.at_end, *leaf);
          break;
      }
    }
    for (const Condition* c : {&a.at_start, &a.over_all, &a.at_end}) {
      for (FactId f : c->positive) {
        if (std::find(c->negative.begin(), c->negative.end(), f) != c->negative.end()) return false;
      }
    }
    return true;
  }

  // Grounds the effects into `a`; false on an unsupported construct.
  bool GroundEffects(const Schema& s, std::vector<Obj>& b, Action& a) {
    for (const auto& eff : s.effects) {
      if (!GroundEffect(s, eff, b, 0, a)) return false;
    }
    return true;
  }

  bool GroundEffect(const Schema& s, const EffItem& eff, std::vector<Obj>& b, std::size_t i,
                    Action& a) {
    if (i < eff.forall_vars.size()) {
      const auto slot = static_cast<std::size_t>(eff.forall_vars[i]);
      for (Obj o : s.vars[slot].objects) {
        b[slot] = o;
        if (!Tick() || !GroundEffect(s, eff, b, i + 1, a)) return false;
      }
      b[slot] = -1;
      return true;
    }
    Effects& target = eff.time == TimeSpec::kAtEnd ? a.end_effects : a.start_effects;
    // The effect itself.
    if (eff.k != EffItem::K::kNum && eff.cond.k == F::K::kTrue) {
      // Fast path (most effects): an unconditional add or delete.
      args_scratch_.clear();
      for (auto x : eff.args) {
        const Obj o = IsVar(x) ? b[static_cast<std::size_t>(Slot(x))] : x;
        if (o < 0) {
          Error(pddl::DiagnosticKind::kUnsupported, eff.location, "",
                "an effect uses a variable bound only by an existential precondition");
          return false;
        }
        args_scratch_.push_back(o);
      }
      const std::int32_t id = FindAtom(eff.pred, args_scratch_);
      FactId fact = id >= 0 && static_cast<std::size_t>(id) < atom_fact_.size() ? FactOf(id) : -1;
      if (eff.k == EffItem::K::kAdd) {
        if (fact < 0) {
          std::vector<Obj> args = args_scratch_;
          fact = ForceFact(eff.pred, args);
        }
        target.add.push_back(fact);
      } else if (fact >= 0) {
        target.del.push_back(fact);
      }
      return true;
    }
    std::vector<FactId> add, del;
    std::vector<NumericEffect> num;
    if (eff.k == EffItem::K::kNum) {
      std::vector<Obj> args;
      for (auto x : eff.fargs) args.push_back(IsVar(x) ? b[static_cast<std::size_t>(Slot(x))] : x);
      NumericEffect ne;
      ne.op = ToTask(eff.op);
      ne.var = VarOf(eff.func, args);
      if (!EmitExpr(eff.value, b, ne.value)) {
        // Reads an undefined static fluent: the action can never be applied.
        effect_undefined_ = true;
        return true;
      }
      num.push_back(std::move(ne));
    } else {
      std::vector<Obj> args;
      for (auto x : eff.args) args.push_back(IsVar(x) ? b[static_cast<std::size_t>(Slot(x))] : x);
      for (Obj o : args) {
        if (o < 0) {
          Error(pddl::DiagnosticKind::kUnsupported, eff.location, "",
                "an effect uses a variable bound only by an existential precondition");
          return false;
        }
      }
      std::int32_t id = FindAtom(eff.pred, args);
      FactId fact = id >= 0 && static_cast<std::size_t>(id) < atom_fact_.size() ? FactOf(id) : -1;
      if (eff.k == EffItem::K::kAdd) {
        if (fact < 0) fact = ForceFact(eff.pred, args);  // cannot happen after exploration; be safe
        add.push_back(fact);
      } else if (fact >= 0) {
        del.push_back(fact);
      } else {
        return true;  // deleting a never-true atom does nothing
      }
    }
    if (eff.cond.k == F::K::kTrue) {
      target.add.insert(target.add.end(), add.begin(), add.end());
      target.del.insert(target.del.end(), del.begin(), del.end());
      for (auto& n : num) target.numeric.push_back(std::move(n));
      return true;
    }
    GF g = GroundF(eff.cond, b, s, false);
    std::vector<GroundLits> dnf;
    if (!GroundDnf(g, dnf)) {
      Error(pddl::DiagnosticKind::kUnsupported, eff.location, "",
            "conditional effect condition too large in disjunctive normal form");
      return false;
    }
    if (dnf.size() > 1 && !num.empty()) {
      Error(pddl::DiagnosticKind::kUnsupported, eff.location, "",
            "numeric conditional effect with a disjunctive condition");
      return false;
    }
    for (const auto& lits : dnf) {
      if (lits.leaves.empty()) {  // condition is always true
        target.add.insert(target.add.end(), add.begin(), add.end());
        target.del.insert(target.del.end(), del.begin(), del.end());
        for (auto& n : num) target.numeric.push_back(n);
        continue;
      }
      ConditionalEffect ce;
      std::optional<TimeSpec> time;
      for (const GF* leaf : lits.leaves) {
        const TimeSpec t = leaf->time == TimeSpec::kNone ? TimeSpec::kAtStart : leaf->time;
        if (t == TimeSpec::kOverAll || (time && *time != t)) {
          Error(pddl::DiagnosticKind::kUnsupported, eff.location, "",
                "conditional effect whose condition mixes time points or uses 'over all'");
          return false;
        }
        time = t;
        AddLeaf(ce.condition, *leaf);
      }
      if (time == TimeSpec::kAtEnd && eff.time != TimeSpec::kAtEnd) {
        Error(pddl::DiagnosticKind::kUnsupported, eff.location, "",
              "conditional effect at start whose condition is checked at end");
        return false;
      }
      ce.condition_time = time == TimeSpec::kAtEnd ? TimePoint::kEnd : TimePoint::kStart;
      ce.add = add;
      ce.del = del;
      ce.numeric = num;
      target.conditional.push_back(std::move(ce));
    }
    return true;
  }

  void AssignFacts() {
    atom_fact_.assign(atoms_.size(), -1);
    for (std::size_t id = 0; id < atoms_.size(); ++id) {
      auto key = atoms_.Get(static_cast<std::int32_t>(id));
      if (pred_static_[static_cast<std::size_t>(key[0])] || !atom_queued_[id]) continue;
      atom_fact_[id] = static_cast<FactId>(task_->facts.size());
      Fact f;
      f.predicate = pred_names_[static_cast<std::size_t>(key[0])];
      for (std::size_t i = 1; i < key.size(); ++i)
        f.args.push_back(object_names_[static_cast<std::size_t>(key[i])]);
      task_->facts.push_back(std::move(f));
    }
  }

  // For a spec of plain literals and equalities (the common case), fills the
  // action's conditions directly, without building a ground formula. Returns
  // false when the spec needs the general path (quantifiers, comparisons);
  // `ok` is false when a literal is statically false.
  bool SimpleConditions(const Spec& spec, const std::vector<Obj>& b, Action& a, bool& ok) {
    for (const F* item : spec.items) {
      if (item->k != F::K::kAtom && item->k != F::K::kEq) return false;
    }
    ok = true;
    for (const F* item : spec.items) {
      if (item->k == F::K::kEq) {
        Obj x =
            IsVar(item->args[0]) ? b[static_cast<std::size_t>(Slot(item->args[0]))] : item->args[0];
        Obj y =
            IsVar(item->args[1]) ? b[static_cast<std::size_t>(Slot(item->args[1]))] : item->args[1];
        if ((x == y) != item->positive) ok = false;
        continue;
      }
      args_scratch_.clear();
      for (auto x : item->args)
        args_scratch_.push_back(IsVar(x) ? b[static_cast<std::size_t>(Slot(x))] : x);
      const std::int32_t id = FindAtom(item->pred, args_scratch_);
      if (pred_static_[static_cast<std::size_t>(item->pred)]) {
        const bool known_true = id >= 0 && atom_popped_[static_cast<std::size_t>(id)];
        if (known_true != item->positive) ok = false;
        continue;
      }
      const FactId fact =
          id >= 0 && static_cast<std::size_t>(id) < atom_fact_.size() ? FactOf(id) : -1;
      if (fact < 0) {
        if (item->positive) ok = false;  // unreachable; a negative literal on it is true
        continue;
      }
      Condition& c = item->time == TimeSpec::kOverAll ? a.over_all
                     : item->time == TimeSpec::kAtEnd ? a.at_end
                                                      : a.at_start;
      auto& list = item->positive ? c.positive : c.negative;
      if (std::find(list.begin(), list.end(), fact) == list.end()) list.push_back(fact);
    }
    return true;
  }

  bool BuildActions() {
    TupleSet names;  // (schema, params...) -> id, for variant numbering
    std::vector<int> next_variant;
    task_->actions.reserve(instances_.size());
    for (std::size_t inst = 0; inst < instances_.size(); ++inst) {
      auto key = instances_.Get(static_cast<std::int32_t>(inst));
      const Spec& spec = specs_[static_cast<std::size_t>(key[0])];
      const Schema& s = *schemas_[static_cast<std::size_t>(spec.schema)];
      std::vector<Obj> b(key.begin() + 1, key.end());
      Action simple;
      bool simple_ok = true;
      const bool is_simple = SimpleConditions(spec, b, simple, simple_ok);
      if (is_simple && !simple_ok) continue;
      // Condition: the spec's items, grounded.
      GF cond;
      cond.k = GF::K::kAnd;
      for (const F* item : spec.items) {
        if (is_simple) break;
        if (!AddKid(cond, GroundF(*item, b, s, false), true)) break;
      }
      cond = Collapse(std::move(cond), true);
      if (budget_exceeded_) return false;
      if (cond.k == GF::K::kFalse) continue;
      std::vector<GroundLits> dnf;
      if (is_simple) {
        dnf.emplace_back();  // conditions already in `simple`
      } else if (!GroundDnf(cond, dnf)) {
        Error(pddl::DiagnosticKind::kUnsupported, s.action->location, s.action->name,
              "ground precondition too large in disjunctive normal form");
        return false;
      }
      if (dnf.empty()) continue;
      Action base = std::move(simple);
      base.name = s.action->name;
      for (int p = 0; p < s.n_params; ++p)
        base.args.push_back(
            object_names_[static_cast<std::size_t>(b[static_cast<std::size_t>(p)])]);
      base.is_durative = s.action->durative;
      bool duration_ok = true;
      for (const auto& d : s.duration) {
        DurationConstraint dc;
        dc.comparator = ToTask(d.cmp);
        if (!EmitExpr(d.value, b, dc.value)) {
          duration_ok = false;
          break;
        }
        base.duration.push_back(std::move(dc));
      }
      if (!duration_ok) continue;
      effect_undefined_ = false;
      std::vector<Obj> eb = b;
      if (!GroundEffects(s, eb, base)) return false;
      if (effect_undefined_) continue;
      // Variant numbers: only schemas with several specs or existential
      // variables can produce one (name, args) twice, so only they pay for
      // the lookup.
      int* variant = nullptr;
      int local_variant = 0;
      if (s.specs.size() > 1 || spec.free_vars.size() > static_cast<std::size_t>(s.n_params)) {
        key_.clear();
        key_.push_back(spec.schema);
        key_.insert(key_.end(), b.begin(), b.begin() + s.n_params);
        auto [name_id, fresh] = names.Insert(key_);
        if (fresh) next_variant.push_back(0);
        variant = &next_variant[static_cast<std::size_t>(name_id)];
      } else {
        variant = &local_variant;
      }
      for (std::size_t v = 0; v < dnf.size(); ++v) {
        Action a = v + 1 == dnf.size() ? std::move(base) : base;
        if (!FillConditions(a, dnf[v])) continue;
        a.variant = (*variant)++;
        task_->actions.push_back(std::move(a));
        if (task_->actions.size() > options_.max_actions) {
          Error(pddl::DiagnosticKind::kSemantic, problem_.location, "",
                "grounding exceeds the action budget of " + std::to_string(options_.max_actions) +
                    " actions",
                "a smaller problem or a larger GroundingOptions::max_actions");
          return false;
        }
      }
    }
    return true;
  }

  bool BuildGoal() {
    Schema goal_schema;
    scope_.clear();
    F goal = ConvertCondition(goal_schema, problem_.goal, false, TimeSpec::kNone);
    scope_.clear();
    std::vector<Obj> b(goal_schema.vars.size(), -1);
    GF g = GroundF(goal, b, goal_schema, true);
    if (budget_exceeded_) return false;
    if (g.k == GF::K::kFalse) {
      Warn(problem_.goal.location, "",
           "the goal is statically false (it contradicts facts that never change); the task has no "
           "solution");
      // A fact nothing achieves stands for the impossible goal.
      task_->goal.positive.push_back(static_cast<FactId>(task_->facts.size()));
      task_->facts.push_back({"@false", {}});
      return true;
    }
    std::vector<GroundLits> dnf;
    if (!GroundDnf(g, dnf)) {
      Error(pddl::DiagnosticKind::kUnsupported, problem_.goal.location, "",
            "goal too large in disjunctive normal form");
      return false;
    }
    if (dnf.size() > 1) {
      Error(pddl::DiagnosticKind::kUnsupported, problem_.goal.location, "",
            "disjunctive goal (a goal with 'or', 'imply' or 'exists' that does not simplify to a "
            "conjunction)");
      return false;
    }
    for (const GF* leaf : dnf[0].leaves) AddLeaf(task_->goal, *leaf);
    for (FactId f : task_->goal.positive) {
      if (f >= static_cast<FactId>(reachable_facts_)) {
        Warn(problem_.goal.location, task_->facts[static_cast<std::size_t>(f)].DisplayName(),
             "goal fact is unreachable: no action or timed literal can make it true");
      }
    }
    return true;
  }

  void BuildMetric() {
    task_->metric.minimize = !problem_.metric.present || problem_.metric.minimize;
    if (!problem_.metric.present) {
      task_->metric.expression.nodes.push_back({NumericExpr::Op::kTotalTime, 0.0, -1, -1, -1});
      return;
    }
    Schema none;
    scope_.clear();
    NExpr e = ConvertExpr(problem_.metric.expression);
    std::vector<Obj> b;
    NumericExpr out;
    if (!EmitExpr(e, b, out)) {
      Warn(problem_.metric.location, "", "metric reads an undefined fluent; using total-time");
      out.nodes.clear();
      out.nodes.push_back({NumericExpr::Op::kTotalTime, 0.0, -1, -1, -1});
    }
    task_->metric.expression = std::move(out);
  }

  // ---- data ----------------------------------------------------------------------

  const pddl::Domain& domain_;
  const pddl::Problem& problem_;
  const GroundingOptions& options_;
  std::vector<pddl::Diagnostic>& diags_;

  pddl::TypeHierarchy types_;
  std::unordered_map<std::string, Obj> object_index_;
  std::vector<std::string> object_names_;
  std::vector<std::vector<std::string>> object_types_;
  std::vector<std::vector<Obj>> objects_of_type_;
  std::vector<std::vector<std::uint8_t>> type_member_;
  std::unordered_map<std::string, int> pred_index_;
  std::vector<std::string> pred_names_;
  std::vector<int> pred_arity_;
  std::vector<bool> pred_static_;
  std::unordered_map<std::string, int> func_index_;
  std::vector<std::string> func_names_;
  std::vector<bool> func_static_;

  TupleSet atoms_;  // (pred, args...) of every atom seen
  std::vector<std::uint8_t> atom_popped_;
  std::vector<std::uint8_t> atom_queued_;
  std::vector<FactId> atom_fact_;
  std::vector<std::int32_t> queue_;
  std::vector<std::int32_t> init_atoms_;
  std::vector<std::int32_t> til_atoms_;
  std::vector<std::vector<std::int32_t>> by_pred_;
  std::vector<std::vector<std::vector<std::vector<std::int32_t>>>> by_arg_;  // [pred][pos][object]
  std::size_t static_true_ = 0;

  TupleSet fterms_;  // (func, args...)
  std::vector<double> fterm_value_;
  std::vector<NumericVarId> fterm_var_;

  std::vector<std::unique_ptr<Schema>> schemas_;
  std::vector<Spec> specs_;
  TupleSet instances_;  // (spec, binding...)
  std::vector<std::pair<std::string, int>> scope_;

  std::vector<std::int32_t> key_;
  std::vector<Obj> args_scratch_;
  std::vector<Obj> fargs_scratch_;
  bool budget_exceeded_ = false;
  std::size_t work_ = 0;
  std::size_t index_cells_ = 0;
  bool effect_undefined_ = false;
  std::size_t reachable_facts_ = 0;
  std::shared_ptr<GroundTask> task_;
};

std::shared_ptr<GroundTask> Grounder::Build() {
  task_ = std::make_shared<GroundTask>();
  task_->domain_name = domain_.name;
  task_->problem_name = problem_.name;
  AssignFacts();
  reachable_facts_ = task_->facts.size();
  // Numeric variables: every changing fluent defined in :init first, so that
  // initial values line up; others appear as actions read them.
  for (std::size_t id = 0; id < fterms_.size(); ++id) {
    auto key = fterms_.Get(static_cast<std::int32_t>(id));
    if (func_static_[static_cast<std::size_t>(key[0])]) continue;
    std::vector<Obj> args(key.begin() + 1, key.end());
    VarOf(key[0], args);
  }
  if (!BuildActions()) return nullptr;
  for (std::int32_t atom : init_atoms_) {
    const FactId f = FactOf(atom);
    if (f >= 0) task_->initial_facts.push_back(f);
  }
  std::sort(task_->initial_facts.begin(), task_->initial_facts.end());
  task_->initial_facts.erase(std::unique(task_->initial_facts.begin(), task_->initial_facts.end()),
                             task_->initial_facts.end());
  for (std::size_t i = 0; i < problem_.timed_literals.size(); ++i) {
    const auto& til = problem_.timed_literals[i];
    auto key = atoms_.Get(til_atoms_[i]);
    std::vector<Obj> args(key.begin() + 1, key.end());
    TimedInitialLiteral t;
    t.time_s = til.time;
    t.fact = ForceFact(key[0], args);
    t.value = til.positive;
    task_->timed_literals.push_back(t);
  }
  std::stable_sort(task_->timed_literals.begin(), task_->timed_literals.end(),
                   [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
  for (const auto& tif : problem_.timed_numeric_init) {
    std::vector<Obj> args;
    for (const auto& a : tif.init.args) args.push_back(ObjectId(a));
    TimedInitialFluent t;
    t.time_s = tif.time;
    t.var = VarOf(func_index_.at(tif.init.function), args);
    t.value = tif.init.value;
    task_->timed_fluents.push_back(t);
  }
  std::stable_sort(task_->timed_fluents.begin(), task_->timed_fluents.end(),
                   [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
  if (!BuildGoal()) return nullptr;
  BuildMetric();
  if (task_->facts.size() > options_.max_facts) {
    Error(pddl::DiagnosticKind::kSemantic, problem_.location, "",
          "grounding exceeds the fact budget of " + std::to_string(options_.max_facts) + " facts",
          "a smaller problem or a larger GroundingOptions::max_facts");
    return nullptr;
  }
  return task_;
}

std::string Grounder::Explain(std::string_view name, std::span<const std::string> args,
                              const GroundTask* task) {
  const pddl::Action* action = domain_.FindAction(name);
  std::string call = "(" + std::string(name);
  for (const auto& a : args) call += " " + a;
  call += ")";
  if (action == nullptr) {
    std::string known;
    for (const auto& a : domain_.actions) known += (known.empty() ? "" : ", ") + a.name;
    return call + ": unknown action '" + std::string(name) + "' (the domain has: " + known + ")";
  }
  if (args.size() != action->parameters.size()) {
    std::string params;
    for (const auto& p : action->parameters) params += (params.empty() ? "" : " ") + p.name;
    return call + ": wrong number of arguments: " + std::to_string(args.size()) + " given, '" +
           action->name + "' takes " + std::to_string(action->parameters.size()) + " (" + params +
           ")";
  }
  InternSymbols();
  if (!CheckProblemMatchesDomain()) return call + ": the problem does not match the domain";
  FindStatics();
  std::vector<Obj> objs;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const Obj o = ObjectId(args[i]);
    if (o < 0) return call + ": unknown object '" + args[i] + "'";
    bool fits = false;
    for (const auto& want : action->parameters[i].types) {
      for (const auto& have : object_types_[static_cast<std::size_t>(o)])
        fits = fits || types_.IsSubtype(have, want);
    }
    if (!fits) {
      std::string have, want;
      for (const auto& t : object_types_[static_cast<std::size_t>(o)])
        have += (have.empty() ? "" : " or ") + t;
      for (const auto& t : action->parameters[i].types) want += (want.empty() ? "" : " or ") + t;
      return call + ": type mismatch: argument " + std::to_string(i + 1) + " '" + args[i] +
             "' is a " + have + ", but " + action->parameters[i].name + " must be a " + want;
    }
    objs.push_back(o);
  }
  if (!LoadInit()) return call + ": grounding budget exceeded";
  for (const auto& a : domain_.actions) {
    if (!BuildSchema(a)) return call + ": unsupported construct in the domain";
  }
  if (!RunExploration()) return call + ": grounding budget exceeded";
  if (task != nullptr) {
    for (const auto& a : task->actions) {
      if (a.name == action->name &&
          std::equal(a.args.begin(), a.args.end(), args.begin(), args.end()))
        return "";
    }
  }
  std::size_t schema_id = 0;
  while (schemas_[schema_id]->action != action) ++schema_id;
  const Schema& s = *schemas_[schema_id];
  auto show_atom = [&](const F& item, const std::vector<Obj>& b) {
    std::string out =
        "(" +
        (item.k == F::K::kEq ? std::string("=") : pred_names_[static_cast<std::size_t>(item.pred)]);
    for (auto x : item.args) {
      const Obj o = IsVar(x) ? b[static_cast<std::size_t>(Slot(x))] : x;
      out += " " + (o < 0 ? s.vars[static_cast<std::size_t>(Slot(x))].name
                          : object_names_[static_cast<std::size_t>(o)]);
    }
    return out + ")";
  };
  auto bound = [&](const F& item, const std::vector<Obj>& b) {
    for (auto x : item.args) {
      if (IsVar(x) && b[static_cast<std::size_t>(Slot(x))] < 0) return false;
    }
    return true;
  };
  std::string first_reason;
  std::vector<Obj> b(s.vars.size(), -1);
  for (std::size_t p = 0; p < objs.size(); ++p) b[p] = objs[p];
  for (int spec_id : s.specs) {
    const Spec& spec = specs_[static_cast<std::size_t>(spec_id)];
    std::string reason;
    for (const F* item : spec.items) {
      if ((item->k == F::K::kAtom || item->k == F::K::kEq) && bound(*item, b)) {
        if (item->k == F::K::kEq) {
          Obj x = IsVar(item->args[0]) ? b[static_cast<std::size_t>(Slot(item->args[0]))]
                                       : item->args[0];
          Obj y = IsVar(item->args[1]) ? b[static_cast<std::size_t>(Slot(item->args[1]))]
                                       : item->args[1];
          if ((x == y) != item->positive) {
            reason = "the precondition " + std::string(item->positive ? "" : "(not ") +
                     show_atom(*item, b) + (item->positive ? "" : ")") + " is false";
          }
        } else {
          std::vector<Obj> a;
          for (auto x : item->args)
            a.push_back(IsVar(x) ? b[static_cast<std::size_t>(Slot(x))] : x);
          const std::int32_t id = FindAtom(item->pred, a);
          const bool reached = id >= 0 && atom_popped_[static_cast<std::size_t>(id)];
          if (pred_static_[static_cast<std::size_t>(item->pred)] && reached != item->positive) {
            reason = "the precondition " + std::string(item->positive ? "" : "(not ") +
                     show_atom(*item, b) + (item->positive ? "" : ")") +
                     " is false and never changes (static)";
          } else if (!pred_static_[static_cast<std::size_t>(item->pred)] && item->positive &&
                     !reached) {
            reason = "the precondition " + show_atom(*item, b) +
                     " can never become true (unreachable from the initial state)";
          }
        }
      } else if (item->k == F::K::kCmp && IsStaticExpr(item->lhs) && IsStaticExpr(item->rhs) &&
                 std::all_of(b.begin(), b.begin() + s.n_params, [](Obj o) { return o >= 0; })) {
        const double l = EvalStatic(item->lhs, b);
        const double r = EvalStatic(item->rhs, b);
        if (std::isnan(l) || std::isnan(r)) {
          reason = "a numeric precondition reads a function with no value in :init";
        } else if (!Compare(l, ToTask(item->cmp), r)) {
          reason = "a numeric precondition over static functions is false (" + std::to_string(l) +
                   " " + pddl::ComparatorSymbol(item->cmp) + " " + std::to_string(r) + ")";
        }
      }
      if (!reason.empty()) break;
    }
    if (reason.empty()) {
      for (const auto& d : s.duration) {
        if (IsStaticExpr(d.value) && std::isnan(EvalStatic(d.value, b))) {
          reason = "its duration reads a function with no value in :init";
        }
      }
    }
    if (reason.empty()) {
      if (task == nullptr) {
        return call +
               ": no reason found: its static preconditions hold and its fact preconditions are "
               "reachable";
      }
      return call +
             ": its preconditions cannot hold together (a quantified, numeric or duration "
             "condition is "
             "false or undefined for these arguments; pruned by grounding)";
    }
    if (first_reason.empty()) first_reason = reason;
  }
  if (first_reason.empty()) first_reason = "its precondition is always false";
  return call + ": " + first_reason;
}

}  // namespace

absl::Status GroundingOptions::Validate() const {
  if (max_actions == 0 || max_facts == 0 || max_work == 0) {
    return absl::InvalidArgumentError(
        "GroundingOptions: max_actions, max_facts and max_work must be > 0");
  }
  return absl::OkStatus();
}

LoadResult Ground(const pddl::Domain& domain, const pddl::Problem& problem,
                  const GroundingOptions& options) {
  LoadResult result;
  if (absl::Status status = options.Validate(); !status.ok()) {
    result.diagnostics.push_back({pddl::Severity::kError,
                                  pddl::DiagnosticKind::kSemantic,
                                  {},
                                  "",
                                  std::string(status.message()),
                                  ""});
    return result;
  }
  const auto start = std::chrono::steady_clock::now();
  Grounder grounder(domain, problem, options, result.diagnostics);
  if (grounder.Explore()) {
    auto task = grounder.Build();
    if (task != nullptr && !pddl::HasErrors(result.diagnostics)) result.task = std::move(task);
  }
  result.stats.ground_ms = Millis(start);
  result.stats.reachable_atoms = grounder.reachable_atoms();
  result.stats.static_atoms = grounder.static_atoms();
  if (result.task) result.stats.size = result.task->Size();
  return result;
}

LoadResult LoadTask(std::string_view domain_text, std::string_view problem_text,
                    const GroundingOptions& options, std::string_view domain_file,
                    std::string_view problem_file) {
  LoadResult result;
  const auto start = std::chrono::steady_clock::now();
  auto parsed_domain = pddl::ParseDomain(domain_text, domain_file);
  result.diagnostics = std::move(parsed_domain.diagnostics);
  if (!parsed_domain.domain) {
    result.stats.parse_ms = Millis(start);
    return result;
  }
  auto domain = std::make_shared<const pddl::Domain>(std::move(*parsed_domain.domain));
  auto parsed_problem = pddl::ParseProblem(problem_text, *domain, problem_file);
  result.diagnostics.insert(result.diagnostics.end(), parsed_problem.diagnostics.begin(),
                            parsed_problem.diagnostics.end());
  result.stats.parse_ms = Millis(start);
  result.domain = domain;
  if (!parsed_problem.problem) return result;
  auto problem = std::make_shared<const pddl::Problem>(std::move(*parsed_problem.problem));
  result.problem = problem;
  LoadResult grounded = Ground(*domain, *problem, options);
  result.diagnostics.insert(result.diagnostics.end(), grounded.diagnostics.begin(),
                            grounded.diagnostics.end());
  result.task = std::move(grounded.task);
  const double parse_ms = result.stats.parse_ms;
  result.stats = grounded.stats;
  result.stats.parse_ms = parse_ms;
  return result;
}

LoadResult LoadTaskFromFiles(const std::string& domain_path, const std::string& problem_path,
                             const GroundingOptions& options) {
  auto read = [](const std::string& path, std::string& out) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::ostringstream ss;
    ss << in.rdbuf();
    out = ss.str();
    return true;
  };
  std::string domain_text, problem_text;
  LoadResult result;
  for (const auto* path : {&domain_path, &problem_path}) {
    if (!read(*path, path == &domain_path ? domain_text : problem_text)) {
      result.diagnostics.push_back({pddl::Severity::kError,
                                    pddl::DiagnosticKind::kSyntax,
                                    {*path, 0, 0},
                                    *path,
                                    "cannot read the file",
                                    "a readable PDDL file"});
    }
  }
  if (pddl::HasErrors(result.diagnostics)) return result;
  return LoadTask(domain_text, problem_text, options, domain_path, problem_path);
}

ActionIndex::ActionIndex(const GroundTask& task) : task_(&task) {
  by_hash_.reserve(task.actions.size());
  for (std::size_t i = 0; i < task.actions.size(); ++i) {
    by_hash_.emplace_back(Hash(task.actions[i].name, task.actions[i].args),
                          static_cast<ActionId>(i));
  }
  std::sort(by_hash_.begin(), by_hash_.end());
}

namespace {

char AsciiLower(char c) {
  return static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
}

bool EqualsLowered(std::string_view query, std::string_view lower) {
  if (query.size() != lower.size()) return false;
  for (std::size_t i = 0; i < query.size(); ++i) {
    if (AsciiLower(query[i]) != lower[i]) return false;
  }
  return true;
}

}  // namespace

std::uint64_t ActionIndex::Hash(std::string_view name, std::span<const std::string> args) {
  // FNV-1a over the lower-cased "name arg1 arg2 ...".
  std::uint64_t h = 1469598103934665603ull;
  auto add = [&h](char c) {
    h ^= static_cast<unsigned char>(AsciiLower(c));
    h *= 1099511628211ull;
  };
  for (char c : name) add(c);
  for (const auto& a : args) {
    add(' ');
    for (char c : a) add(c);
  }
  return h;
}

std::vector<ActionId> ActionIndex::Find(std::string_view name,
                                        std::span<const std::string> args) const {
  std::vector<ActionId> out;
  const std::uint64_t h = Hash(name, args);
  auto it = std::lower_bound(by_hash_.begin(), by_hash_.end(), std::make_pair(h, ActionId{0}),
                             [](const auto& x, const auto& y) { return x.first < y.first; });
  for (; it != by_hash_.end() && it->first == h; ++it) {
    const Action& action = task_->actions[static_cast<std::size_t>(it->second)];
    if (action.args.size() != args.size() || !EqualsLowered(name, action.name)) continue;
    bool same = true;
    for (std::size_t k = 0; k < args.size() && same; ++k)
      same = EqualsLowered(args[k], action.args[k]);
    if (same) out.push_back(it->second);
  }
  return out;
}

}  // namespace seaplan::task

namespace seaplan::task {

std::string ExplainMissingAction(const pddl::Domain& domain, const pddl::Problem& problem,
                                 std::string_view name, std::span<const std::string> args,
                                 const GroundTask* task) {
  auto lower = [](std::string_view in) {
    std::string out(in);
    for (auto& c : out) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
    return out;
  };
  std::vector<std::string> lowered;
  for (const auto& a : args) lowered.push_back(lower(a));
  std::vector<pddl::Diagnostic> diagnostics;
  GroundingOptions options;
  Grounder grounder(domain, problem, options, diagnostics);
  return grounder.Explain(lower(name), lowered, task);
}

}  // namespace seaplan::task
