#include "server/core/planning_handlers.h"

#include <cstdio>
#include <deque>
#include <mutex>

#include "absl/strings/str_cat.h"
#include "seaplan/search/planner.h"
#include "seaplan/task/grounder.h"
#include "seaplan/validate/plan.h"
#include "seaplan/validate/validator.h"
#include "server/core/convert.h"
#include "server/core/status_details.h"

namespace seaplan::server {
namespace {

absl::Status CheckPddlInputs(const std::string& domain, const std::string& problem) {
  if (domain.empty()) return absl::InvalidArgumentError("domain: the PDDL domain text is empty");
  if (problem.empty()) return absl::InvalidArgumentError("problem: the PDDL problem text is empty");
  return absl::OkStatus();
}

bool HasInputErrors(const std::vector<pddl::Diagnostic>& diagnostics) {
  for (const auto& d : diagnostics) {
    if (d.severity == pddl::Severity::kError && d.kind != pddl::DiagnosticKind::kUnsupported)
      return true;
  }
  return false;
}

// INVALID_ARGUMENT naming the first error, with every diagnostic attached.
absl::Status MalformedPddl(const task::LoadResult& loaded) {
  std::string first;
  int errors = 0;
  for (const auto& d : loaded.diagnostics) {
    if (d.severity != pddl::Severity::kError) continue;
    if (errors++ == 0) first = d.ToString();
  }
  return WithDiagnostics(
      absl::InvalidArgumentError(absl::StrCat(
          "malformed PDDL (", errors, errors == 1 ? " error): " : " errors), first: ", first)),
      ToProto(loaded.diagnostics));
}

// ParsePlan says "plan line L, column C: ..."; keep the location structured.
v1::Diagnostic PlanDiagnostic(const absl::Status& status) {
  v1::Diagnostic d;
  d.set_severity(v1::Diagnostic::ERROR);
  d.set_kind(v1::Diagnostic::SYNTAX);
  d.set_file("plan");
  int line = 0, column = 0;
  const std::string message(status.message());
  if (std::sscanf(message.c_str(), "plan line %d, column %d", &line, &column) >= 1) {
    d.set_line(line);
    d.set_column(column);
  }
  d.set_message(message);
  return d;
}

v1::PlanStatus StatusToProto(search::PlanStatus s) {
  switch (s) {
    case search::PlanStatus::kSolvedSatisficing:
      return v1::SOLVED_SATISFICING;
    case search::PlanStatus::kSolvedOptimally:
      return v1::SOLVED_OPTIMALLY;
    case search::PlanStatus::kUnsolvableProven:
      return v1::UNSOLVABLE_PROVEN;
    case search::PlanStatus::kTimeout:
      return v1::TIMEOUT;
    case search::PlanStatus::kMemout:
      return v1::MEMOUT;
    case search::PlanStatus::kUnsupported:
      return v1::UNSUPPORTED;
    case search::PlanStatus::kCancelled:
      return v1::CANCELLED;
    case search::PlanStatus::kError:
      return v1::PLAN_STATUS_UNSPECIFIED;
  }
  return v1::PLAN_STATUS_UNSPECIFIED;
}

void StatsToProto(const search::SearchStatistics& s, v1::SearchStatistics* out) {
  out->set_expanded(s.expanded);
  out->set_generated(s.generated);
  out->set_evaluated(s.evaluated);
  out->set_search_time_s(s.search_time_s);
  out->set_first_plan_time_s(s.first_plan_time_s);
  out->set_best_plan_time_s(s.best_plan_time_s);
  out->set_peak_memory_mb(s.peak_memory_mb);
  out->set_plans_found(s.plans_found);
  out->set_symmetric_objects(static_cast<std::uint32_t>(s.symmetric_objects));
  out->set_symmetry_classes(static_cast<std::uint32_t>(s.symmetry_classes));
  out->set_symmetric_drops(s.symmetric_drops);
  out->set_eager_ends(s.eager_ends);
  out->set_first_plan_restarts(static_cast<std::uint32_t>(s.first_plan_restarts));
  out->set_seed_rounds(static_cast<std::uint32_t>(s.seed_rounds));
  out->set_seed_round_plans(static_cast<std::uint32_t>(s.seed_round_plans));
  out->set_suffix_searches(static_cast<std::uint32_t>(s.suffix_searches));
  out->set_suffix_plans(static_cast<std::uint32_t>(s.suffix_plans));
}

void FillPlan(const search::PlanResult& r, v1::PlanResponse* out) {
  out->set_status(StatusToProto(r.status));
  out->clear_plan();
  for (const auto& step : r.plan.steps) {
    v1::TimedAction* a = out->add_plan();
    a->set_start_s(step.start_s);
    a->set_duration_s(step.duration_s);
    a->set_name(step.name);
    for (const auto& arg : step.args) a->add_arguments(arg);
  }
  out->set_makespan_s(r.makespan_s);
  if (r.metric_value)
    out->set_metric_value(*r.metric_value);
  else
    out->clear_metric_value();
  StatsToProto(r.stats, out->mutable_statistics());
  out->set_plan_text(r.plan.steps.empty() ? std::string() : validate::FormatPlan(r.plan));
  out->set_message(r.message);
}

void GroundingStatsToProto(const task::GroundingStats& in, v1::SearchStatistics* out) {
  out->set_grounding_time_s((in.parse_ms + in.ground_ms) / 1000.0);
  out->set_ground_facts(in.size.facts);
  out->set_ground_numeric_variables(in.size.numeric_vars);
  out->set_ground_actions(in.size.actions);
  v1::GroundingStatistics* stages = out->mutable_grounding();
  stages->set_parse_s(in.parse_ms / 1000.0);
  stages->set_symbols_s(in.stages.symbols_ms / 1000.0);
  stages->set_schemas_s(in.stages.schemas_ms / 1000.0);
  stages->set_reachability_s(in.stages.reachability_ms / 1000.0);
  stages->set_instantiation_s(in.stages.instantiation_ms / 1000.0);
  stages->set_reachable_atoms(in.reachable_atoms);
  stages->set_static_atoms(in.static_atoms);
}

// One planning run on a worker thread. `observer` may be null.
struct PlanRun {
  absl::Status status;
  v1::PlanResponse response;
};

PlanRun RunPlanner(const v1::PlanRequest& request, const search::PlannerOptions& options,
                   const StopToken& stop, const search::PlanObserver* observer) {
  PlanRun run;
  task::LoadResult loaded =
      task::LoadTask(request.domain(), request.problem(), task::GroundingOptions{},
                     search::WithinTimeLimit(options, stop));
  // Memory, the limit or the caller ended grounding: a result, not an error.
  const std::optional<search::PlanResult> unfinished = search::UnfinishedLoadResult(loaded);
  if (unfinished) {
    run.response.set_status(StatusToProto(unfinished->status));
    run.response.set_message(unfinished->message);
    if (loaded.memory_ran_out) return run;  // nothing was counted
  }
  v1::SearchStatistics* stats = run.response.mutable_statistics();
  GroundingStatsToProto(loaded.stats, stats);
  for (const auto& d : loaded.diagnostics) *run.response.add_diagnostics() = ToProto(d);
  if (unfinished) {
    StatsToProto(search::SearchStatistics{}, stats);  // no search: no plan times
    return run;
  }
  if (HasInputErrors(loaded.diagnostics)) {
    run.status = MalformedPddl(loaded);
    return run;
  }
  if (!loaded.ok()) {  // only unsupported features: a result, not an error
    run.response.set_status(v1::UNSUPPORTED);
    run.response.set_message(loaded.ErrorText());
    return run;
  }
  search::PlanResult result = search::SolveTask(*loaded.task, options, stop, observer);
  FillPlan(result, &run.response);
  GroundingStatsToProto(loaded.stats, stats);
  if (result.status == search::PlanStatus::kError) {
    run.status = absl::InvalidArgumentError(absl::StrCat("planner: ", result.message));
  }
  return run;
}

// The request's planner options, within the server's budgets.
absl::StatusOr<search::PlannerOptions> PlannerOptionsWithin(const v1::PlannerOptions& options,
                                                            const RequestBudgets& budgets) {
  SEAPLAN_ASSIGN_OR_RETURN(search::PlannerOptions p, PlannerOptionsToEngine(options, "options"));
  if (p.time_limit_s > budgets.max_plan_time_s) {
    return absl::InvalidArgumentError(absl::StrCat("options.time_limit: ", p.time_limit_s,
                                                   " s is more than this server allows (",
                                                   budgets.max_plan_time_s, " s)"));
  }
  if (p.memory_limit_mb > budgets.max_plan_memory_mb) {
    return absl::InvalidArgumentError(absl::StrCat("options.memory_limit_mb: ", p.memory_limit_mb,
                                                   " MB is more than this server allows (",
                                                   budgets.max_plan_memory_mb, " MB)"));
  }
  return p;
}

}  // namespace

absl::StatusOr<search::PlannerOptions> PlannerOptionsToEngine(const v1::PlannerOptions& o,
                                                              const char* field,
                                                              search::PlannerOptions p) {
  if (o.has_time_limit()) {
    SEAPLAN_ASSIGN_OR_RETURN(
        double s, DurationSeconds(o.time_limit(), absl::StrCat(field, ".time_limit").c_str()));
    if (s > 0) p.time_limit_s = s;
  }
  if (o.memory_limit_mb() != 0) p.memory_limit_mb = o.memory_limit_mb();
  if (o.max_concurrent_actions() < 0) {
    return absl::InvalidArgumentError(
        absl::StrCat(field, ".max_concurrent_actions must not be negative"));
  }
  p.max_concurrent_actions = o.max_concurrent_actions();
  if (o.has_anytime()) p.anytime = o.anytime();
  if (o.has_type_based_exploration()) p.type_based_exploration = o.type_based_exploration();
  if (o.has_landmarks()) p.landmarks = o.landmarks();
  if (o.has_symmetry_reduction()) p.symmetry_reduction = o.symmetry_reduction();
  if (o.has_eager_ends()) p.eager_ends = o.eager_ends();
  if (o.has_second_greedy_after_share()) {
    p.second_greedy_after_share = o.second_greedy_after_share();
  }
  if (o.has_seed_rounds_share()) p.seed_rounds_share = o.seed_rounds_share();
  if (o.has_suffix_search_share()) p.suffix_search_share = o.suffix_search_share();
  if (o.random_seed() != 0) p.random_seed = o.random_seed();
  if (o.epsilon_s() != 0) p.epsilon_s = o.epsilon_s();
  p.max_expansions = o.max_expansions();
  if (o.has_cpu_time_limit()) {
    SEAPLAN_ASSIGN_OR_RETURN(
        p.cpu_time_limit_s,
        DurationSeconds(o.cpu_time_limit(), absl::StrCat(field, ".cpu_time_limit").c_str()));
  }
  absl::Status valid = p.Validate();
  if (!valid.ok()) return absl::InvalidArgumentError(absl::StrCat(field, ": ", valid.message()));
  return p;
}

absl::StatusOr<v1::PlanResponse> PlanningHandlers::Plan(const v1::PlanRequest& request,
                                                        const CallContext& ctx) {
  SEAPLAN_RETURN_IF_ERROR(CheckPddlInputs(request.domain(), request.problem()));
  SEAPLAN_ASSIGN_OR_RETURN(search::PlannerOptions options,
                           PlannerOptionsWithin(request.options(), budgets_));
  PlanRun run;
  SEAPLAN_RETURN_IF_ERROR(pool_.Run([&] { run = RunPlanner(request, options, ctx.stop, nullptr); },
                                    ctx.stop, [&] { ctx.ForwardCancellation(); }));
  if (ctx.stop.StopRequested()) return StopStatus(ctx.stop, root_.StopRequested(), "planning");
  if (!run.status.ok()) return run.status;
  return run.response;
}

absl::Status PlanningHandlers::PlanStream(const v1::PlanRequest& request, const CallContext& ctx,
                                          const StreamSink<v1::PlanStreamEvent>& sink) {
  SEAPLAN_RETURN_IF_ERROR(CheckPddlInputs(request.domain(), request.problem()));
  SEAPLAN_ASSIGN_OR_RETURN(search::PlannerOptions options,
                           PlannerOptionsWithin(request.options(), budgets_));
  // The planner's callbacks run on the worker; they queue events and the
  // RPC thread writes them (tick), so only one thread writes to the client.
  std::mutex mu;
  std::deque<v1::PlanStreamEvent> pending;
  const auto started = std::chrono::steady_clock::now();
  search::PlanObserver observer;
  observer.on_plan = [&](const search::PlanResult& r) {
    v1::PlanStreamEvent event;
    FillPlan(r, event.mutable_improved_plan());
    std::lock_guard lock(mu);
    pending.push_back(std::move(event));
  };
  observer.on_progress = [&](const search::SearchStatistics& s) {
    v1::PlanStreamEvent event;
    StatsToProto(s, event.mutable_progress()->mutable_statistics());
    event.mutable_progress()->set_elapsed_s(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
    std::lock_guard lock(mu);
    pending.push_back(std::move(event));
  };
  bool client_ok = true;
  auto drain = [&] {
    ctx.ForwardCancellation();
    std::deque<v1::PlanStreamEvent> batch;
    {
      std::lock_guard lock(mu);
      batch.swap(pending);
    }
    for (const auto& event : batch) {
      if (client_ok && !sink(event)) {
        client_ok = false;
        ctx.stop.Cancel();
      }
    }
  };
  PlanRun run;
  SEAPLAN_RETURN_IF_ERROR(
      pool_.Run([&] { run = RunPlanner(request, options, ctx.stop, &observer); }, ctx.stop, drain));
  if (ctx.stop.StopRequested()) return StopStatus(ctx.stop, root_.StopRequested(), "planning");
  if (!run.status.ok()) return run.status;
  v1::PlanStreamEvent final_event;
  *final_event.mutable_final_result() = std::move(run.response);
  if (!sink(final_event)) return absl::CancelledError("planning stream: the client went away");
  return absl::OkStatus();
}

absl::StatusOr<v1::ValidateResponse> PlanningHandlers::Validate(const v1::ValidateRequest& request,
                                                                const CallContext& ctx) {
  SEAPLAN_RETURN_IF_ERROR(CheckPddlInputs(request.domain(), request.problem()));
  if (request.epsilon_s() < 0) return absl::InvalidArgumentError("epsilon_s must not be negative");
  auto plan = validate::ParsePlan(request.plan());
  if (!plan.ok()) {
    v1::DiagnosticList list;
    *list.add_diagnostics() = PlanDiagnostic(plan.status());
    return WithDiagnostics(absl::InvalidArgumentError(plan.status().message()), list);
  }
  absl::Status status;
  v1::ValidateResponse response;
  SEAPLAN_RETURN_IF_ERROR(pool_.Run(
      [&] {
        task::LoadResult loaded =
            task::LoadTask(request.domain(), request.problem(), task::GroundingOptions{}, ctx.stop);
        if (loaded.stopped()) return;  // reported below, as for planning
        if (loaded.memory_ran_out) {
          status = absl::ResourceExhaustedError(
              "memory ran out (an allocation failed) grounding the task to validate against");
          return;
        }
        for (const auto& d : loaded.diagnostics) *response.add_diagnostics() = ToProto(d);
        if (HasInputErrors(loaded.diagnostics)) {
          status = MalformedPddl(loaded);
          return;
        }
        if (!loaded.ok()) {
          status = WithDiagnostics(
              absl::UnimplementedError(absl::StrCat(
                  "the input uses PDDL seaplan does not support: ", loaded.ErrorText())),
              ToProto(loaded.diagnostics));
          return;
        }
        validate::ValidationOptions options;
        if (request.epsilon_s() > 0) options.epsilon_s = request.epsilon_s();
        options.explain_missing_action = validate::ExplainerFor(loaded);
        const validate::ValidationResult r = validate::ValidatePlan(*loaded.task, *plan, options);
        response.set_valid(r.valid);
        response.set_makespan_s(r.makespan_s);
        response.set_action_count(static_cast<std::int32_t>(r.action_count));
        if (r.metric_value) response.set_metric_value(*r.metric_value);
        if (r.first_failure) {
          v1::ValidationFailure* f = response.mutable_first_failure();
          f->set_time_s(r.first_failure->time_s);
          f->set_step_index(r.first_failure->step_index);
          f->set_action(r.first_failure->action);
          f->set_condition(r.first_failure->condition);
          f->set_reason(absl::StrCat(validate::KindName(r.first_failure->kind), ": ",
                                     r.first_failure->reason));
        }
      },
      ctx.stop, [&] { ctx.ForwardCancellation(); }));
  if (ctx.stop.StopRequested()) return StopStatus(ctx.stop, root_.StopRequested(), "validation");
  if (!status.ok()) return status;
  return response;
}

}  // namespace seaplan::server
