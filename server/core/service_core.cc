#include "server/core/service_core.h"

#include "absl/strings/str_cat.h"
#include "seaplan/common/log.h"
#include "server/core/route_convert.h"

namespace seaplan::server {

ServiceCore::ServiceCore(storage::Store& store, const CoreOptions& options,
                         std::shared_ptr<mission::MissionEngine> mission_engine)
    : auth_(store.tokens()),
      access_(auth_, store.tokens(), store.audit()),
      limiter_(options.rate_limit),
      pool_(options.planning_threads, options.planning_queue),
      planning_(pool_, root_, options.budgets),
      charts_(store.charts(), pool_, root_,
              [this](const std::string& chart_id) { missions_.ForgetChart(chart_id); }),
      routes_(store.charts(), pool_, root_, options.budgets),
      missions_(store.missions(), pool_, root_,
                mission_engine
                    ? std::move(mission_engine)
                    : mission::MakeMissionEngine([&charts = store.charts()](const std::string& id) {
                        return LoadMap(charts, id);
                      }),
                options.missions,
                MissionCoordinator::Cluster{&store.work(), &store.changes(), options.holder}),
      vessels_(store.missions()) {}

ServiceCore::~ServiceCore() {
  Stop();
}

CallContext ServiceCore::NewCall(std::string transport, StopToken::Clock::time_point deadline,
                                 std::function<bool()> client_gone) const {
  return CallContext{std::move(transport), root_.Child(deadline), std::move(client_gone)};
}

void ServiceCore::CloseStreams() {
  missions_.notifier().Close();
  vessels_.Close();
}

void ServiceCore::CancelAllWork() {
  root_.Cancel();
}

void ServiceCore::Stop() {
  CloseStreams();
  CancelAllWork();
  missions_.Shutdown();
  pool_.Shutdown();
}

void LogCall(const std::string& transport, const std::string& method, const absl::Status& status,
             StopToken::Clock::time_point started) {
  const double ms =
      std::chrono::duration<double, std::milli>(StopToken::Clock::now() - started).count();
  const std::string code = absl::StatusCodeToString(status.code());
  if (status.ok()) {
    log::Info("request transport={} method={} code={} latency_ms={:.1f}", transport, method, code,
              ms);
  } else {
    log::Info("request transport={} method={} code={} latency_ms={:.1f} error=\"{}\"", transport,
              method, code, ms, std::string(status.message()));
  }
}

}  // namespace seaplan::server
