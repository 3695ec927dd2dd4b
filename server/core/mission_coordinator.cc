#include "server/core/mission_coordinator.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "seaplan/common/log.h"
#include "seaplan/mission/mission_state.h"
#include "server/core/caller_limits.h"
#include "server/core/convert.h"

namespace seaplan::server {
namespace {

constexpr char kServerSource[] = "server";

const char* StateName(int state) {
  return v1::MissionState_IsValid(state)
             ? v1::MissionState_Name(static_cast<v1::MissionState>(state)).c_str()
             : "MISSION_STATE_UNKNOWN";
}

storage::NewLogEvent ServerEvent(std::string message, double mission_time_s = 0.0) {
  return {NowMs(), mission_time_s, kServerSource, std::move(message)};
}

std::string DescribeVersion(const v1::PlanVersion& v) {
  return absl::StrFormat("plan version %d ready (%s): %d tasks, makespan %.3f s", v.version(),
                         v.reason(), v.tasks_size(), v.makespan_s());
}

std::string DescribeFeedback(const v1::Feedback& f) {
  std::string text = v1::Feedback::Kind_Name(f.kind());
  if (!f.task_id().empty()) absl::StrAppend(&text, " task ", f.task_id());
  if (!f.detail().empty()) absl::StrAppend(&text, ": ", f.detail());
  return text;
}

}  // namespace

bool IsFinalState(int state) {
  return mission::IsFinal(MissionStateFromProto(state));
}

v1::Mission MissionFromRecord(const storage::MissionRecord& r) {
  v1::Mission m;
  m.set_mission_id(r.id);
  m.mutable_spec()->ParseFromString(r.spec);
  m.set_state(static_cast<v1::MissionState>(r.state));
  m.set_current_version(r.current_version);
  *m.mutable_created_at() = ToTimestamp(r.created_at_ms);
  *m.mutable_updated_at() = ToTimestamp(r.updated_at_ms);
  if (!r.last_state.empty()) m.mutable_last_state()->ParseFromString(r.last_state);
  for (const auto& t : r.completed_tasks) m.add_completed_tasks(t);
  m.set_failure_reason(r.failure_reason);
  return m;
}

// ---- MissionNotifier ----

std::uint64_t MissionNotifier::Generation(const std::string& mission_id) {
  std::lock_guard lock(mu_);
  return generation_[mission_id];
}

void MissionNotifier::Notify(const std::string& mission_id) {
  {
    std::lock_guard lock(mu_);
    ++generation_[mission_id];
  }
  cv_.notify_all();
}

std::uint64_t MissionNotifier::Wait(const std::string& mission_id, std::uint64_t seen,
                                    std::chrono::milliseconds timeout) {
  std::unique_lock lock(mu_);
  cv_.wait_for(lock, timeout, [&] { return closed_ || generation_[mission_id] != seen; });
  return generation_[mission_id];
}

void MissionNotifier::Close() {
  {
    std::lock_guard lock(mu_);
    closed_ = true;
  }
  cv_.notify_all();
}

bool MissionNotifier::closed() {
  std::lock_guard lock(mu_);
  return closed_;
}

// ---- MissionCoordinator ----

MissionCoordinator::MissionCoordinator(storage::MissionRepository& repo, WorkPool& pool,
                                       StopToken root,
                                       std::shared_ptr<mission::MissionEngine> engine,
                                       Options options)
    : repo_(repo),
      pool_(pool),
      root_(std::move(root)),
      adapter_(std::move(engine)),
      options_(options) {
  // A mission left REPLANNING by a process that died (killed, crashed)
  // has no replan running anywhere: queue one, or its ship waits forever.
  // A replan of the same base by another replica cannot append twice
  // (AppendVersion checks current + 1).
  std::int64_t after = 0;
  while (true) {
    auto page = repo_.List(v1::MISSION_STATE_REPLANNING, 1000, after);
    if (!page.ok()) {
      log::Error("missions left replanning not resumed: {}", page.status().ToString());
      break;
    }
    for (const storage::MissionRecord& m : page->items) {
      log::Warn("mission {}: resuming the replan of version {} interrupted by a restart", m.id,
                m.current_version);
      jobs_.push_back({m.id, "replan resumed after a server restart", m.current_version});
    }
    if (page->next_after == 0) break;  // the last page
    after = page->next_after;
  }
  background_ = std::thread([this] { BackgroundLoop(); });
}

MissionCoordinator::~MissionCoordinator() {
  Shutdown();
}

void MissionCoordinator::Shutdown() {
  notifier_.Close();
  {
    std::lock_guard lock(jobs_mu_);
    stopping_ = true;
    for (auto& [id, token] : running_replans_) token.Cancel();
  }
  jobs_cv_.notify_all();
  if (background_.joinable()) background_.join();
}

std::shared_ptr<std::mutex> MissionCoordinator::MissionLock(const std::string& mission_id) {
  std::lock_guard lock(locks_mu_);
  auto& m = locks_[mission_id];
  if (!m) m = std::make_shared<std::mutex>();
  return m;
}

absl::StatusOr<MissionRuntimeState> MissionCoordinator::LoadRuntime(const std::string& mission_id) {
  MissionRuntimeState state;
  SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(mission_id));
  state.mission = MissionFromRecord(record);
  if (record.current_version > 0) {
    SEAPLAN_ASSIGN_OR_RETURN(storage::PlanVersionRecord v,
                             repo_.GetVersion(mission_id, record.current_version));
    if (!state.current_version.ParseFromString(v.content)) {
      return absl::DataLossError(
          absl::StrCat("plan version ", v.version, " of mission '", mission_id, "' is unreadable"));
    }
    state.engine_state = std::move(v.engine_state);
  }
  SEAPLAN_ASSIGN_OR_RETURN(auto feedback,
                           repo_.ListFeedback(mission_id, options_.feedback_history));
  for (const auto& f : feedback) state.recent_feedback.emplace_back().ParseFromString(f.payload);
  return state;
}

absl::Status MissionCoordinator::SetState(const std::string& mission_id,
                                          mission::MissionState state, const std::string& message,
                                          const std::string& failure_reason) {
  storage::MissionUpdate update;
  update.state = MissionStateToProto(state);
  if (!failure_reason.empty()) update.failure_reason = failure_reason;
  absl::Status st = repo_.Update(mission_id, update, {ServerEvent(message)});
  notifier_.Notify(mission_id);
  return st;
}

void MissionCoordinator::EndReplanning(const std::string& mission_id, const std::string& message) {
  auto lock_ptr = MissionLock(mission_id);
  std::lock_guard lock(*lock_ptr);
  auto record = repo_.Get(mission_id);
  if (!record.ok()) return;
  if (MissionStateFromProto(record->state) == mission::MissionState::kReplanning) {
    (void)SetState(mission_id, mission::MissionState::kActive, message);
    return;
  }
  // Cancelled (or finished) meanwhile: keep that state, log the outcome.
  (void)repo_.AppendEvents(mission_id, {ServerEvent(message)});
  notifier_.Notify(mission_id);
}

absl::StatusOr<v1::Mission> MissionCoordinator::CreateMission(
    const v1::CreateMissionRequest& request, const CallContext& ctx) {
  const v1::MissionSpec& spec = request.spec();
  if (!request.request_id().empty()) {
    SEAPLAN_ASSIGN_OR_RETURN(auto existing, repo_.FindByRequestId(request.request_id()));
    if (existing) return MissionFromRecord(*existing);  // a retry of a create that succeeded
  }
  if (spec.domain().empty())
    return absl::InvalidArgumentError("spec.domain: the PDDL domain text is empty");
  if (spec.problem().empty())
    return absl::InvalidArgumentError("spec.problem: the PDDL problem text is empty");
  SEAPLAN_RETURN_IF_ERROR(adapter_.CheckSpec(spec));
  absl::StatusOr<PlannedVersion> planned = absl::UnknownError("mission planning did not run");
  SEAPLAN_RETURN_IF_ERROR(pool_.Run([&] { planned = adapter_.PlanInitial(spec, ctx.stop); },
                                    ctx.stop, [&] { ctx.ForwardCancellation(); }));
  if (ctx.stop.StopRequested())
    return StopStatus(ctx.stop, root_.StopRequested(), "mission planning");
  if (!planned.ok()) return planned.status();

  const std::int64_t now = NowMs();
  storage::MissionRecord record;
  record.id = NewId("m-");
  record.name = spec.name();
  record.vessel_id = spec.vessel_id();
  record.request_id = request.request_id();
  record.spec = spec.SerializeAsString();
  record.state = MissionStateToProto(mission::MissionState::kActive);
  record.current_version = 1;
  record.created_at_ms = now;
  record.updated_at_ms = now;
  if (spec.has_initial_state()) record.last_state = spec.initial_state().SerializeAsString();

  v1::PlanVersion& version = planned->version;
  version.set_mission_id(record.id);
  version.set_version(1);
  if (version.reason().empty()) version.set_reason("initial plan");
  *version.mutable_created_at() = ToTimestamp(now);

  std::vector<storage::NewLogEvent> events;
  events.push_back(ServerEvent(absl::StrCat("mission created: ", spec.name())));
  for (const auto& line : planned->log_messages) events.push_back(ServerEvent(line));
  events.push_back(ServerEvent(DescribeVersion(version), version.mission_time_origin_s()));
  absl::Status st = repo_.Create(
      record,
      {record.id, 1, version.reason(), now, version.SerializeAsString(), planned->engine_state},
      events);
  if (absl::IsAlreadyExists(st) && !request.request_id().empty()) {
    // A concurrent retry with the same key won: answer with its mission.
    SEAPLAN_ASSIGN_OR_RETURN(auto existing, repo_.FindByRequestId(request.request_id()));
    if (existing) return MissionFromRecord(*existing);
  }
  SEAPLAN_RETURN_IF_ERROR(st);
  notifier_.Notify(record.id);
  return MissionFromRecord(record);
}

absl::StatusOr<v1::Mission> MissionCoordinator::GetMission(const v1::GetMissionRequest& request,
                                                           const CallContext&) {
  if (request.mission_id().empty()) return absl::InvalidArgumentError("mission_id is empty");
  SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(request.mission_id()));
  return MissionFromRecord(record);
}

absl::StatusOr<v1::ListMissionsResponse> MissionCoordinator::ListMissions(
    const v1::ListMissionsRequest& request, const CallContext&) {
  SEAPLAN_ASSIGN_OR_RETURN(int page_size, PageSize(request.page_size()));
  SEAPLAN_ASSIGN_OR_RETURN(std::int64_t after, ParsePageToken(request.page_token()));
  SEAPLAN_ASSIGN_OR_RETURN(auto page, repo_.List(request.state(), page_size, after));
  v1::ListMissionsResponse response;
  for (const auto& r : page.items) *response.add_missions() = MissionFromRecord(r);
  response.set_next_page_token(MakePageToken(page.next_after));
  return response;
}

absl::StatusOr<v1::Mission> MissionCoordinator::CancelMission(
    const v1::CancelMissionRequest& request, const CallContext&) {
  if (request.mission_id().empty()) return absl::InvalidArgumentError("mission_id is empty");
  const std::string& id = request.mission_id();
  {
    auto lock_ptr = MissionLock(id);
    std::lock_guard lock(*lock_ptr);
    SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(id));
    if (MissionStateFromProto(record.state) == mission::MissionState::kCancelled)
      return MissionFromRecord(record);  // idempotent
    if (IsFinalState(record.state)) {
      return absl::FailedPreconditionError(absl::StrCat(
          "mission '", id, "' is already ", StateName(record.state), " and cannot be cancelled"));
    }
    const std::string reason =
        request.reason().empty() ? "cancelled by operator" : request.reason();
    SEAPLAN_RETURN_IF_ERROR(SetState(id, mission::MissionState::kCancelled,
                                     absl::StrCat("mission cancelled: ", reason)));
  }
  {
    std::lock_guard lock(jobs_mu_);
    auto it = running_replans_.find(id);
    if (it != running_replans_.end()) it->second.Cancel();
  }
  SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(id));
  return MissionFromRecord(record);
}

absl::Status MissionCoordinator::CheckVesselCaller(const CallContext& ctx,
                                                   const std::string& mission_id) {
  if (ctx.client_cert_subject.empty()) return absl::OkStatus();
  SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(mission_id));
  return CheckVesselCertificate(ctx, record.vessel_id, mission_id);
}

absl::Status MissionCoordinator::WatchMission(const v1::WatchMissionRequest& request,
                                              const CallContext& ctx,
                                              const StreamSink<v1::MissionEvent>& sink) {
  const std::string& id = request.mission_id();
  if (id.empty()) return absl::InvalidArgumentError("mission_id is empty");
  if (request.after_version() < 0 || request.after_event_id() < 0) {
    return absl::InvalidArgumentError("after_version and after_event_id must not be negative");
  }
  SEAPLAN_RETURN_IF_ERROR(repo_.Get(id).status());  // NotFound before anything is sent
  SEAPLAN_RETURN_IF_ERROR(CheckVesselCaller(ctx, id));
  int last_version = request.after_version();
  std::int64_t last_event = request.after_event_id();
  int last_state_sent = -1;
  int last_current_version_sent = -1;
  constexpr int kBatch = 200;
  std::uint64_t generation = notifier_.Generation(id);  // subscribe before reading
  while (true) {
    ctx.ForwardCancellation();
    if (ctx.stop.StopRequested())
      return StopStatus(ctx.stop, root_.StopRequested(), "mission watch");
    if (notifier_.closed())
      return absl::UnavailableError("mission watch ended: the server is shutting down");
    bool more = false;
    // The mission is read FIRST: when this snapshot is final, every version
    // and event committed before it is visible to the reads below, so the
    // stream can end complete after them.
    SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(id));
    SEAPLAN_ASSIGN_OR_RETURN(auto versions, repo_.ListVersions(id, last_version, kBatch));
    more |= static_cast<int>(versions.size()) == kBatch;
    for (const auto& v : versions) {
      v1::MissionEvent event;
      if (!event.mutable_plan_version()->ParseFromString(v.content)) {
        return absl::DataLossError(
            absl::StrCat("plan version ", v.version, " of mission '", id, "' is unreadable"));
      }
      if (!sink(event)) return absl::CancelledError("mission watch: the client went away");
      last_version = v.version;
    }
    SEAPLAN_ASSIGN_OR_RETURN(auto events, repo_.ListEvents(id, last_event, kBatch));
    more |= static_cast<int>(events.size()) == kBatch;
    for (const auto& e : events) {
      v1::MissionEvent event;
      v1::LogEvent* log = event.mutable_log();
      log->set_event_id(e.event_id);
      log->set_mission_id(e.mission_id);
      *log->mutable_time() = ToTimestamp(e.time_ms);
      log->set_mission_time_s(e.mission_time_s);
      log->set_source(e.source);
      log->set_message(e.message);
      if (!sink(event)) return absl::CancelledError("mission watch: the client went away");
      last_event = e.event_id;
    }
    if (record.state != last_state_sent || record.current_version != last_current_version_sent) {
      v1::MissionEvent event;
      *event.mutable_mission() = MissionFromRecord(record);
      if (!sink(event)) return absl::CancelledError("mission watch: the client went away");
      last_state_sent = record.state;
      last_current_version_sent = record.current_version;
    }
    if (more) continue;
    // Final state (snapshot taken before the reads): the stream is complete.
    if (IsFinalState(record.state) && last_version >= record.current_version)
      return absl::OkStatus();
    std::uint64_t now_generation = generation;
    while (now_generation == generation) {
      now_generation = notifier_.Wait(id, generation, options_.watch_poll);
      ctx.ForwardCancellation();
      if (ctx.stop.StopRequested() || notifier_.closed()) break;
    }
    generation = now_generation;
  }
}

absl::StatusOr<v1::ReportFeedbackResponse> MissionCoordinator::ReportFeedback(
    const v1::ReportFeedbackRequest& request, const CallContext& ctx) {
  const std::string& id = request.mission_id();
  if (id.empty()) return absl::InvalidArgumentError("mission_id is empty");
  if (request.vessel_id().empty()) return absl::InvalidArgumentError("vessel_id is empty");
  if (request.sequence_number() < 0)
    return absl::InvalidArgumentError("sequence_number must not be negative");
  SEAPLAN_RETURN_IF_ERROR(CheckVesselCertificate(ctx, request.vessel_id(), id));
  SEAPLAN_RETURN_IF_ERROR(CheckVesselCaller(ctx, id));
  v1::ReportFeedbackResponse response;
  // A retry of a stored report: answer "duplicate" and change nothing.
  SEAPLAN_ASSIGN_OR_RETURN(auto existing,
                           repo_.FindFeedback(request.vessel_id(), request.sequence_number()));
  if (existing) {
    if (existing->mission_id != id) {
      return absl::InvalidArgumentError(absl::StrCat(
          "sequence number ", request.sequence_number(), " of vessel '", request.vessel_id(),
          "' was already used for mission '", existing->mission_id, "'"));
    }
    SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(id));
    response.set_duplicate(true);
    response.set_current_version(record.current_version);
    return response;
  }
  auto lock_ptr = MissionLock(id);
  std::unique_lock lock(*lock_ptr);
  SEAPLAN_ASSIGN_OR_RETURN(MissionRuntimeState runtime, LoadRuntime(id));
  const v1::Mission& mission = runtime.mission;
  if (IsFinalState(mission.state())) {
    return absl::FailedPreconditionError(absl::StrCat(
        "mission '", id, "' is ", StateName(mission.state()), "; feedback is no longer accepted"));
  }
  const v1::Feedback& feedback = request.feedback();
  const mission::FeedbackOutcome decision = adapter_.OnFeedback(mission.spec(), runtime, feedback);

  storage::MissionUpdate update;
  if (feedback.has_state()) update.last_state = feedback.state().SerializeAsString();
  if (decision.completed_changed) update.completed_tasks = decision.completed_task_ids;
  const bool replan = decision.replan_reason && !decision.mission_completed;
  const std::string replan_reason = replan ? *decision.replan_reason : "";
  if (decision.mission_completed || replan) {
    SEAPLAN_ASSIGN_OR_RETURN(
        mission::MissionState next,
        mission::NextState(MissionStateFromProto(mission.state()),
                           decision.mission_completed ? mission::MissionEvent::kCompleted
                                                      : mission::MissionEvent::kReplanStarted));
    update.state = MissionStateToProto(next);
  }

  std::vector<storage::NewLogEvent> events;
  events.push_back(
      {NowMs(), feedback.mission_time_s(), request.vessel_id(), DescribeFeedback(feedback)});
  for (const auto& line : decision.log_messages)
    events.push_back(ServerEvent(line, feedback.mission_time_s()));
  if (replan)
    events.push_back(
        ServerEvent(absl::StrCat("replanning: ", replan_reason), feedback.mission_time_s()));

  storage::FeedbackRecord record{id,
                                 request.vessel_id(),
                                 request.sequence_number(),
                                 feedback.kind(),
                                 feedback.SerializeAsString(),
                                 NowMs()};
  SEAPLAN_ASSIGN_OR_RETURN(bool inserted, repo_.RecordFeedback(record, update, events));
  lock.unlock();
  response.set_current_version(mission.current_version());
  if (!inserted) {  // a concurrent retry stored it first
    response.set_duplicate(true);
    return response;
  }
  notifier_.Notify(id);
  if (replan) {
    std::lock_guard jobs_lock(jobs_mu_);
    const int base = mission.current_version();
    const auto running = running_bases_.find(id);
    const bool already = (running != running_bases_.end() && running->second == base) ||
                         std::any_of(jobs_.begin(), jobs_.end(), [&](const ReplanJob& j) {
                           return j.mission_id == id && j.base_version == base;
                         });
    if (already) {
      // The replan already under way covers this report too (it reads the
      // runtime state, this report included, when it starts or it already
      // started from the same version); the mission stays REPLANNING until
      // it ends, and a new version still follows on the watch stream.
      response.set_replan_triggered(true);
      response.set_replan_reason(replan_reason);
    } else if (static_cast<int>(jobs_.size()) >= options_.max_pending_replans || stopping_) {
      log::Error("mission {}: replan queue full, replan '{}' dropped", id, replan_reason);
      EndReplanning(id, absl::StrCat("replan not started (server busy): ", replan_reason));
    } else {
      jobs_.push_back({id, replan_reason, base});
      jobs_cv_.notify_one();
      response.set_replan_triggered(true);
      response.set_replan_reason(replan_reason);
    }
  }
  return response;
}

absl::StatusOr<v1::PlanVersion> MissionCoordinator::Replan(
    const std::string& id, const std::string& reason, const StopToken& stop,
    const std::function<absl::Status(std::function<void()>)>& run, bool* stopped) {
  *stopped = false;
  SEAPLAN_ASSIGN_OR_RETURN(MissionRuntimeState runtime, LoadRuntime(id));
  if (IsFinalState(runtime.mission.state())) {
    return absl::FailedPreconditionError(absl::StrCat(
        "mission '", id, "' is ", StateName(runtime.mission.state()), "; nothing to replan"));
  }
  const double now_s = runtime.recent_feedback.empty()
                           ? runtime.current_version.mission_time_origin_s()
                           : runtime.recent_feedback.back().mission_time_s();
  absl::StatusOr<std::optional<PlannedVersion>> planned =
      absl::UnknownError("replanning did not run");
  SEAPLAN_RETURN_IF_ERROR(
      run([&] { planned = adapter_.Replan(runtime.mission.spec(), runtime, reason, stop); }));
  if (stop.StopRequested()) {
    *stopped = true;
    EndReplanning(id, absl::StrCat("replan stopped before it finished: ", reason));
    return absl::CancelledError("replan stopped");
  }
  if (!planned.ok()) {
    EndReplanning(id, absl::StrCat("replan failed: ", planned.status().message()));
    return planned.status();
  }
  auto lock_ptr = MissionLock(id);
  std::lock_guard lock(*lock_ptr);
  SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(id));
  if (IsFinalState(record.state)) {
    return absl::AbortedError(absl::StrCat("mission '", id, "' became ", StateName(record.state),
                                           " while replanning; the new plan was discarded"));
  }
  if (!planned->has_value()) {
    SEAPLAN_RETURN_IF_ERROR(
        SetState(id, mission::MissionState::kCompleted, "the goal holds: mission completed"));
    return absl::FailedPreconditionError(
        "nothing left to plan: the goal already holds; the mission is completed");
  }
  PlannedVersion& next = **planned;
  v1::PlanVersion& version = next.version;
  const std::int64_t now = NowMs();
  version.set_mission_id(id);
  version.set_version(record.current_version + 1);
  if (version.reason().empty()) version.set_reason(reason);
  *version.mutable_created_at() = ToTimestamp(now);
  storage::MissionUpdate update;
  SEAPLAN_ASSIGN_OR_RETURN(
      mission::MissionState next_state,
      mission::NextState(MissionStateFromProto(record.state), mission::MissionEvent::kNewVersion));
  update.state = MissionStateToProto(next_state);
  std::vector<storage::NewLogEvent> events;
  for (const auto& line : next.log_messages) events.push_back(ServerEvent(line, now_s));
  events.push_back(ServerEvent(DescribeVersion(version), version.mission_time_origin_s()));
  SEAPLAN_RETURN_IF_ERROR(repo_.AppendVersion({id, version.version(), version.reason(), now,
                                               version.SerializeAsString(), next.engine_state},
                                              update, events));
  notifier_.Notify(id);
  return version;
}

absl::StatusOr<v1::RequestReplanResponse> MissionCoordinator::RequestReplan(
    const v1::RequestReplanRequest& request, const CallContext& ctx) {
  const std::string& id = request.mission_id();
  if (id.empty()) return absl::InvalidArgumentError("mission_id is empty");
  SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(id));
  SEAPLAN_RETURN_IF_ERROR(CheckVesselCertificate(ctx, record.vessel_id, id));
  if (IsFinalState(record.state)) {
    return absl::FailedPreconditionError(
        absl::StrCat("mission '", id, "' is ", StateName(record.state), "; nothing to replan"));
  }
  const std::string reason =
      request.reason().empty() ? "replan requested by operator" : request.reason();
  SEAPLAN_RETURN_IF_ERROR(
      SetState(id, mission::MissionState::kReplanning, absl::StrCat("replanning: ", reason)));
  bool stopped = false;
  auto version = Replan(
      id, reason, ctx.stop,
      [&](std::function<void()> work) {
        return pool_.Run(std::move(work), ctx.stop, [&] { ctx.ForwardCancellation(); });
      },
      &stopped);
  if (stopped) return StopStatus(ctx.stop, root_.StopRequested(), "replanning");
  if (!version.ok()) {
    if (absl::IsResourceExhausted(version.status()) || absl::IsUnavailable(version.status())) {
      EndReplanning(id, absl::StrCat("replan not started: ", version.status().message()));
    }
    return version.status();
  }
  v1::RequestReplanResponse response;
  *response.mutable_version() = std::move(*version);
  return response;
}

void MissionCoordinator::BackgroundLoop() {
  while (true) {
    ReplanJob job;
    StopToken stop;
    {
      std::unique_lock lock(jobs_mu_);
      jobs_cv_.wait(lock, [&] { return stopping_ || !jobs_.empty(); });
      if (stopping_) return;
      job = std::move(jobs_.front());
      jobs_.pop_front();
      stop = root_.Child(StopToken::Clock::now() + options_.background_replan_timeout);
      running_replans_[job.mission_id] = stop;
      running_bases_[job.mission_id] = job.base_version;
    }
    // A trigger about a version that was replanned meanwhile (the job was
    // queued just as an earlier replan of the same base ended) is stale.
    if (auto record = repo_.Get(job.mission_id);
        record.ok() && record->current_version != job.base_version) {
      log::Info("mission {}: replan '{}' skipped: version {} was already replanned", job.mission_id,
                job.reason, job.base_version);
      std::lock_guard lock(jobs_mu_);
      running_replans_.erase(job.mission_id);
      running_bases_.erase(job.mission_id);
      continue;
    }
    // On the work pool like every planning job (--planning-threads bounds
    // them), waiting for a free worker: nobody would retry a refused one.
    bool stopped = false;
    auto version = Replan(
        job.mission_id, job.reason, stop,
        [&](std::function<void()> work) { return pool_.RunWhenFree(std::move(work), stop); },
        &stopped);
    if (!version.ok() &&
        (absl::IsUnavailable(version.status()) || (!stopped && stop.StopRequested()))) {
      EndReplanning(job.mission_id,
                    absl::StrCat("replan not started: ", version.status().message()));
    }
    if (!version.ok()) {
      log::Warn("mission {}: replan '{}' ended without a new version: {}", job.mission_id,
                job.reason, version.status().ToString());
    }
    std::lock_guard lock(jobs_mu_);
    running_replans_.erase(job.mission_id);
    running_bases_.erase(job.mission_id);
  }
}

}  // namespace seaplan::server
