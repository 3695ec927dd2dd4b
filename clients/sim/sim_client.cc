#include "sim_client.h"

#include <algorithm>
#include <random>

#include "absl/strings/str_cat.h"
#include "seaplan/common/log.h"
#include "seaplan/common/wall_clock.h"
#include "token_channel.h"

namespace seaplan::sim {
namespace {

// Retry pacing towards the shore: exponential, capped, with jitter so that
// many ships coming back after one outage do not retry in step.
constexpr auto kFirstBackoff = std::chrono::milliseconds(100);
constexpr auto kMaxBackoff = std::chrono::milliseconds(5000);

// A uniformly random duration in [backoff / 2, backoff].
std::chrono::milliseconds Jittered(std::chrono::milliseconds backoff) {
  thread_local std::mt19937 rng{std::random_device{}()};
  std::uniform_int_distribution<std::int64_t> pick(backoff.count() / 2, backoff.count());
  return std::chrono::milliseconds(pick(rng));
}

std::chrono::milliseconds Next(std::chrono::milliseconds backoff) {
  return std::min(backoff * 2, std::chrono::duration_cast<std::chrono::milliseconds>(kMaxBackoff));
}

// gRPC's own reconnection backoff grows to 120 s by default: a ship would
// then stay deaf long after the shore is back. Keep it short. Not
// GRPC_ARG_MIN_RECONNECT_BACKOFF_MS: gRPC takes it as the time a connection
// attempt has to receive the server's HTTP/2 SETTINGS (default 20 s), and
// at 200 ms a loaded balancer missed it and the first call failed.
std::shared_ptr<grpc::Channel> MakeChannel(
    const std::string& address, const std::shared_ptr<grpc::ChannelCredentials>& credentials,
    const std::string& token) {
  grpc::ChannelArguments args;
  args.SetInt(GRPC_ARG_INITIAL_RECONNECT_BACKOFF_MS, 200);
  args.SetInt(GRPC_ARG_MAX_RECONNECT_BACKOFF_MS, 2000);
  return client::CreateChannelWithToken(address, credentials, args, token);
}

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

SimClient::SimClient(const std::string& address,
                     const std::shared_ptr<grpc::ChannelCredentials>& credentials,
                     const std::string& token)
    : channel_(MakeChannel(address, credentials, token)),
      missions_(v1::MissionService::NewStub(channel_)),
      charts_(v1::ChartService::NewStub(channel_)) {}

SimClient::~SimClient() {
  StopUplink();
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

grpc::Status SimClient::PostFeedback(const v1::ReportFeedbackRequest& request,
                                     v1::ReportFeedbackResponse* response) {
  grpc::ClientContext ctx;
  // Longer in slower builds: a report that times out is taken for a shore
  // outage, and the ship sails on without waiting for the replan it asks for.
  ctx.set_deadline(std::chrono::system_clock::now() +
                   ScaledWallClock(std::chrono::milliseconds(5000)));
  return missions_->ReportFeedback(&ctx, request, response);
}

absl::Status SimClient::StartUplink(const std::string& journal_path) {
  auto journal = FeedbackJournal::Open(journal_path);
  if (!journal.ok()) return journal.status();
  std::lock_guard<std::mutex> lock(uplink_mu_);
  for (const JournalEntry& e : journal->unacknowledged_at_open()) {
    v1::ReportFeedbackRequest r;
    if (!r.ParseFromString(e.payload)) {
      return absl::DataLossError(
          absl::StrCat(journal_path, ": report ", e.sequence, " is not a ReportFeedbackRequest"));
    }
    outbox_.push_back(std::move(r));
  }
  if (!outbox_.empty()) {
    log::Warn("feedback journal {}: re-sending {} reports an earlier run left unacknowledged",
              journal_path, outbox_.size());
  }
  // Sequence numbers are per vessel across every mission the server has
  // seen, so a run starts above any earlier one: microseconds since the
  // epoch, and above anything in the journal.
  const std::int64_t now_us = std::chrono::duration_cast<std::chrono::microseconds>(
                                  std::chrono::system_clock::now().time_since_epoch())
                                  .count();
  next_sequence_ = std::max(now_us, journal->max_sequence() + 1);
  replayed_until_ = journal->max_sequence();
  journal_.emplace(std::move(*journal));
  uplink_stop_ = false;
  uplink_ = std::thread([this] { UplinkLoop(); });
  return absl::OkStatus();
}

absl::Status SimClient::Send(std::vector<v1::ReportFeedbackRequest> reports) {
  std::lock_guard<std::mutex> lock(uplink_mu_);
  if (!journal_) return absl::FailedPreconditionError("the feedback uplink is not started");
  std::vector<JournalEntry> entries;
  for (v1::ReportFeedbackRequest& r : reports) {
    r.set_sequence_number(next_sequence_++);
    entries.push_back({r.sequence_number(), r.SerializeAsString()});
  }
  // On disk before it may reach the shore: a report the server stored is
  // always in the journal, so a restarted client can tell what it sent.
  if (absl::Status st = journal_->Append(entries); !st.ok()) return st;
  for (v1::ReportFeedbackRequest& r : reports) outbox_.push_back(std::move(r));
  uplink_cv_.notify_all();
  return absl::OkStatus();
}

bool SimClient::WaitSent(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(uplink_mu_);
  uplink_cv_.wait_for(lock, timeout,
                      [&] { return outbox_.empty() || shore_unreachable_ || uplink_stop_; });
  return outbox_.empty();
}

std::vector<FeedbackAck> SimClient::TakeAcks() {
  std::lock_guard<std::mutex> lock(uplink_mu_);
  std::vector<FeedbackAck> out;
  out.swap(acks_);
  return out;
}

absl::Status SimClient::uplink_error() const {
  std::lock_guard<std::mutex> lock(uplink_mu_);
  return uplink_error_;
}

size_t SimClient::backlog() const {
  std::lock_guard<std::mutex> lock(uplink_mu_);
  return outbox_.size();
}

void SimClient::StopUplink() {
  {
    std::lock_guard<std::mutex> lock(uplink_mu_);
    uplink_stop_ = true;
  }
  uplink_cv_.notify_all();
  if (uplink_.joinable()) uplink_.join();
}

void SimClient::UplinkLoop() {
  auto backoff = std::chrono::duration_cast<std::chrono::milliseconds>(kFirstBackoff);
  auto lost_at = std::chrono::steady_clock::now();
  int failures = 0;
  while (true) {
    v1::ReportFeedbackRequest request;
    {
      std::unique_lock<std::mutex> lock(uplink_mu_);
      uplink_cv_.wait(lock, [&] { return uplink_stop_ || !outbox_.empty(); });
      if (uplink_stop_) return;
      request = outbox_.front();
    }
    v1::ReportFeedbackResponse response;
    const grpc::Status s = PostFeedback(request, &response);
    std::unique_lock<std::mutex> lock(uplink_mu_);
    if (!s.ok() && Transient(s.error_code())) {
      if (!shore_unreachable_) {
        lost_at = std::chrono::steady_clock::now();
        log::Warn(
            "shore link lost: report {} failed ({}: {}); executing on, {} reports kept in {} and "
            "retried with backoff",
            request.sequence_number(), static_cast<int>(s.error_code()), s.error_message(),
            outbox_.size(), journal_->path());
      }
      shore_unreachable_ = true;
      ++failures;
      uplink_cv_.notify_all();
      uplink_cv_.wait_for(lock, Jittered(backoff), [&] { return uplink_stop_; });
      backoff = Next(backoff);
      continue;
    }
    if (shore_unreachable_) {
      const double down_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - lost_at).count();
      log::Warn("shore link back after {:.1f} s ({} failed attempts): sending the {} reports kept",
                down_s, failures, outbox_.size());
      shore_unreachable_ = false;
    }
    failures = 0;
    backoff = std::chrono::duration_cast<std::chrono::milliseconds>(kFirstBackoff);
    outbox_.pop_front();
    // Refused reports are acknowledged too: re-sending them cannot succeed.
    if (absl::Status st = journal_->Acknowledge(request.sequence_number()); !st.ok())
      log::Warn("{} (the report may be re-sent after a restart)", st.ToString());
    if (s.ok()) {
      acks_.push_back({std::move(request), std::move(response)});
    } else if (s.error_code() == grpc::StatusCode::FAILED_PRECONDITION ||
               request.sequence_number() <= replayed_until_) {
      // The mission finished meanwhile, or a report of an earlier run the
      // server no longer takes: nothing to do with it.
      log::Warn("report {} of mission {} refused and dropped: {}", request.sequence_number(),
                request.mission_id(), s.error_message());
    } else {
      log::Error("report {} of mission {} refused: {}", request.sequence_number(),
                 request.mission_id(), s.error_message());
      if (uplink_error_.ok()) {
        const absl::Status refused = FromGrpc(s);
        uplink_error_ =
            absl::Status(refused.code(), absl::StrCat("ReportFeedback: ", refused.message()));
      }
    }
    uplink_cv_.notify_all();
  }
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
  auto backoff = std::chrono::duration_cast<std::chrono::milliseconds>(kFirstBackoff);
  bool broken = false;  // the stream broke and has not delivered since
  int attempts = 0;
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
      if (broken) {
        log::Warn("shore link: watch of mission {} resumed from version {}, event {} ({} attempts)",
                  mission_id, req.after_version(), req.after_event_id(), attempts);
        broken = false;
        attempts = 0;
        backoff = std::chrono::duration_cast<std::chrono::milliseconds>(kFirstBackoff);
      }
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
        s.error_code() == grpc::StatusCode::INVALID_ARGUMENT ||
        s.error_code() == grpc::StatusCode::UNAUTHENTICATED ||
        s.error_code() == grpc::StatusCode::PERMISSION_DENIED) {
      log::Error("watch ended: {}", s.error_message());
      break;
    }
    if (!broken) {
      log::Warn(
          "shore link: watch of mission {} broken ({}); reconnecting from version {}, event {}",
          mission_id, s.error_message(), req.after_version(), req.after_event_id());
    }
    broken = true;
    ++attempts;
    ++reconnects_;
    std::this_thread::sleep_for(Jittered(backoff));
    backoff = Next(backoff);
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
