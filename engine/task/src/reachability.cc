#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "reachability_internal.h"

namespace seaplan::task::internal {

// ---- tables -------------------------------------------------------------------

namespace {

// (head, objects...) as TupleSet keys hold them.
void Pack(std::int32_t head, std::span<const ObjectId> args, std::vector<std::int32_t>& key) {
  key.clear();
  key.push_back(head);
  for (ObjectId o : args) key.push_back(o.value());
}

std::vector<ObjectId> Unpack(std::span<const std::int32_t> key) {
  std::vector<ObjectId> args;
  args.reserve(key.size() - 1);
  for (std::size_t i = 1; i < key.size(); ++i) args.push_back(ObjectId(key[i]));
  return args;
}

}  // namespace

void AtomTable::PackKey(PredicateId predicate, std::span<const ObjectId> args) {
  Pack(predicate.value(), args, key_);
}

AtomId AtomTable::Intern(PredicateId predicate, std::span<const ObjectId> args, bool* inserted) {
  PackKey(predicate, args);
  auto [id, fresh] = atoms_.Insert(key_);
  if (fresh) reached_.push_back(0);
  if (inserted != nullptr) *inserted = fresh;
  return AtomId(id);
}

AtomId AtomTable::Find(PredicateId predicate, std::span<const ObjectId> args) {
  PackKey(predicate, args);
  return AtomId(atoms_.Find(key_));
}

std::vector<ObjectId> AtomTable::arguments(AtomId atom) const {
  return Unpack(atoms_.Get(atom.value()));
}

void FunctionTermTable::PackKey(FunctionId function, std::span<const ObjectId> args) {
  Pack(function.value(), args, key_);
}

FunctionTermId FunctionTermTable::Intern(FunctionId function, std::span<const ObjectId> args,
                                         bool* inserted) {
  PackKey(function, args);
  auto [id, fresh] = terms_.Insert(key_);
  if (fresh) initial_values_.push_back(kUndefinedValue);
  if (inserted != nullptr) *inserted = fresh;
  return FunctionTermId(id);
}

double FunctionTermTable::InitialValue(FunctionId function, std::span<const ObjectId> args) {
  PackKey(function, args);
  const std::int32_t id = terms_.Find(key_);
  return id < 0 ? kUndefinedValue : initial_values_[static_cast<std::size_t>(id)];
}

void FunctionTermTable::SetInitialValue(FunctionId function, std::span<const ObjectId> args,
                                        double value) {
  initial_values_[Intern(function, args).index()] = value;
}

std::vector<ObjectId> FunctionTermTable::arguments(FunctionTermId term) const {
  return Unpack(terms_.Get(term.value()));
}

bool InstanceTable::Insert(DisjunctId disjunct, const Binding& binding) {
  Pack(disjunct.value(), binding, key_);
  return instances_.Insert(key_).second;
}

Binding InstanceTable::binding(std::size_t instance) const {
  return Unpack(instances_.Get(static_cast<std::int32_t>(instance)));
}

double EvaluateStatic(const SchemaExpression& e, const Binding& binding,
                      FunctionTermTable& function_terms) {
  using Kind = SchemaExpression::Kind;
  switch (e.kind) {
    case Kind::kNumber:
      return e.number;
    case Kind::kFluent: {
      std::vector<ObjectId> args;
      args.reserve(e.args.size());
      for (Term a : e.args) args.push_back(Resolve(a, binding));
      return function_terms.InitialValue(e.function, args);
    }
    case Kind::kDuration:
    case Kind::kTotalTime:
      return kUndefinedValue;
    case Kind::kNegate:
      return -EvaluateStatic(e.children[0], binding, function_terms);
    case Kind::kAdd:
      return EvaluateStatic(e.children[0], binding, function_terms) +
             EvaluateStatic(e.children[1], binding, function_terms);
    case Kind::kSub:
      return EvaluateStatic(e.children[0], binding, function_terms) -
             EvaluateStatic(e.children[1], binding, function_terms);
    case Kind::kMul:
      return EvaluateStatic(e.children[0], binding, function_terms) *
             EvaluateStatic(e.children[1], binding, function_terms);
    case Kind::kDiv: {
      const double divisor = EvaluateStatic(e.children[1], binding, function_terms);
      return divisor == 0.0 ? kUndefinedValue
                            : EvaluateStatic(e.children[0], binding, function_terms) / divisor;
    }
  }
  return kUndefinedValue;
}

// ---- the fixpoint ---------------------------------------------------------------

namespace {

using ConditionKind = SchemaCondition::Kind;

class RelaxedExploration {
 public:
  RelaxedExploration(const SymbolTable& symbols, const CompiledSchemas& schemas,
                     const pddl::Problem& problem, GroundingContext& context)
      : symbols_(symbols),
        schemas_(schemas),
        problem_(problem),
        context_(context),
        options_(context.options()),
        atoms_of_predicate_(symbols.predicate_names.size()),
        atoms_by_argument_(symbols.predicate_names.size()) {}

  std::optional<ReachableTask> Run() {
    if (!LoadInit()) return std::nullopt;
    if (!RunFixpoint()) return std::nullopt;
    return std::move(out_);
  }

 private:
  // Makes an atom reachable (queued for the fixpoint).
  bool Reach(PredicateId predicate, std::span<const ObjectId> args) {
    const AtomId id = out_.atoms.Intern(predicate, args);
    if (queued_.size() < out_.atoms.size()) queued_.resize(out_.atoms.size(), 0);
    if (queued_[id.index()]) return true;
    if (out_.atoms.size() > options_.max_facts) {
      context_.BudgetExceeded(
          "grounding exceeds the fact budget of " + std::to_string(options_.max_facts) + " atoms",
          "a smaller problem or a larger GroundingOptions::max_facts");
      return false;
    }
    queued_[id.index()] = 1;
    queue_.push_back(id);
    return true;
  }

  // Marks a queued atom reached and adds it to the indexes the joins read.
  // False when the per-argument index would exceed its budget.
  bool Pop(AtomId id) {
    out_.atoms.MarkReached(id);
    auto key = out_.atoms.packed(id);
    const auto predicate = static_cast<std::size_t>(key[0]);
    atoms_of_predicate_[predicate].push_back(id);
    auto& index = atoms_by_argument_[predicate];
    if (index.empty() && key.size() > 1) {
      // The per-argument index costs (arity x objects) cells per predicate;
      // bounded by the fact budget so that many predicates over many objects
      // end in a diagnostic instead of exhausting memory.
      index_cells_ += (key.size() - 1) * symbols_.object_count();
      if (index_cells_ > 4 * options_.max_facts + (1u << 20)) {
        context_.BudgetExceeded(
            "grounding index exceeds the fact budget (" + std::to_string(index_cells_) + " cells)",
            "fewer predicates or objects, or a larger "
            "GroundingOptions::max_facts");
        return false;
      }
      index.assign(key.size() - 1, std::vector<std::vector<AtomId>>(symbols_.object_count()));
    }
    for (std::size_t i = 1; i < key.size(); ++i)
      index[i - 1][static_cast<std::size_t>(key[i])].push_back(id);
    return true;
  }

  bool LoadInit() {
    std::vector<ObjectId> args;
    auto convert_args = [&](const pddl::Atom& atom) {
      args.clear();
      for (const auto& t : atom.args) args.push_back(symbols_.FindObject(t.name));
    };
    for (const auto& atom : problem_.init) {
      const PredicateId predicate = symbols_.FindPredicate(atom.predicate);
      convert_args(atom);
      if (symbols_.IsStatic(predicate)) {
        bool fresh = false;
        const AtomId id = out_.atoms.Intern(predicate, args, &fresh);
        if (fresh) {
          if (!Pop(id)) return false;
          ++out_.static_true_atoms;
        }
      } else {
        out_.initial_atoms.push_back(out_.atoms.Intern(predicate, args));
        if (!Reach(predicate, args)) return false;
      }
    }
    for (const auto& til : problem_.timed_literals) {
      const PredicateId predicate = symbols_.FindPredicate(til.atom.predicate);
      convert_args(til.atom);
      out_.timed_literal_atoms.push_back(out_.atoms.Intern(predicate, args));
      if (til.positive && !Reach(predicate, args)) return false;
    }
    for (const auto& n : problem_.numeric_init) {
      args.clear();
      for (const auto& a : n.args) args.push_back(symbols_.FindObject(a));
      out_.function_terms.SetInitialValue(symbols_.FindFunction(n.function), args, n.value);
    }
    return true;
  }

  // Checks the filters of a complete binding (equalities, static literals,
  // static numeric conditions, a static duration that must be defined).
  bool PassesFilters(const PreconditionDisjunct& disjunct, const Binding& b) {
    for (const SchemaCondition* item : disjunct.items) {
      switch (item->kind) {
        case ConditionKind::kEquality: {
          const bool same = Resolve(item->args[0], b) == Resolve(item->args[1], b);
          if (same != item->positive) return false;
          break;
        }
        case ConditionKind::kAtom:
          if (!item->positive && symbols_.IsStatic(item->predicate)) {
            ResolveArgs(item->args, b);
            if (out_.atoms.IsReached(out_.atoms.Find(item->predicate, args_))) return false;
          }
          break;
        case ConditionKind::kComparison:
          if (IsStaticExpression(item->lhs, symbols_) && IsStaticExpression(item->rhs, symbols_)) {
            const double l = EvaluateStatic(item->lhs, b, out_.function_terms);
            const double r = EvaluateStatic(item->rhs, b, out_.function_terms);
            if (std::isnan(l) || std::isnan(r) || !Compare(l, ToTask(item->comparator), r))
              return false;
          }
          break;
        default:
          break;
      }
    }
    for (const auto& d : schemas_.schema_of(disjunct).duration) {
      if (IsStaticExpression(d.value, symbols_) &&
          std::isnan(EvaluateStatic(d.value, b, out_.function_terms)))
        return false;
    }
    return true;
  }

  void ResolveArgs(const std::vector<Term>& terms, const Binding& b) {
    args_.clear();
    for (Term t : terms) args_.push_back(Resolve(t, b));
  }

  // Binds `item`'s arguments against atom `id`; false on a clash or a type
  // mismatch. `bound` records which slots this call bound (for undoing).
  static bool Unify(const Schema& s, const SchemaCondition& item,
                    std::span<const std::int32_t> atom_key, Binding& b,
                    std::vector<VariableSlot>& bound) {
    for (std::size_t i = 0; i < item.args.size(); ++i) {
      const ObjectId value(atom_key[i + 1]);
      const Term term = item.args[i];
      if (!term.is_variable()) {
        if (term.object() != value) return false;
        continue;
      }
      const VariableSlot slot = term.slot();
      ObjectId& bound_value = b[slot.index()];
      if (bound_value.valid()) {
        if (bound_value != value) return false;
        continue;
      }
      if (!s.variable(slot).allowed[value.index()]) return false;
      bound_value = value;
      bound.push_back(slot);
    }
    return true;
  }

  static void Unbind(Binding& b, std::vector<VariableSlot>& bound, std::size_t mark) {
    while (bound.size() > mark) {
      b[bound.back().index()] = ObjectId::None();
      bound.pop_back();
    }
  }

  // Joins the remaining atoms of `disjunct` (done[i] set = join atom i handled).
  bool Join(const PreconditionDisjunct& disjunct, Binding& b, std::vector<VariableSlot>& bound,
            std::vector<std::uint8_t>& done, std::size_t remaining) {
    const Schema& s = schemas_.schema_of(disjunct);
    if (remaining == 0) return EnumerateFree(disjunct, b, 0);
    // Pick the most selective remaining atom.
    int best = -1;
    std::size_t best_count = std::numeric_limits<std::size_t>::max();
    const std::vector<AtomId>* best_candidates = nullptr;
    for (std::size_t i = 0; i < disjunct.join_atoms.size(); ++i) {
      if (done[i]) continue;
      const SchemaCondition& item =
          *disjunct.items[static_cast<std::size_t>(disjunct.join_atoms[i])];
      const std::size_t predicate = item.predicate.index();
      const std::vector<AtomId>* candidates = &atoms_of_predicate_[predicate];
      bool all_bound = true;
      for (std::size_t position = 0; position < item.args.size(); ++position) {
        const ObjectId value = Resolve(item.args[position], b);
        if (!value.valid()) {
          all_bound = false;
          continue;
        }
        if (atoms_by_argument_[predicate].empty()) {
          candidates = &atoms_of_predicate_[predicate];  // nothing reached for this predicate
          break;
        }
        const auto& with_value = atoms_by_argument_[predicate][position][value.index()];
        if (with_value.size() < candidates->size()) candidates = &with_value;
      }
      const std::size_t count = all_bound ? 1 : candidates->size();
      if (count < best_count) {
        best_count = count;
        best = static_cast<int>(i);
        best_candidates = all_bound ? nullptr : candidates;
      }
    }
    const auto best_index = static_cast<std::size_t>(best);
    const SchemaCondition& item =
        *disjunct.items[static_cast<std::size_t>(disjunct.join_atoms[best_index])];
    done[best_index] = 1;
    bool ok = true;
    if (best_candidates == nullptr) {
      std::vector<ObjectId> args;
      args.reserve(item.args.size());
      for (Term t : item.args) args.push_back(Resolve(t, b));
      if (out_.atoms.IsReached(out_.atoms.Find(item.predicate, args)))
        ok = Join(disjunct, b, bound, done, remaining - 1);
    } else {
      // Atoms reached by effects are popped later, so the list does not
      // grow while we iterate; iterate by index for safety.
      for (std::size_t j = 0; j < best_candidates->size() && ok; ++j) {
        if (!context_.Tick()) {
          ok = false;
          break;
        }
        const std::size_t mark = bound.size();
        if (Unify(s, item, out_.atoms.packed((*best_candidates)[j]), b, bound))
          ok = Join(disjunct, b, bound, done, remaining - 1);
        Unbind(b, bound, mark);
      }
    }
    done[best_index] = 0;
    return ok;
  }

  // Binds the variables no atom bound to every object of their type.
  bool EnumerateFree(const PreconditionDisjunct& disjunct, Binding& b, std::size_t i) {
    while (i < disjunct.free_variables.size() && b[disjunct.free_variables[i].index()].valid()) ++i;
    if (i == disjunct.free_variables.size()) return Emit(disjunct, b);
    const VariableSlot slot = disjunct.free_variables[i];
    for (ObjectId o : schemas_.schema_of(disjunct).variable(slot).objects) {
      b[slot.index()] = o;
      if (!context_.Tick() || !EnumerateFree(disjunct, b, i + 1)) {
        b[slot.index()] = ObjectId::None();
        return false;
      }
    }
    b[slot.index()] = ObjectId::None();
    return true;
  }

  // A complete binding: filter, record, and reach its add effects.
  bool Emit(const PreconditionDisjunct& disjunct, const Binding& b) {
    if (!PassesFilters(disjunct, b)) return true;
    const DisjunctId disjunct_id(static_cast<std::size_t>(&disjunct - schemas_.disjuncts.data()));
    if (!out_.instances.Insert(disjunct_id, b)) return true;
    if (out_.instances.size() > options_.max_actions) {
      context_.BudgetExceeded("grounding exceeds the action budget of " +
                                  std::to_string(options_.max_actions) + " actions",
                              "a smaller problem or a larger GroundingOptions::max_actions");
      return false;
    }
    const Schema& s = schemas_.schema_of(disjunct);
    Binding effect_binding = b;
    for (const auto& effect : s.effects) {
      if (effect.kind != SchemaEffect::Kind::kAdd) continue;
      if (!ReachEffect(s, effect, effect_binding, 0)) return false;
    }
    return true;
  }

  bool ReachEffect(const Schema& s, const SchemaEffect& effect, Binding& b, std::size_t i) {
    if (i == effect.forall_variables.size()) {
      std::vector<ObjectId> args;
      args.reserve(effect.args.size());
      for (Term t : effect.args) args.push_back(Resolve(t, b));
      for (ObjectId o : args) {
        if (!o.valid()) return true;  // unbound (exists variable used in an effect): ignore
      }
      return Reach(effect.predicate, args);
    }
    const VariableSlot slot = effect.forall_variables[i];
    for (ObjectId o : s.variable(slot).objects) {
      b[slot.index()] = o;
      if (!context_.Tick() || !ReachEffect(s, effect, b, i + 1)) return false;
    }
    b[slot.index()] = ObjectId::None();
    return true;
  }

  bool RunFixpoint() {
    // Disjuncts without fluent atoms fire once, against the static atoms;
    // the others are triggered by each of their fluent atoms.
    struct Trigger {
      DisjunctId disjunct;
      std::size_t join_atom;  // index into join_atoms
    };
    std::vector<std::vector<Trigger>> triggers(symbols_.predicate_names.size());
    for (std::size_t d = 0; d < schemas_.disjuncts.size(); ++d) {
      const PreconditionDisjunct& disjunct = schemas_.disjuncts[d];
      const Schema& s = schemas_.schema_of(disjunct);
      if (!disjunct.has_fluent_atom) {
        Binding b(s.variables.size(), ObjectId::None());
        std::vector<VariableSlot> bound;
        std::vector<std::uint8_t> done(disjunct.join_atoms.size(), 0);
        if (!Join(disjunct, b, bound, done, disjunct.join_atoms.size())) return false;
        continue;
      }
      for (std::size_t i = 0; i < disjunct.join_atoms.size(); ++i) {
        const SchemaCondition& item =
            *disjunct.items[static_cast<std::size_t>(disjunct.join_atoms[i])];
        if (!symbols_.IsStatic(item.predicate))
          triggers[item.predicate.index()].push_back({DisjunctId(d), i});
      }
    }
    Binding b;
    std::vector<VariableSlot> bound;
    std::vector<std::uint8_t> done;
    for (std::size_t head = 0; head < queue_.size(); ++head) {
      const AtomId id = queue_[head];
      if (!Pop(id)) return false;
      // Atoms whose triggers do little work never Tick: poll here too.
      if (head % 1024 == 0) context_.StopRequested();
      if (!context_.ok()) return false;
      const auto key = out_.atoms.packed(id);
      for (const Trigger& trigger : triggers[static_cast<std::size_t>(key[0])]) {
        const PreconditionDisjunct& disjunct = schemas_.disjunct(trigger.disjunct);
        const Schema& s = schemas_.schema_of(disjunct);
        b.assign(s.variables.size(), ObjectId::None());
        bound.clear();
        const SchemaCondition& item =
            *disjunct.items[static_cast<std::size_t>(disjunct.join_atoms[trigger.join_atom])];
        if (!Unify(s, item, out_.atoms.packed(id), b, bound)) continue;
        done.assign(disjunct.join_atoms.size(), 0);
        done[trigger.join_atom] = 1;
        if (!Join(disjunct, b, bound, done, disjunct.join_atoms.size() - 1)) return false;
      }
    }
    return context_.ok();
  }

  const SymbolTable& symbols_;
  const CompiledSchemas& schemas_;
  const pddl::Problem& problem_;
  GroundingContext& context_;
  const GroundingOptions& options_;
  ReachableTask out_;

  std::vector<std::uint8_t> queued_;  // by AtomId
  std::vector<AtomId> queue_;
  std::vector<std::vector<AtomId>> atoms_of_predicate_;  // reached, by PredicateId
  // Reached atoms by [predicate][argument position][object].
  std::vector<std::vector<std::vector<std::vector<AtomId>>>> atoms_by_argument_;
  std::size_t index_cells_ = 0;
  std::vector<ObjectId> args_;  // scratch
};

}  // namespace

std::optional<ReachableTask> ExploreReachability(const SymbolTable& symbols,
                                                 const CompiledSchemas& schemas,
                                                 const pddl::Problem& problem,
                                                 GroundingContext& context) {
  return RelaxedExploration(symbols, schemas, problem, context).Run();
}

}  // namespace seaplan::task::internal
