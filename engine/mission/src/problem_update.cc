#include "seaplan/mission/problem_update.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"
#include "action_model.h"
#include "seaplan/mission/replan_policy.h"

namespace seaplan::mission {
namespace {

using internal::AtomKey;

// "(pred a b)" -> {"pred", "a", "b"}.
std::vector<std::string> SplitKey(const std::string& key) {
  std::string inner = key.substr(1, key.size() - 2);
  return absl::StrSplit(inner, ' ', absl::SkipEmpty());
}

std::string JoinKey(const std::vector<std::string>& parts) {
  return AtomKey(parts[0], std::vector<std::string>(parts.begin() + 1, parts.end()));
}

std::string UniqueName(const std::string& base, const std::set<std::string>& taken) {
  if (!taken.contains(base)) return base;
  for (int i = 2;; ++i) {
    std::string n = absl::StrCat(base, i);
    if (!taken.contains(n)) return n;
  }
}

struct TimedEvent {
  double time;
  int order;
  bool at_end;
  size_t step;
};

}  // namespace

namespace {

// Functions consumed by an effect (decrease) of `e`.
void Consumed(const pddl::Effect& e, std::set<std::string>* out) {
  if (e.kind == pddl::Effect::Kind::kNumeric && e.op == pddl::AssignOp::kDecrease &&
      e.fluent.kind == pddl::NumExpr::Kind::kFluent && e.fluent.args.size() == 1) {
    out->insert(e.fluent.function);
  }
  for (const pddl::Effect& c : e.children) Consumed(c, out);
}

// Functions whose level a comparison in `c` bounds from below.
void BoundedBelow(const pddl::Condition& c, std::set<std::string>* out) {
  if (c.kind == pddl::Condition::Kind::kCompare) {
    const bool lhs_floor = c.comparator == pddl::Comparator::kGreaterEqual ||
                           c.comparator == pddl::Comparator::kGreater;
    const bool rhs_floor =
        c.comparator == pddl::Comparator::kLessEqual || c.comparator == pddl::Comparator::kLess;
    const pddl::NumExpr* level = lhs_floor ? &c.lhs : rhs_floor ? &c.rhs : nullptr;
    if (level && level->kind == pddl::NumExpr::Kind::kFluent && level->args.size() == 1)
      out->insert(level->function);
  }
  for (const pddl::Condition& child : c.children) BoundedBelow(child, out);
}

}  // namespace

std::string PlannedFuelFunction(std::string_view domain_text) {
  pddl::DomainParseResult d = pddl::ParseDomain(domain_text);
  if (!d.domain) return "";
  std::set<std::string> consumed, bounded;
  for (const pddl::Action& a : d.domain->actions) {
    Consumed(a.effect, &consumed);
    BoundedBelow(a.condition, &bounded);
  }
  for (const pddl::FunctionDecl& f : d.domain->functions) {
    if (f.parameters.size() == 1 && consumed.contains(f.name) && bounded.contains(f.name))
      return f.name;
  }
  return "";
}

Status RegenerationOptions::Validate() const {
  if (location_predicate.empty())
    return absl::InvalidArgumentError("regeneration: location_predicate is empty");
  if (!(snap_distance_m >= 0))
    return absl::InvalidArgumentError("regeneration: snap_distance_m must be >= 0");
  if (new_location_name.empty())
    return absl::InvalidArgumentError("regeneration: new_location_name is empty");
  if (!(fuel_threshold_fraction >= 0 && fuel_threshold_fraction <= 1)) {
    return absl::InvalidArgumentError("regeneration: fuel_threshold_fraction must be in [0, 1]");
  }
  return absl::OkStatus();
}

StatusOr<RegeneratedProblem> RegenerateProblem(std::string_view domain_text,
                                               std::string_view problem_text,
                                               const std::vector<validate::PlanStep>& completed,
                                               const std::vector<validate::PlanStep>& interrupted,
                                               const LocationTable& locations,
                                               const ShipObservation& ship,
                                               const RegenerationOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  SEAPLAN_ASSIGN_OR_RETURN(auto model, internal::ActionModel::Create(domain_text, problem_text));
  const pddl::Problem& problem = model.problem();

  // 1. Apply the executed prefix in time order (starts before ends at a tie:
  //    a step that starts when another ends was scheduled epsilon later).
  internal::WorldState state = model.InitialState();
  std::vector<internal::ActionInstance> inst;
  std::vector<TimedEvent> events;
  std::vector<const validate::PlanStep*> steps;
  for (const auto* list : {&completed, &interrupted}) {
    for (const validate::PlanStep& s : *list) {
      auto a = model.Instantiate(s.name, s.args);
      if (!a.ok()) return a.status();
      size_t idx = inst.size();
      inst.push_back(std::move(*a));
      steps.push_back(&s);
      events.push_back({s.start_s, 0, false, idx});
      if (list == &completed) events.push_back({s.end_s(), 1, true, idx});
    }
  }
  std::stable_sort(events.begin(), events.end(), [](const TimedEvent& a, const TimedEvent& b) {
    return a.time != b.time ? a.time < b.time : a.order > b.order;  // ends first at a tie
  });
  for (const TimedEvent& e : events) {
    SEAPLAN_RETURN_IF_ERROR(model.Apply(inst[e.step], e.at_end, steps[e.step]->duration_s, &state));
  }

  // 2. The ship object.
  std::string ship_obj = options.ship_object;
  if (ship_obj.empty()) {
    auto ships = model.ObjectsOfType("ship");
    if (ships.empty()) {
      return absl::InvalidArgumentError("regeneration: no object of type ship; set ship_object");
    }
    ship_obj = ships.front();
  }

  // Objects of the problem and their types.
  std::vector<std::pair<std::string, std::string>> objects;  // name, type text
  std::set<std::string> taken;
  for (const pddl::TypedName& o : problem.objects) {
    objects.emplace_back(
        o.name, o.types.size() == 1 ? o.types[0] : "(either " + absl::StrJoin(o.types, " ") + ")");
    taken.insert(o.name);
  }
  for (const pddl::TypedName& c : model.domain().constants) taken.insert(c.name);

  // 3. Where the ship is: snap or add a new location.
  RegeneratedProblem out;
  out.locations = locations;
  std::string nearest;
  double nearest_d = std::numeric_limits<double>::infinity();
  for (const auto& [name, pos] : locations) {
    if (!taken.contains(name)) continue;  // a location this problem does not have
    double d = Distance(pos, ship.position);
    if (d < nearest_d) {
      nearest_d = d;
      nearest = name;
    }
  }
  if (nearest.empty()) {
    return absl::FailedPreconditionError(
        "regeneration: no location of the problem has a known position");
  }
  std::string here = nearest;
  if (nearest_d > options.snap_distance_m) {
    here = UniqueName(options.new_location_name, taken);
    taken.insert(here);
    out.added_location = true;
    out.locations[here] = ship.position;
    const std::string& tmpl = nearest;
    objects.emplace_back(here, model.TypeOf(tmpl));

    // Static numeric fluents by object, for length-carrying objects.
    std::map<std::string, std::vector<std::string>> numeric_by_object;  // object -> fluent keys
    for (const auto& [key, value] : state.fluents) {
      auto parts = SplitKey(key);
      if (!model.IsStaticFunction(parts[0])) continue;
      for (size_t i = 1; i < parts.size(); ++i) numeric_by_object[parts[i]].push_back(key);
    }
    auto is_location = [&](const std::string& o) {
      return locations.contains(o) && taken.contains(o);
    };

    std::set<std::string> new_facts;
    std::map<std::string, double> new_fluents;
    std::map<std::string, std::string> cloned_objects;  // "<orig>|<new atom locations>" -> new name
    std::vector<std::pair<std::string, std::string>> clone_origin;  // new object, original
    auto clone_atom = [&](std::vector<std::string> parts, const std::string& other) {
      // parts: the static atom with tmpl; other: location replaced by tmpl ("" = none).
      for (size_t i = 1; i < parts.size(); ++i) {
        if (parts[i] == tmpl) {
          parts[i] = here;
        } else if (!other.empty() && parts[i] == other) {
          parts[i] = tmpl;
        }
      }
      std::vector<std::string> locs;
      for (size_t i = 1; i < parts.size(); ++i) {
        if (parts[i] == here || is_location(parts[i])) locs.push_back(parts[i]);
      }
      if (!other.empty() && std::count(locs.begin(), locs.end(), tmpl) == 0) return;
      // Old endpoints for the scale factor.
      for (size_t i = 1; i < parts.size(); ++i) {
        const std::string& o = parts[i];
        if (o == here || is_location(o) || o == ship_obj) continue;
        auto nb = numeric_by_object.find(o);
        if (nb == numeric_by_object.end()) continue;
        std::string key = o + "|" + absl::StrJoin(locs, ",");
        auto [it, inserted] = cloned_objects.try_emplace(key, "");
        if (inserted) {
          it->second = UniqueName(absl::StrCat("r-", absl::StrJoin(locs, "-")), taken);
          taken.insert(it->second);
          objects.emplace_back(it->second, model.TypeOf(o));
          clone_origin.emplace_back(it->second, o);
          // Scale the static values by new distance / old distance.
          std::vector<std::string> old_locs;
          old_locs.reserve(locs.size());
          // The original atom's locations: undo the substitution.
          for (const std::string& l : locs) {
            old_locs.push_back(l == here ? tmpl : (l == tmpl && !other.empty() ? other : l));
          }
          double scale = 1.0;
          if (locs.size() == 2) {
            double d_new = Distance(out.locations.at(locs[0]), out.locations.at(locs[1]));
            double d_old = Distance(out.locations.at(old_locs[0]), out.locations.at(old_locs[1]));
            scale = d_old > 1e-9 ? d_new / d_old : 0.0;
          }
          for (const std::string& fk : nb->second) {
            auto fparts = SplitKey(fk);
            for (size_t k = 1; k < fparts.size(); ++k) {
              if (fparts[k] == o) fparts[k] = it->second;
            }
            double v = state.fluents.at(fk);
            double nv = v * scale;
            if (locs.size() == 2 && !(scale > 0)) {
              nv = Distance(out.locations.at(locs[0]), out.locations.at(locs[1]));
            }
            new_fluents[JoinKey(fparts)] = nv;
          }
        }
        parts[i] = it->second;
      }
      new_facts.insert(JoinKey(parts));
    };

    for (const std::string& f : state.facts) {
      auto parts = SplitKey(f);
      if (!model.IsStaticPredicate(parts[0])) continue;
      if (std::find(parts.begin() + 1, parts.end(), tmpl) == parts.end()) continue;
      clone_atom(parts, "");
      for (size_t i = 1; i < parts.size(); ++i) {
        if (parts[i] != tmpl && is_location(parts[i])) clone_atom(parts, parts[i]);
      }
    }
    // Static facts of the cloned objects that name no location ((route_available r)).
    for (const auto& [clone, orig] : clone_origin) {
      for (const std::string& f : state.facts) {
        auto parts = SplitKey(f);
        if (!model.IsStaticPredicate(parts[0])) continue;
        bool mentions = false, has_loc = false;
        for (size_t i = 1; i < parts.size(); ++i) {
          mentions |= parts[i] == orig;
          has_loc |= is_location(parts[i]);
        }
        if (!mentions || has_loc) continue;
        for (size_t i = 1; i < parts.size(); ++i) {
          if (parts[i] == orig) parts[i] = clone;
        }
        new_facts.insert(JoinKey(parts));
      }
    }
    // Static numeric fluents of the template location itself ((distance a b)
    // kind), once with T -> new and once per other location X with X -> T.
    for (const auto& [key, value] : state.fluents) {
      auto parts = SplitKey(key);
      if (!model.IsStaticFunction(parts[0])) continue;
      if (std::find(parts.begin() + 1, parts.end(), tmpl) == parts.end()) continue;
      std::vector<std::string> variants = {""};
      for (size_t i = 1; i < parts.size(); ++i) {
        if (parts[i] != tmpl && is_location(parts[i])) variants.push_back(parts[i]);
      }
      for (const std::string& other : variants) {
        std::vector<std::string> locs_old, locs_new, np = parts;
        for (size_t i = 1; i < np.size(); ++i) {
          if (is_location(np[i])) locs_old.push_back(np[i]);
          if (np[i] == tmpl) {
            np[i] = here;
          } else if (!other.empty() && np[i] == other) {
            np[i] = tmpl;
          }
          if (np[i] == here || is_location(np[i])) locs_new.push_back(np[i]);
        }
        double v = value;
        if (locs_old.size() == 2 && locs_new.size() == 2) {
          double d_old = Distance(out.locations.at(locs_old[0]), out.locations.at(locs_old[1]));
          double d_new = Distance(out.locations.at(locs_new[0]), out.locations.at(locs_new[1]));
          v = d_old > 1e-9 ? value * d_new / d_old : d_new;
        }
        new_fluents[JoinKey(np)] = v;
      }
    }
    state.facts.insert(new_facts.begin(), new_facts.end());
    for (auto& [k, v] : new_fluents) state.fluents[k] = v;
  }

  // 4. Put the ship there.
  for (auto it = state.facts.begin(); it != state.facts.end();) {
    auto parts = SplitKey(*it);
    if (parts.size() == 3 && parts[0] == options.location_predicate && parts[1] == ship_obj) {
      it = state.facts.erase(it);
    } else {
      ++it;
    }
  }
  state.facts.insert(AtomKey(options.location_predicate, {ship_obj, here}));
  out.ship_location = here;

  // 5. Fuel.
  // The (fuel ?v) flags follow the tank only in domains where they gate
  // actions (executor fuel, case C); in case A (no_fuel ?v) is a mission
  // goal ("refuel at E"), not a tank reading, and is left to the plan.
  const bool fuel_gates_actions = !options.fuel_predicate.empty() &&
                                  model.PredicateInConditions(options.fuel_predicate) &&
                                  model.domain().FindPredicate(options.fuel_predicate);
  const std::string& fuel_function = options.fuel_function;
  if (ship.fuel_fraction) {
    const bool low = FuelAtOrBelow(*ship.fuel_fraction, options.fuel_threshold_fraction);
    const pddl::Domain& d = model.domain();
    if (fuel_gates_actions) {
      std::string k = AtomKey(options.fuel_predicate, {ship_obj});
      if (low)
        state.facts.erase(k);
      else
        state.facts.insert(k);
    }
    if (fuel_gates_actions && !options.no_fuel_predicate.empty() &&
        d.FindPredicate(options.no_fuel_predicate)) {
      std::string k = AtomKey(options.no_fuel_predicate, {ship_obj});
      if (low)
        state.facts.insert(k);
      else
        state.facts.erase(k);
    }
    if (!fuel_function.empty() && d.FindFunction(fuel_function)) {
      state.fluents[AtomKey(fuel_function, {ship_obj})] =
          *ship.fuel_fraction * options.fuel_function_full;
    }
  }

  out.goal_satisfied = model.GoalHolds(state);

  // 6. Print.
  std::ostringstream p;
  p << "(define (problem " << problem.name << ")\n  (:domain " << problem.domain_name << ")\n";
  p << "  (:objects";
  for (const auto& [name, type] : objects) p << "\n    " << name << " - " << type;
  p << ")\n  (:init";
  for (const std::string& f : state.facts) p << "\n    " << f;
  for (const auto& [k, v] : state.fluents)
    p << "\n    (= " << k << " " << validate::FormatTime(v) << ")";
  p << ")\n  (:goal " << internal::ToPddl(problem.goal) << ")\n";
  if (problem.metric.present) {
    p << "  (:metric " << (problem.metric.minimize ? "minimize " : "maximize ")
      << internal::ToPddl(problem.metric.expression) << ")\n";
  }
  p << ")\n";
  out.problem_text = p.str();
  return out;
}

}  // namespace seaplan::mission
