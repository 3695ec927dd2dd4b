// The transport-agnostic core of seaplan-server: one handler object per
// service, the bounded WorkPool and the root StopToken, shared by the gRPC
// services (server/grpc) and the HTTP/JSON gateway (server/http) so that no
// logic is written twice.
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "seaplan/common/stop_token.h"
#include "seaplan/mission/mission_engine.h"
#include "seaplan/storage/repositories.h"
#include "server/auth/authenticator.h"
#include "server/core/access_handlers.h"
#include "server/core/call_context.h"
#include "server/core/caller_limits.h"
#include "server/core/chart_handlers.h"
#include "server/core/mission_coordinator.h"
#include "server/core/planning_handlers.h"
#include "server/core/route_handlers.h"
#include "server/core/vessel_tracker.h"
#include "server/core/work_pool.h"

namespace seaplan::server {

struct CoreOptions {
  // Planning / route / chart-loading jobs running at once; more wait in a
  // queue of at most `planning_queue` calls, beyond which they get
  // RESOURCE_EXHAUSTED.
  int planning_threads = 2;
  int planning_queue = 12;
  // Per-caller rate limit of every RPC (health checks aside).
  RateLimiter::Options rate_limit;
  // What one request may ask of the engines.
  RequestBudgets budgets;
  MissionCoordinator::Options missions;
  // This process's name in the database's work leases; "" = host, pid and
  // a random part.
  std::string holder;
};

class ServiceCore {
 public:
  // `store` must outlive the core. Without `mission_engine`, the one over
  // engine/search and engine/route with the store's charts.
  ServiceCore(storage::Store& store, const CoreOptions& options,
              std::shared_ptr<mission::MissionEngine> mission_engine = nullptr);
  ~ServiceCore();
  ServiceCore(const ServiceCore&) = delete;
  ServiceCore& operator=(const ServiceCore&) = delete;

  PlanningHandlers& planning() { return planning_; }
  ChartHandlers& charts() { return charts_; }
  RouteHandlers& routes() { return routes_; }
  MissionCoordinator& missions() { return missions_; }
  VesselTracker& vessels() { return vessels_; }
  AccessHandlers& access() { return access_; }
  const auth::Authenticator& authenticator() const { return auth_; }

  // The caller of `method` ("Service/Method") from the credential the
  // transport found ("Bearer <token>"; empty when none): Unauthenticated or
  // PermissionDenied when the call must not run.
  absl::StatusOr<Caller> Authorize(std::string_view method, std::string_view authorization) const {
    return auth_.Check(method, authorization);
  }
  WorkPool& pool() { return pool_; }

  // A call's context: its token stops at `deadline` (steady clock; max() =
  // none), when `client_gone` says so, or when the server cancels all work.
  CallContext NewCall(std::string transport, StopToken::Clock::time_point deadline,
                      std::function<bool()> client_gone) const;

  // Counts the call against its caller's rate limit (ctx.caller_key):
  // ResourceExhausted with a retry-after when over it. The transports call
  // it once per call before the handler.
  absl::Status Admit(const CallContext& ctx) { return limiter_.Admit(ctx.caller_key); }

  // Shutdown, step 1: ends watch streams (clients resume elsewhere).
  void CloseStreams();
  // Shutdown, step 2 (after the grace period): stops all running work.
  void CancelAllWork();
  bool shutting_down() const { return root_.StopRequested(); }
  // Shutdown, step 3: joins the pool and the mission thread.
  void Stop();

 private:
  StopToken root_;
  auth::Authenticator auth_;
  AccessHandlers access_;
  RateLimiter limiter_;
  WorkPool pool_;
  PlanningHandlers planning_;
  ChartHandlers charts_;
  RouteHandlers routes_;
  MissionCoordinator missions_;
  VesselTracker vessels_;
};

// One log line per request: transport, method, status code, latency.
void LogCall(const std::string& transport, const std::string& method, const absl::Status& status,
             StopToken::Clock::time_point started);

}  // namespace seaplan::server
