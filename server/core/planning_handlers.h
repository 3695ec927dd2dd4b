// PlanningService handlers (transport-agnostic): Plan, PlanStream, Validate.
//
// Each translates the request to engine values, runs the engine on the
// bounded WorkPool with the call's StopToken, and translates back. Parse
// errors are INVALID_ARGUMENT with a DiagnosticList attached
// (status_details.h); "no plan", "timeout" and "unsupported PDDL" are
// result statuses.
#pragma once

#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"
#include "seaplan/search/planner.h"
#include "seaplan/v1/planning.pb.h"
#include "server/core/call_context.h"
#include "server/core/caller_limits.h"
#include "server/core/work_pool.h"

namespace seaplan::server {

// The planner settings of a request over `base` (fields left unset or 0
// keep base's). InvalidArgument naming `field` ("options",
// "spec.planner_options") and the bad value's name within it.
absl::StatusOr<search::PlannerOptions> PlannerOptionsToEngine(const v1::PlannerOptions& o,
                                                              const char* field,
                                                              search::PlannerOptions base = {});

class PlanningHandlers {
 public:
  // `pool` and `root` outlive this; root is cancelled at shutdown.
  PlanningHandlers(WorkPool& pool, StopToken root, const RequestBudgets& budgets = {})
      : pool_(pool), root_(std::move(root)), budgets_(budgets) {}

  absl::StatusOr<v1::PlanResponse> Plan(const v1::PlanRequest& request, const CallContext& ctx);
  // Writes progress and improved plans, then exactly one final_result
  // (unless an error status is returned instead).
  absl::Status PlanStream(const v1::PlanRequest& request, const CallContext& ctx,
                          const StreamSink<v1::PlanStreamEvent>& sink);
  absl::StatusOr<v1::ValidateResponse> Validate(const v1::ValidateRequest& request,
                                                const CallContext& ctx);

 private:
  WorkPool& pool_;
  StopToken root_;
  RequestBudgets budgets_;
};

}  // namespace seaplan::server
