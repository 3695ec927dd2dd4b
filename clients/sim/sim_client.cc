#include "sim_client.h"

#include "absl/strings/str_cat.h"
#include "seaplan/common/log.h"

namespace seaplan::sim {
namespace {

bool Transient(grpc::StatusCode c) {
  return c == grpc::StatusCode::UNAVAILABLE || c == grpc::StatusCode::DEADLINE_EXCEEDED ||
         c == grpc::StatusCode::RESOURCE_EXHAUSTED || c == grpc::StatusCode::ABORTED;
}

bool Terminal(v1::MissionState s) {
  return s == v1::MISSION_STATE_COMPLETED || s == v1::MISSION_STATE_FAILED ||
         s == v1::MISSION_STATE_CANCELLED;
}

}  // namespace

absl::Status FromGrpc(const grpc::Status& s) {
  if (s.ok()) return absl::OkStatus();
  return absl::Status(static_cast<absl::StatusCode>(s.error_code()), s.error_message());
}

SimClient::SimClient(const std::string& address)
    : channel_(grpc::CreateChannel(address, grpc::InsecureChannelCredentials())),
      missions_(v1::MissionService::NewStub(channel_)),
      charts_(v1::ChartService::NewStub(channel_)) {}

SimClient::~SimClient() {
  StopWatch();
}

absl::StatusOr<v1::Mission> SimClient::CreateMission(const v1::MissionSpec& spec,
                                                     const std::string& request_id) {
  v1::CreateMissionRequest req;
  *req.mutable_spec() = spec;
  req.set_request_id(request_id);
  v1::Mission out;
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(120));
  grpc::Status s = missions_->CreateMission(&ctx, req, &out);
  if (!s.ok()) return FromGrpc(s);
  return out;
}

absl::StatusOr<v1::Mission> SimClient::GetMission(const std::string& mission_id) {
  v1::GetMissionRequest req;
  req.set_mission_id(mission_id);
  v1::Mission out;
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
  grpc::Status s = missions_->GetMission(&ctx, req, &out);
  if (!s.ok()) return FromGrpc(s);
  return out;
}

absl::StatusOr<v1::Chart> SimClient::UploadChart(const std::string& name,
                                                 const std::string& file_name,
                                                 const std::string& bytes) {
  v1::UploadChartRequest req;
  req.set_name(name);
  req.set_format(v1::CHART_FORMAT_GEOJSON);
  auto* f = req.add_files();
  f->set_name(file_name);
  f->set_content(bytes);
  v1::UploadChartResponse out;
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(120));
  grpc::Status s = charts_->UploadChart(&ctx, req, &out);
  if (!s.ok()) return FromGrpc(s);
  return out.chart();
}

absl::StatusOr<v1::ReportFeedbackResponse> SimClient::Report(
    const v1::ReportFeedbackRequest& request, int attempts) {
  grpc::Status last;
  auto backoff = std::chrono::milliseconds(20);
  for (int i = 0; i < attempts; ++i) {
    v1::ReportFeedbackResponse out;
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(10));
    last = missions_->ReportFeedback(&ctx, request, &out);
    if (last.ok()) return out;
    if (!Transient(last.error_code())) break;
    log::Warn("feedback {} failed ({}), retrying with the same sequence number",
              request.sequence_number(), last.error_message());
    std::this_thread::sleep_for(backoff);
    backoff = std::min(backoff * 2, std::chrono::milliseconds(1000));
  }
  return FromGrpc(last);
}

absl::Status SimClient::ReportVesselState(const v1::ReportVesselStateRequest& request) {
  v1::ReportVesselStateResponse out;
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(2));
  return FromGrpc(missions_->ReportVesselState(&ctx, request, &out));
}

void SimClient::StartWatch(const std::string& mission_id) {
  stop_ = false;
  watcher_ = std::thread([this, mission_id] { WatchLoop(mission_id); });
}

void SimClient::StopWatch() {
  stop_ = true;
  {
    std::lock_guard<std::mutex> lock(mu_);
    if (watch_context_) watch_context_->TryCancel();
  }
  if (watcher_.joinable()) watcher_.join();
}

void SimClient::WatchLoop(std::string mission_id) {
  auto backoff = std::chrono::milliseconds(50);
  while (!stop_) {
    v1::WatchMissionRequest req;
    req.set_mission_id(mission_id);
    {
      std::lock_guard<std::mutex> lock(mu_);
      req.set_after_version(last_version_);
      req.set_after_event_id(last_event_id_);
      watch_context_ = std::make_unique<grpc::ClientContext>();
    }
    grpc::ClientContext* ctx;
    {
      std::lock_guard<std::mutex> lock(mu_);
      ctx = watch_context_.get();
    }
    auto reader = missions_->WatchMission(ctx, req);
    v1::MissionEvent ev;
    while (reader->Read(&ev)) {
      std::lock_guard<std::mutex> lock(mu_);
      switch (ev.event_case()) {
        case v1::MissionEvent::kPlanVersion:
          if (ev.plan_version().version() > last_version_) {
            last_version_ = ev.plan_version().version();
            versions_.push_back(ev.plan_version());
          }
          break;
        case v1::MissionEvent::kLog:
          if (ev.log().event_id() > last_event_id_) {
            last_event_id_ = ev.log().event_id();
            log_events_.push_back(ev.log());
          }
          break;
        case v1::MissionEvent::kMission:
          state_ = ev.mission().state();
          break;
        default:
          break;
      }
      cv_.notify_all();
    }
    grpc::Status s = reader->Finish();
    if (stop_) break;
    {
      std::lock_guard<std::mutex> lock(mu_);
      if (Terminal(state_)) break;  // the server ends the stream after a terminal state
    }
    if (s.error_code() == grpc::StatusCode::NOT_FOUND ||
        s.error_code() == grpc::StatusCode::UNIMPLEMENTED ||
        s.error_code() == grpc::StatusCode::INVALID_ARGUMENT) {
      log::Error("watch ended: {}", s.error_message());
      break;
    }
    ++reconnects_;
    std::this_thread::sleep_for(backoff);
    backoff = std::min(backoff * 2, std::chrono::milliseconds(1000));
  }
  cv_.notify_all();
}

std::optional<v1::PlanVersion> SimClient::PollVersion(int after_version) {
  std::lock_guard<std::mutex> lock(mu_);
  std::optional<v1::PlanVersion> best;
  while (!versions_.empty()) {
    if (versions_.front().version() > after_version) best = versions_.front();
    versions_.pop_front();
  }
  return best;  // the newest one: older pending versions are superseded
}

std::optional<v1::PlanVersion> SimClient::WaitForVersion(int after_version,
                                                         std::chrono::milliseconds timeout) {
  auto deadline = std::chrono::steady_clock::now() + timeout;
  while (true) {
    if (auto v = PollVersion(after_version)) return v;
    std::unique_lock<std::mutex> lock(mu_);
    if (Terminal(state_)) return std::nullopt;
    if (!versions_.empty()) continue;
    if (cv_.wait_until(lock, deadline) == std::cv_status::timeout && versions_.empty())
      return std::nullopt;
  }
}

std::vector<v1::LogEvent> SimClient::TakeLogEvents() {
  std::lock_guard<std::mutex> lock(mu_);
  std::vector<v1::LogEvent> out;
  out.swap(log_events_);
  return out;
}

v1::MissionState SimClient::terminal_state() const {
  std::lock_guard<std::mutex> lock(mu_);
  return state_;
}

}  // namespace seaplan::sim
