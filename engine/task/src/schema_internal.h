// Grounding stage 2, schema compilation: each action schema's condition in
// negation normal form over ids (SchemaCondition), its effects flattened
// (SchemaEffect: forall variables and `when` conditions attached to each
// literal), and its precondition split into DNF disjuncts
// (PreconditionDisjunct: conjunctions of literals, equalities, comparisons
// and opaque forall items; exists variables become extra variables to bind),
// which the reachability stage joins. The goal and the metric are compiled
// the same way.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "symbols_internal.h"

namespace seaplan::task::internal {

// A numeric expression over a schema's variables.
struct SchemaExpression {
  enum class Kind { kNumber, kFluent, kDuration, kTotalTime, kAdd, kSub, kMul, kDiv, kNegate };
  Kind kind = Kind::kNumber;
  double number = 0.0;                     // kNumber
  FunctionId function;                     // kFluent
  std::vector<Term> args;                  // kFluent
  std::vector<SchemaExpression> children;  // operands (two for binary operators)
};

// A condition in negation normal form (negation only on atoms and equalities).
struct SchemaCondition {
  enum class Kind { kTrue, kFalse, kAtom, kEquality, kComparison, kAnd, kOr, kForall, kExists };
  Kind kind = Kind::kTrue;
  bool positive = true;                                    // kAtom, kEquality
  PredicateId predicate;                                   // kAtom
  std::vector<Term> args;                                  // kAtom, kEquality
  pddl::TimeSpec time = pddl::TimeSpec::kNone;             // the enclosing time specifier
  pddl::Comparator comparator = pddl::Comparator::kEqual;  // kComparison
  SchemaExpression lhs, rhs;                               // kComparison
  std::vector<SchemaCondition> children;                   // kAnd, kOr; one for quantifiers
  std::vector<VariableSlot> quantified;                    // kForall, kExists
};

// One add, delete or numeric effect with everything that encloses it.
struct SchemaEffect {
  enum class Kind { kAdd, kDelete, kNumeric };
  Kind kind = Kind::kAdd;
  pddl::TimeSpec time = pddl::TimeSpec::kNone;
  std::vector<VariableSlot> forall_variables;   // enclosing foralls, outermost first
  SchemaCondition condition;                    // of the enclosing whens; kTrue when none
  PredicateId predicate;                        // kAdd, kDelete
  std::vector<Term> args;                       // kAdd, kDelete
  pddl::AssignOp op = pddl::AssignOp::kAssign;  // kNumeric
  FunctionId function;                          // kNumeric
  std::vector<Term> function_args;              // kNumeric
  SchemaExpression value;                       // kNumeric
  pddl::SourceLocation location;
};

// A parameter or quantified variable and the objects it ranges over.
struct SchemaVariable {
  std::string name;
  std::vector<ObjectId> objects;      // of the variable's type(s), ascending
  std::vector<std::uint8_t> allowed;  // by ObjectId: 1 when in `objects`
};

struct DurationBound {
  pddl::Comparator comparator = pddl::Comparator::kEqual;
  SchemaExpression value;
};

// One disjunct of a schema's precondition DNF: a conjunction of items
// (atoms, equalities, comparisons, foralls) pointing into Schema::condition.
struct PreconditionDisjunct {
  SchemaId schema;
  std::vector<const SchemaCondition*> items;
  std::vector<int> join_atoms;               // indexes into items of the positive atoms
  std::vector<VariableSlot> free_variables;  // to bind: parameters, then exists variables
  bool has_fluent_atom = false;              // some join atom's predicate can change
};

struct Schema {
  const pddl::Action* action = nullptr;   // null for the goal
  int parameter_count = 0;                // slots 0..parameter_count-1 are the parameters
  std::vector<SchemaVariable> variables;  // by VariableSlot
  SchemaCondition condition;
  std::vector<SchemaEffect> effects;
  std::vector<DurationBound> duration;
  std::vector<DisjunctId> disjuncts;

  const SchemaVariable& variable(VariableSlot slot) const { return variables[slot.index()]; }
};

// The stage's value. Schemas are heap-allocated so that the disjuncts'
// item pointers stay valid when the vector grows or the value moves.
struct CompiledSchemas {
  std::vector<std::unique_ptr<Schema>> schemas;  // by SchemaId, in domain order
  std::vector<PreconditionDisjunct> disjuncts;   // by DisjunctId
  std::unique_ptr<Schema> goal;                  // variables and condition only
  std::optional<SchemaExpression> metric;        // when the problem has a metric

  const Schema& schema(SchemaId id) const { return *schemas[id.index()]; }
  const PreconditionDisjunct& disjunct(DisjunctId id) const { return disjuncts[id.index()]; }
  const Schema& schema_of(const PreconditionDisjunct& d) const { return schema(d.schema); }
};

// nullopt when a precondition's DNF has more than kMaxDisjuncts disjuncts
// (an unsupported diagnostic says which action) or the stop token fired.
std::optional<CompiledSchemas> CompileSchemas(const pddl::Domain& domain,
                                              const pddl::Problem& problem,
                                              const SymbolTable& symbols,
                                              GroundingContext& context);

// True when the expression reads only numbers and static fluents.
bool IsStaticExpression(const SchemaExpression& expression, const SymbolTable& symbols);

}  // namespace seaplan::task::internal
