#include "server/core/service_core.h"

#include "absl/strings/str_cat.h"
#include "seaplan/common/log.h"

namespace seaplan::server {

std::string BuiltEngines() {
  std::string out;
  [[maybe_unused]] auto add = [&](const char* name) {
    absl::StrAppend(&out, out.empty() ? "" : ",", name);
  };
#if SEAPLAN_SERVER_HAS_VALIDATE
  add("validate");
#endif
#if SEAPLAN_SERVER_HAS_SEARCH
  add("search");
#endif
#if SEAPLAN_SERVER_HAS_CHART
  add("chart");
#endif
#if SEAPLAN_SERVER_HAS_ROUTE
  add("route");
#endif
#if SEAPLAN_SERVER_HAS_MISSION
  add("mission");
#endif
  return out.empty() ? "none" : out;
}

ServiceCore::ServiceCore(storage::Store& store, const CoreOptions& options,
                         std::shared_ptr<MissionEngine> mission_engine)
    : pool_(options.planning_threads),
      planning_(pool_, root_),
      charts_(store.charts(), pool_, root_),
      routes_(store.charts(), pool_, root_),
      missions_(store.missions(), pool_, root_, std::move(mission_engine), options.missions),
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
