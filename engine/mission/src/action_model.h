// Internal: PDDL action semantics over the parsed AST, used to lift a plan to
// a partial order (which facts each event reads and writes) and to apply a
// plan prefix to the problem's initial state (state update for replanning).
//
// Why not the ground task: the grounder folds static facts away and renames
// nothing, but the state update must print a PDDL problem again, static
// facts included, and must work for objects that only the regenerated
// problem has (port-s). Instantiating the few actions of a plan straight
// from the AST is cheap and keeps the semantics in one readable place.
#pragma once

#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/pddl/parser.h"
#include "seaplan/pddl/type_hierarchy.h"

namespace seaplan::mission::internal {

// "(pred a b)" with lower-case names; fluents use the same form.
std::string AtomKey(std::string_view predicate, const std::vector<std::string>& args);

struct WorldState {
  std::set<std::string> facts;            // true atoms (static ones included)
  std::map<std::string, double> fluents;  // defined numeric fluents
};

using Binding = std::map<std::string, std::string, std::less<>>;  // "?v" -> "ship0"

// One instantiated plan action.
struct ActionInstance {
  const pddl::Action* schema = nullptr;  // points into the ActionModel's domain
  std::string name;
  std::vector<std::string> args;
  Binding binding;
  // Atom/fluent keys each part reads (conditions, when-conditions, numeric
  // expressions) and writes (effects), for interference detection.
  std::set<std::string> reads_start, reads_overall, reads_end;
  std::set<std::string> writes_start, writes_end;
};

// Holds the parsed domain and problem (copies: values). Thread-compatible.
class ActionModel {
 public:
  static StatusOr<ActionModel> Create(std::string_view domain_text, std::string_view problem_text);

  const pddl::Domain& domain() const { return domain_; }
  const pddl::Problem& problem() const { return problem_; }

  // The initial state of the problem (timed literals ignored).
  WorldState InitialState() const;

  // Instantiates (name args); InvalidArgument when the action is unknown or
  // the argument count is wrong.
  StatusOr<ActionInstance> Instantiate(std::string_view name,
                                       const std::vector<std::string>& args) const;

  // Applies the start (at_end=false) or end effects; numeric effects may
  // read ?duration. Deletes are applied before adds (PDDL semantics).
  Status Apply(const ActionInstance& action, bool at_end, double duration_s,
               WorldState* state) const;

  // True when the problem's goal holds in `state`.
  bool GoalHolds(const WorldState& state) const { return Holds(problem_.goal, {}, state, 0.0); }

  // Objects (and domain constants) whose type is `type` or a subtype.
  std::vector<std::string> ObjectsOfType(std::string_view type) const;
  // The declared type of an object or constant ("" when unknown).
  std::string TypeOf(std::string_view object) const;
  // True when no action effect changes this predicate / function.
  bool IsStaticPredicate(std::string_view predicate) const;
  bool IsStaticFunction(std::string_view function) const;
  // True when some action's condition mentions `predicate` (positively or not).
  bool PredicateInConditions(std::string_view predicate) const;

 private:
  ActionModel() = default;
  void CollectReads(const pddl::Condition& c, const Binding& b, pddl::TimeSpec time,
                    ActionInstance* out) const;
  void CollectExprReads(const pddl::NumExpr& e, const Binding& b, std::set<std::string>* out) const;
  void CollectWrites(const pddl::Effect& e, const Binding& b, pddl::TimeSpec time,
                     ActionInstance* out) const;
  bool Holds(const pddl::Condition& c, const Binding& b, const WorldState& s,
             double duration_s) const;
  StatusOr<double> Eval(const pddl::NumExpr& e, const Binding& b, const WorldState& s,
                        double duration_s) const;
  Status ApplyEffect(const pddl::Effect& e, const Binding& b, bool at_end, bool durative,
                     pddl::TimeSpec inherited, const WorldState& before, double duration_s,
                     std::vector<std::string>* add, std::vector<std::string>* del,
                     std::vector<std::pair<std::string, double>>* assign) const;
  std::string Resolve(const pddl::Term& t, const Binding& b) const;
  std::vector<std::string> Resolve(const std::vector<pddl::Term>& ts, const Binding& b) const;
  // Every binding of `vars` to objects of their types, extending `b`.
  std::vector<Binding> Expand(const std::vector<pddl::TypedName>& vars, const Binding& b) const;

  pddl::Domain domain_;
  pddl::Problem problem_;
  pddl::TypeHierarchy types_;  // of domain_
  std::set<std::string, std::less<>> changed_predicates_;
  std::set<std::string, std::less<>> changed_functions_;
};

// PDDL text of a condition / numeric expression (for printing goals).
std::string ToPddl(const pddl::Condition& c);
std::string ToPddl(const pddl::NumExpr& e);

}  // namespace seaplan::mission::internal
