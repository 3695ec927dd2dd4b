#include "seaplan/mission/refine.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>
#include <set>

#include "absl/strings/str_cat.h"
#include "action_model.h"
#include "seaplan/common/log.h"
#include "seaplan/task/grounder.h"
#include "seaplan/validate/validator.h"

namespace seaplan::mission {
namespace {

// Event b of step j must come at least epsilon after event a of step i:
// start_j + (b_end ? d_j : 0) >= start_i + (a_end ? d_i : 0) + epsilon.
struct OrderEdge {
  int from_step;
  bool from_end;
  int to_step;
  bool to_end;
};

bool Intersects(const std::set<std::string>& a, const std::set<std::string>& b) {
  const auto& small = a.size() < b.size() ? a : b;
  const auto& large = a.size() < b.size() ? b : a;
  for (const std::string& x : small) {
    if (large.contains(x)) return true;
  }
  return false;
}

struct EventSets {
  std::set<std::string> reads, writes;
};

EventSets SetsOf(const internal::ActionInstance& a, bool end) {
  EventSets s;
  s.reads = end ? a.reads_end : a.reads_start;
  s.reads.insert(a.reads_overall.begin(), a.reads_overall.end());
  s.writes = end ? a.writes_end : a.writes_start;
  return s;
}

bool Interfere(const EventSets& a, const EventSets& b) {
  return Intersects(a.writes, b.reads) || Intersects(a.writes, b.writes) ||
         Intersects(a.reads, b.writes);
}

// The partial order of `plan`: one edge per interfering pair of events, in
// the order the plan has them (ties broken by step order).
StatusOr<std::vector<OrderEdge>> LiftOrder(const internal::ActionModel& model,
                                           const validate::Plan& plan) {
  const int n = static_cast<int>(plan.steps.size());
  std::vector<internal::ActionInstance> inst;
  inst.reserve(n);
  for (int i = 0; i < n; ++i) {
    auto a = model.Instantiate(plan.steps[i].name, plan.steps[i].args);
    if (!a.ok()) {
      return absl::InvalidArgumentError(absl::StrCat(
          "plan step ", i + 1, " ", plan.steps[i].DisplayName(), ": ", a.status().message()));
    }
    inst.push_back(std::move(*a));
  }
  std::vector<std::array<EventSets, 2>> sets(n);
  for (int i = 0; i < n; ++i) sets[i] = {SetsOf(inst[i], false), SetsOf(inst[i], true)};
  constexpr double kTie = 1e-9;
  std::vector<OrderEdge> edges;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      if (i == j) continue;
      for (int ae = 0; ae < 2; ++ae) {
        for (int be = 0; be < 2; ++be) {
          double ta = ae ? plan.steps[i].end_s() : plan.steps[i].start_s;
          double tb = be ? plan.steps[j].end_s() : plan.steps[j].start_s;
          bool before = ta < tb - kTie || (std::abs(ta - tb) <= kTie && i < j);
          if (before && Interfere(sets[i][ae], sets[j][be])) {
            edges.push_back({i, ae == 1, j, be == 1});
          }
        }
      }
    }
  }
  return edges;
}

// Earliest start times satisfying `edges` and start >= origin (Bellman-Ford
// longest paths; a positive cycle means the order cannot be kept).
StatusOr<std::vector<double>> Schedule(const std::vector<OrderEdge>& edges,
                                       const std::vector<double>& durations, double origin,
                                       double epsilon) {
  const size_t n = durations.size();
  std::vector<double> start(n, origin);
  for (size_t round = 0; round <= n; ++round) {
    bool changed = false;
    for (const OrderEdge& e : edges) {
      double need = start[e.from_step] + (e.from_end ? durations[e.from_step] : 0.0) + epsilon -
                    (e.to_end ? durations[e.to_step] : 0.0);
      if (need > start[e.to_step] + 1e-12) {
        start[e.to_step] = need;
        changed = true;
      }
    }
    if (!changed) return start;
  }
  return absl::FailedPreconditionError(
      "the refined durations make the plan's order impossible (an action would have to end "
      "before another that it contains); replan instead");
}

double EarliestStart(const validate::Plan& plan) {
  double origin = plan.steps.empty() ? 0.0 : plan.steps[0].start_s;
  for (const auto& s : plan.steps) origin = std::min(origin, s.start_s);
  return origin;
}

// A numeric expression over fluent values (nullopt: undefined or ?duration).
std::optional<double> EvalDuration(const pddl::NumExpr& e, const internal::Binding& binding,
                                   const std::map<std::string, double>& fluents) {
  using Kind = pddl::NumExpr::Kind;
  switch (e.kind) {
    case Kind::kNumber:
      return e.value;
    case Kind::kFluent: {
      std::vector<std::string> args;
      for (const pddl::Term& t : e.args) {
        auto it = binding.find(t.name);
        args.push_back(it != binding.end() ? it->second : t.name);
      }
      auto it = fluents.find(internal::AtomKey(e.function, args));
      if (it == fluents.end()) return std::nullopt;
      return it->second;
    }
    case Kind::kNeg: {
      if (e.children.empty()) return std::nullopt;
      auto v = EvalDuration(e.children[0], binding, fluents);
      if (!v) return std::nullopt;
      return -*v;
    }
    case Kind::kAdd:
    case Kind::kSub:
    case Kind::kMul:
    case Kind::kDiv:
      break;
    default:
      return std::nullopt;
  }
  if (e.children.empty()) return std::nullopt;
  auto acc = EvalDuration(e.children[0], binding, fluents);
  for (size_t i = 1; acc && i < e.children.size(); ++i) {
    auto v = EvalDuration(e.children[i], binding, fluents);
    if (!v || (e.kind == Kind::kDiv && *v == 0.0)) return std::nullopt;
    if (e.kind == Kind::kAdd) *acc += *v;
    if (e.kind == Kind::kSub) *acc -= *v;
    if (e.kind == Kind::kMul) *acc *= *v;
    if (e.kind == Kind::kDiv) *acc /= *v;
  }
  return acc;
}

// Keys ("(distance port-a port-b)") of the fluents an expression reads.
void FluentKeys(const pddl::NumExpr& e, const internal::Binding& binding,
                std::vector<std::pair<std::string, std::string>>* out) {
  if (e.kind == pddl::NumExpr::Kind::kFluent) {
    std::vector<std::string> args;
    for (const pddl::Term& t : e.args) {
      auto it = binding.find(t.name);
      args.push_back(it != binding.end() ? it->second : t.name);
    }
    out->emplace_back(e.function, internal::AtomKey(e.function, args));
  }
  for (const pddl::NumExpr& c : e.children) FluentKeys(c, binding, out);
}

// The problem with the refined durations, and the plan checked against it.
//  * A move whose duration is `(= ?duration expr)` with expr proportional to
//    a static fluent (the fjord's (distance ?from ?to), a (route-length ?r))
//    gets that fluent scaled so that expr gives the route's sailing time: the
//    route's length in the problem's own units, so effects reading it (fuel
//    use) see the route too.
//  * Where that is impossible (no such fluent, or one leg sailed twice with
//    different times) and for port operations with measured durations, the
//    action's duration constraint is lifted: its duration is the one given.
// Everything else (conditions, effects, mutual exclusion, the goal) is
// checked by engine/validate as for any plan.
Status ValidateRefined(const internal::ActionModel& model, const validate::Plan& plan,
                       const std::vector<bool>& is_move, const std::set<std::string>& overridden,
                       double epsilon_s) {
  const pddl::Domain& domain = model.domain();
  pddl::Domain checked_domain = domain;
  pddl::Problem problem = model.problem();
  std::map<std::string, double> fluents;
  for (const pddl::NumericInit& n : problem.numeric_init) {
    fluents[internal::AtomKey(n.function, n.args)] = n.value;
  }
  std::map<std::string, double> scaled;  // key -> new value
  std::set<std::string> lifted(overridden.begin(), overridden.end());
  for (size_t i = 0; i < plan.steps.size(); ++i) {
    if (!is_move[i]) continue;
    const validate::PlanStep& step = plan.steps[i];
    const pddl::Action* action = domain.FindAction(step.name);
    if (action == nullptr || action->parameters.size() != step.args.size()) continue;
    internal::Binding binding;
    for (size_t k = 0; k < step.args.size(); ++k) {
      binding[action->parameters[k].name] = step.args[k];
    }
    bool done = false;
    for (const pddl::DurationConstraint& c : action->duration) {
      if (done || c.comparator != pddl::Comparator::kEqual) continue;
      const std::optional<double> model_s = EvalDuration(c.value, binding, fluents);
      if (!model_s || !(*model_s > 0.0)) continue;
      std::vector<std::pair<std::string, std::string>> keys;
      FluentKeys(c.value, binding, &keys);
      for (const auto& [function, key] : keys) {
        if (done || !model.IsStaticFunction(function)) continue;
        std::map<std::string, double> doubled = fluents;
        doubled[key] *= 2.0;
        const std::optional<double> twice = EvalDuration(c.value, binding, doubled);
        if (!twice || std::abs(*twice - 2.0 * *model_s) > 1e-9 * *model_s) continue;
        const double value = fluents[key] * step.duration_s / *model_s;
        auto [it, fresh] = scaled.emplace(key, value);
        if (!fresh && std::abs(it->second - value) > 1e-9 * std::max(1.0, std::abs(value))) {
          break;  // the same leg at two different times: lift instead
        }
        done = true;
      }
    }
    if (!done) lifted.insert(step.name);
  }
  for (pddl::NumericInit& n : problem.numeric_init) {
    auto it = scaled.find(internal::AtomKey(n.function, n.args));
    if (it != scaled.end()) n.value = it->second;
  }
  for (pddl::Action& a : checked_domain.actions) {
    if (lifted.contains(a.name)) a.duration.clear();
  }
  const task::LoadResult loaded = task::Ground(checked_domain, problem);
  if (!loaded.ok()) {
    return absl::InternalError(absl::StrCat(
        "the problem with the routes' durations does not ground: ", loaded.ErrorText()));
  }
  validate::ValidationOptions options;
  options.epsilon_s = epsilon_s;
  const validate::ValidationResult result = validate::ValidatePlan(*loaded.task, plan, options);
  if (!result.valid) {
    return absl::FailedPreconditionError(
        absl::StrCat("the plan refined with route durations is not valid against the problem "
                     "with those durations: ",
                     result.ToString()));
  }
  return absl::OkStatus();
}

}  // namespace

RoutePlanner StraightLineRouter(double speed_mps) {
  return [speed_mps](const RouteRequest& r) -> StatusOr<Route> {
    if (!(speed_mps > 0))
      return absl::InvalidArgumentError("straight-line router: speed must be > 0");
    Route route;
    double length = Distance(r.from_position, r.to_position);
    route.length_m = length;
    route.sailing_time_s = length / speed_mps;
    RouteWaypoint a, b;
    a.position = r.from_position;
    b.position = r.to_position;
    b.eta_s = route.sailing_time_s;
    b.distance_from_start_m = length;
    route.waypoints = {a, b};
    return route;
  };
}

std::optional<MoveLeg> RecognizeMove(const validate::PlanStep& step, const LocationTable& locations,
                                     const MoveRecognition& recognition) {
  bool named = std::find(recognition.move_actions.begin(), recognition.move_actions.end(),
                         step.name) != recognition.move_actions.end();
  if (!named && !recognition.by_arguments) return std::nullopt;
  std::string from, to;
  for (const std::string& a : step.args) {
    if (!locations.contains(a)) continue;
    if (from.empty()) {
      from = a;
    } else if (a != from) {
      to = a;
    }
  }
  if (from.empty() || to.empty()) return std::nullopt;
  return MoveLeg{from, to};
}

Status RefineOptions::Validate() const {
  if (!(epsilon_s >= 0)) return absl::InvalidArgumentError("refine: epsilon_s must be >= 0");
  if (max_iterations < 1) return absl::InvalidArgumentError("refine: max_iterations must be >= 1");
  if (!(tolerance_s >= 0)) return absl::InvalidArgumentError("refine: tolerance_s must be >= 0");
  for (const auto& [name, d] : port_operation_durations_s) {
    if (!(d >= 0)) {
      return absl::InvalidArgumentError(
          absl::StrCat("refine: duration of ", name, " must be >= 0"));
    }
  }
  return absl::OkStatus();
}

StatusOr<validate::Plan> Reschedule(std::string_view domain_text, std::string_view problem_text,
                                    const validate::Plan& plan,
                                    const std::vector<double>& durations_s, double epsilon_s) {
  if (durations_s.size() != plan.steps.size()) {
    return absl::InvalidArgumentError("reschedule: one duration per plan step is needed");
  }
  SEAPLAN_ASSIGN_OR_RETURN(auto model, internal::ActionModel::Create(domain_text, problem_text));
  SEAPLAN_ASSIGN_OR_RETURN(auto edges, LiftOrder(model, plan));
  SEAPLAN_ASSIGN_OR_RETURN(auto starts,
                           Schedule(edges, durations_s, EarliestStart(plan), epsilon_s));
  validate::Plan out = plan;
  for (size_t i = 0; i < out.steps.size(); ++i) {
    out.steps[i].start_s = starts[i];
    out.steps[i].duration_s = durations_s[i];
  }
  return out;
}

StatusOr<RefinedPlan> RefinePlan(std::string_view domain_text, std::string_view problem_text,
                                 const validate::Plan& plan, const LocationTable& locations,
                                 const RoutePlanner& route_planner, const RefineOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  if (!route_planner) return absl::InvalidArgumentError("refine: no route planner given");
  SEAPLAN_ASSIGN_OR_RETURN(auto model, internal::ActionModel::Create(domain_text, problem_text));
  SEAPLAN_ASSIGN_OR_RETURN(auto edges, LiftOrder(model, plan));
  const size_t n = plan.steps.size();
  const double origin = EarliestStart(plan);

  std::vector<std::optional<MoveLeg>> legs(n);
  std::vector<double> durations(n);
  for (size_t i = 0; i < n; ++i) {
    const validate::PlanStep& s = plan.steps[i];
    durations[i] = s.duration_s;
    if (auto it = options.port_operation_durations_s.find(s.name);
        it != options.port_operation_durations_s.end()) {
      durations[i] = it->second;
    }
    legs[i] = RecognizeMove(s, locations, options.moves);
    bool named = std::find(options.moves.move_actions.begin(), options.moves.move_actions.end(),
                           s.name) != options.moves.move_actions.end();
    if (named && !legs[i]) {
      return absl::InvalidArgumentError(
          absl::StrCat("plan step ", i + 1, " ", s.DisplayName(),
                       " is a move but does not name two locations with known positions"));
    }
  }

  // The first move from where the ship is under way starts with its motion.
  size_t under_way_step = n;  // n: none
  if (options.under_way) {
    for (size_t i = 0; i < n; ++i) {
      if (legs[i] && legs[i]->from == options.under_way->location &&
          (under_way_step == n || plan.steps[i].start_s < plan.steps[under_way_step].start_s)) {
        under_way_step = i;
      }
    }
    // Only when the plan starts with it: after a port operation there the
    // ship leaves from rest.
    for (size_t i = 0; i < n && under_way_step < n; ++i) {
      if (!legs[i] &&
          plan.steps[i].start_s + options.epsilon_s < plan.steps[under_way_step].start_s) {
        under_way_step = n;
      }
    }
  }

  RefinedPlan result;
  std::vector<std::optional<Route>> routes(n);
  std::vector<double> starts(n);
  for (size_t i = 0; i < n; ++i) starts[i] = plan.steps[i].start_s;
  for (int iter = 1; iter <= options.max_iterations; ++iter) {
    for (size_t i = 0; i < n; ++i) {
      if (!legs[i]) continue;
      RouteRequest req{plan.steps[i].name,
                       legs[i]->from,
                       legs[i]->to,
                       locations.find(legs[i]->from)->second,
                       locations.find(legs[i]->to)->second,
                       starts[i]};
      if (under_way_step == i) req.start_motion = options.under_way->motion;
      StatusOr<Route> route = route_planner(req);
      if (!route.ok()) {
        if (absl::IsNotFound(route.status()) || absl::IsFailedPrecondition(route.status())) {
          return absl::FailedPreconditionError(
              absl::StrCat("no safe route for leg ", req.from, " -> ", req.to, " (", req.action,
                           ", step ", i + 1, "): ", route.status().message()));
        }
        return route.status();
      }
      if (!(route->sailing_time_s >= 0) || !std::isfinite(route->sailing_time_s)) {
        return absl::InternalError(
            absl::StrCat("route for leg ", req.from, " -> ", req.to, " has no valid sailing time"));
      }
      durations[i] = route->sailing_time_s;
      routes[i] = std::move(*route);
    }
    SEAPLAN_ASSIGN_OR_RETURN(auto next, Schedule(edges, durations, origin, options.epsilon_s));
    double moved = 0.0;
    for (size_t i = 0; i < n; ++i) moved = std::max(moved, std::abs(next[i] - starts[i]));
    starts = std::move(next);
    result.iterations = iter;
    // The first pass always moves things (durations changed); settle when a
    // pass with the routes recomputed at the new departure times changes nothing.
    if (iter > 1 && moved <= options.tolerance_s) break;
    if (iter == options.max_iterations) {
      log::Warn("refine: start times still moving by {:.3f} s after {} passes", moved, iter);
    }
  }

  // Steps sorted by start time (stable), routes alongside.
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return starts[a] < starts[b]; });
  std::vector<bool> is_move;
  for (size_t k : order) {
    validate::PlanStep s = plan.steps[k];
    s.start_s = starts[k];
    s.duration_s = durations[k];
    result.makespan_s = std::max(result.makespan_s, s.end_s());
    result.plan.steps.push_back(std::move(s));
    result.routes.push_back(routes[k]);
    is_move.push_back(legs[k].has_value());
  }
  std::set<std::string> overridden;
  for (const auto& [name, d] : options.port_operation_durations_s) overridden.insert(name);
  SEAPLAN_RETURN_IF_ERROR(
      ValidateRefined(model, result.plan, is_move, overridden, options.epsilon_s));
  return result;
}

}  // namespace seaplan::mission
