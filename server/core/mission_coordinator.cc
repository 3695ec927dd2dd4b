#include "server/core/mission_coordinator.h"

#include <unistd.h>

#include <algorithm>
#include <random>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "seaplan/common/log.h"
#include "seaplan/mission/mission_state.h"
#include "server/core/audit_entry.h"
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

// host:pid:random, unique among the processes sharing a database.
std::string ProcessHolderId() {
  char host[256] = {};
  if (gethostname(host, sizeof(host) - 1) != 0) host[0] = '\0';
  std::random_device random;
  return absl::StrFormat("%s:%d:%08x", host, static_cast<int>(getpid()), random());
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
  if (feed_ != nullptr) return feed_->Generation(mission_id);
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
  if (feed_ != nullptr) {
    // The feed's Wait is not woken by Close(): `timeout` (the watch poll)
    // bounds how long a closing server waits for its watchers.
    if (closed()) return feed_->Generation(mission_id);
    return feed_->Wait(mission_id, seen, timeout);
  }
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

absl::Status MissionCoordinator::Options::Validate() const {
  if (lease_ttl < std::chrono::milliseconds(100)) {
    return absl::InvalidArgumentError(
        absl::StrCat("lease: ", lease_ttl.count(), " ms is too short (at least 100 ms)"));
  }
  if (sweep_interval < std::chrono::milliseconds(10)) {
    return absl::InvalidArgumentError(absl::StrCat("sweep interval: ", sweep_interval.count(),
                                                   " ms is too short (at least 10 ms)"));
  }
  if (sweep_interval >= lease_ttl) {
    return absl::InvalidArgumentError(absl::StrCat("sweep interval: ", sweep_interval.count(),
                                                   " ms must be shorter than the lease (",
                                                   lease_ttl.count(), " ms)"));
  }
  return absl::OkStatus();
}

MissionCoordinator::MissionCoordinator(storage::MissionRepository& repo, WorkPool& pool,
                                       StopToken root,
                                       std::shared_ptr<mission::MissionEngine> engine,
                                       Options options, Cluster cluster)
    : repo_(repo),
      pool_(pool),
      root_(std::move(root)),
      adapter_(std::move(engine)),
      options_(options),
      cluster_(std::move(cluster)),
      holder_(cluster_.holder.empty() ? ProcessHolderId() : cluster_.holder),
      notifier_(cluster_.changes) {
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
      const std::string reason = "replan resumed after a server restart";
      if (cluster_.work != nullptr) {
        // Recorded unless pending already (then its holder, or the sweep
        // once that lease expires, runs it).
        auto item = cluster_.work->Get(m.id);
        if (item.ok() && !(item->has_value() && (*item)->pending())) {
          (void)cluster_.work->Request(m.id, {reason, m.current_version});
        }
      }
      jobs_.push_back({m.id, reason, m.current_version, std::nullopt});
    }
    if (page->next_after == 0) break;  // the last page
    after = page->next_after;
  }
  background_ = std::thread([this] { BackgroundLoop(); });
  if (cluster_.work != nullptr) renewer_ = std::thread([this] { RenewLoop(); });
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
    for (auto& [id, token] : operator_replans_) token.Cancel();
  }
  jobs_cv_.notify_all();
  renew_cv_.notify_all();
  if (background_.joinable()) background_.join();
  if (renewer_.joinable()) renewer_.join();
  bool release = false;
  {
    std::lock_guard lock(jobs_mu_);
    release = cluster_.work != nullptr && !leases_released_;
    leases_released_ = true;  // once: a later call may find the store closed
  }
  if (release) {
    // Running replans were handed back one by one; this catches the rest.
    auto released = cluster_.work->ReleaseAll(holder_);
    if (!released.ok()) {
      log::Warn("work leases of {} not released (they expire): {}", holder_,
                released.status().ToString());
    }
    std::lock_guard lock(jobs_mu_);
    held_.clear();
  }
}

bool MissionCoordinator::ShuttingDown() {
  if (root_.StopRequested()) return true;
  std::lock_guard lock(jobs_mu_);
  return stopping_;
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
                                          const std::string& failure_reason,
                                          const std::optional<storage::WorkFence>& fence,
                                          std::optional<storage::AuditRecord> audit) {
  storage::MissionUpdate update;
  update.state = MissionStateToProto(state);
  update.fence = fence;
  update.audit = std::move(audit);
  if (!failure_reason.empty()) update.failure_reason = failure_reason;
  absl::Status st = repo_.Update(mission_id, update, {ServerEvent(message)});
  notifier_.Notify(mission_id);
  return st;
}

void MissionCoordinator::EndReplanning(const std::string& mission_id, const std::string& message,
                                       const std::optional<storage::WorkFence>& fence) {
  auto lock_ptr = MissionLock(mission_id);
  std::lock_guard lock(*lock_ptr);
  auto record = repo_.Get(mission_id);
  if (!record.ok()) return;
  if (MissionStateFromProto(record->state) == mission::MissionState::kReplanning) {
    (void)SetState(mission_id, mission::MissionState::kActive, message, "", fence);
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
  const auto audit = AuditEntry(ctx, record.id);
  // Storage checks the chart still exists in the creating transaction: a
  // DeleteChart that committed while this mission was planned (it could not
  // see the mission yet) leaves the mission unstored rather than on a chart
  // its replans could no longer load.
  absl::Status st = repo_.Create(
      record,
      {record.id, 1, version.reason(), now, version.SerializeAsString(), planned->engine_state},
      events, AuditPointer(audit), spec.chart_id());
  if (absl::IsAlreadyExists(st) && !request.request_id().empty()) {
    // A concurrent retry with the same key won: answer with its mission.
    SEAPLAN_ASSIGN_OR_RETURN(auto existing, repo_.FindByRequestId(request.request_id()));
    if (existing) return MissionFromRecord(*existing);
  }
  if (absl::IsNotFound(st)) {
    // As for a chart that was already gone when planning began.
    return absl::FailedPreconditionError(
        absl::StrCat("spec.chart_id: chart '", spec.chart_id(),
                     "' was deleted while the mission was planned; the mission was not created"));
  }
  SEAPLAN_RETURN_IF_ERROR(st);
  notifier_.Notify(record.id);
  return MissionFromRecord(record);
}

absl::Status MissionCoordinator::CheckVesselAccess(const std::string& mission_id,
                                                   const CallContext& ctx) {
  SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(mission_id));
  SEAPLAN_RETURN_IF_ERROR(auth::CheckVessel(ctx.caller, record.vessel_id, mission_id));
  return CheckVesselCertificate(ctx, record.vessel_id, mission_id);
}

absl::StatusOr<v1::Mission> MissionCoordinator::GetMission(const v1::GetMissionRequest& request,
                                                           const CallContext& ctx) {
  if (request.mission_id().empty()) return absl::InvalidArgumentError("mission_id is empty");
  SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(request.mission_id()));
  SEAPLAN_RETURN_IF_ERROR(auth::CheckVessel(ctx.caller, record.vessel_id, record.id));
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

absl::StatusOr<v1::ListFeedbackResponse> MissionCoordinator::ListFeedback(
    const v1::ListFeedbackRequest& request, const CallContext& ctx) {
  const std::string& id = request.mission_id();
  if (id.empty()) return absl::InvalidArgumentError("mission_id is empty");
  if (request.after_sequence() < 0) {
    return absl::InvalidArgumentError("after_sequence must not be negative");
  }
  SEAPLAN_ASSIGN_OR_RETURN(int page_size, PageSize(request.page_size()));
  SEAPLAN_RETURN_IF_ERROR(CheckVesselAccess(id, ctx));  // NotFound for an unknown mission
  SEAPLAN_ASSIGN_OR_RETURN(auto page,
                           repo_.ListFeedbackPage(id, request.after_sequence(), page_size));
  v1::ListFeedbackResponse response;
  for (const storage::FeedbackRecord& r : page.items) {
    v1::StoredFeedback* out = response.add_feedback();
    if (!out->mutable_feedback()->ParseFromString(r.payload)) {
      return absl::DataLossError(
          absl::StrCat("feedback report ", r.seq, " of mission '", id, "' is unreadable"));
    }
    out->set_sequence(r.seq);
    out->set_vessel_id(r.vessel_id);
    out->set_sequence_number(r.sequence_number);
    *out->mutable_received_at() = ToTimestamp(r.received_at_ms);
  }
  response.set_next_after_sequence(page.next_after);
  return response;
}

absl::StatusOr<v1::Mission> MissionCoordinator::CancelMission(
    const v1::CancelMissionRequest& request, const CallContext& ctx) {
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
                                     absl::StrCat("mission cancelled: ", reason), "", std::nullopt,
                                     AuditEntry(ctx, id, request.reason())));
  }
  {
    std::lock_guard lock(jobs_mu_);
    auto it = running_replans_.find(id);
    if (it != running_replans_.end()) it->second.Cancel();
    if (auto op = operator_replans_.find(id); op != operator_replans_.end()) op->second.Cancel();
  }
  SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(id));
  return MissionFromRecord(record);
}

absl::Status MissionCoordinator::WatchMission(const v1::WatchMissionRequest& request,
                                              const CallContext& ctx,
                                              const StreamSink<v1::MissionEvent>& sink) {
  const std::string& id = request.mission_id();
  if (id.empty()) return absl::InvalidArgumentError("mission_id is empty");
  if (request.after_version() < 0 || request.after_event_id() < 0) {
    return absl::InvalidArgumentError("after_version and after_event_id must not be negative");
  }
  SEAPLAN_RETURN_IF_ERROR(CheckVesselAccess(id, ctx));  // NotFound before anything is sent
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
  SEAPLAN_RETURN_IF_ERROR(CheckVesselAccess(id, ctx));
  if (ctx.caller.role == auth::Role::kVessel && !ctx.caller.internal() &&
      request.vessel_id() != ctx.caller.vessel_id) {
    return absl::PermissionDeniedError(absl::StrCat("a token of vessel '", ctx.caller.vessel_id,
                                                    "' may not report as vessel '",
                                                    request.vessel_id(), "'"));
  }
  if (request.sequence_number() < 0)
    return absl::InvalidArgumentError("sequence_number must not be negative");
  SEAPLAN_RETURN_IF_ERROR(CheckVesselCertificate(ctx, request.vessel_id(), id));
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
  // In the report's transaction: acknowledged means its replan is recorded
  // for whichever process gets to it, even if this one dies now.
  if (replan && cluster_.work != nullptr)
    update.request_work = storage::WorkRequest{replan_reason, mission.current_version()};
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
      if (cluster_.work != nullptr) {
        // The request is in the database: a sweep (here or elsewhere) runs it.
        log::Warn("mission {}: replan queue full, replan '{}' left to the next sweep", id,
                  replan_reason);
        response.set_replan_triggered(true);
        response.set_replan_reason(replan_reason);
        return response;
      }
      log::Error("mission {}: replan queue full, replan '{}' dropped", id, replan_reason);
      EndReplanning(id, absl::StrCat("replan not started (server busy): ", replan_reason));
    } else {
      jobs_.push_back({id, replan_reason, base, std::nullopt});
      jobs_cv_.notify_one();
      response.set_replan_triggered(true);
      response.set_replan_reason(replan_reason);
    }
  }
  return response;
}

absl::StatusOr<v1::PlanVersion> MissionCoordinator::Replan(
    const std::string& id, const std::string& reason, const StopToken& stop,
    const std::function<absl::Status(std::function<void()>)>& run, bool* stopped,
    const std::optional<storage::WorkFence>& fence) {
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
    // A leased replan stopped by the shutdown is handed back (RunLeasedJob):
    // the mission stays REPLANNING for the process that takes it over.
    if (!fence || !ShuttingDown())
      EndReplanning(id, absl::StrCat("replan stopped before it finished: ", reason), fence);
    return absl::CancelledError("replan stopped");
  }
  if (!planned.ok()) {
    EndReplanning(id, absl::StrCat("replan failed: ", planned.status().message()), fence);
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
    SEAPLAN_RETURN_IF_ERROR(SetState(id, mission::MissionState::kCompleted,
                                     "the goal holds: mission completed", "", fence));
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
  update.fence = fence;
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
  SEAPLAN_RETURN_IF_ERROR(auth::CheckVessel(ctx.caller, record.vessel_id, id));
  SEAPLAN_RETURN_IF_ERROR(CheckVesselCertificate(ctx, record.vessel_id, id));
  if (IsFinalState(record.state)) {
    return absl::FailedPreconditionError(
        absl::StrCat("mission '", id, "' is ", StateName(record.state), "; nothing to replan"));
  }
  const std::string reason =
      request.reason().empty() ? "replan requested by operator" : request.reason();
  absl::StatusOr<v1::PlanVersion> version = cluster_.work == nullptr
                                                ? LocalOperatorReplan(id, reason, ctx)
                                                : LeasedOperatorReplan(id, reason, ctx);
  SEAPLAN_RETURN_IF_ERROR(version.status());
  v1::RequestReplanResponse response;
  *response.mutable_version() = std::move(*version);
  return response;
}

absl::StatusOr<v1::PlanVersion> MissionCoordinator::LocalOperatorReplan(const std::string& id,
                                                                        const std::string& reason,
                                                                        const CallContext& ctx) {
  // The request is what is audited (with the state change it makes), whether
  // or not the replan then finds a plan.
  SEAPLAN_RETURN_IF_ERROR(SetState(id, mission::MissionState::kReplanning,
                                   absl::StrCat("replanning: ", reason), "", std::nullopt,
                                   AuditEntry(ctx, id, reason)));
  bool stopped = false;
  auto version = Replan(
      id, reason, ctx.stop,
      [&](std::function<void()> work) {
        return pool_.Run(std::move(work), ctx.stop, [&] { ctx.ForwardCancellation(); });
      },
      &stopped);
  if (stopped) return StopStatus(ctx.stop, root_.StopRequested(), "replanning");
  if (!version.ok() &&
      (absl::IsResourceExhausted(version.status()) || absl::IsUnavailable(version.status()))) {
    EndReplanning(id, absl::StrCat("replan not started: ", version.status().message()));
  }
  return version;
}

absl::StatusOr<v1::PlanVersion> MissionCoordinator::LeasedOperatorReplan(const std::string& id,
                                                                         const std::string& reason,
                                                                         const CallContext& ctx) {
  // The request and the claim are one write: no sweeper can take the
  // request first, and while another process (or this one's background
  // replan) holds the work nothing is recorded and this call waits, then
  // plans from the version that replan appended. Each call thus gets a
  // version of its own, appended by exactly one process.
  std::optional<storage::WorkLease> lease;
  for (bool waited = false;; waited = true) {
    ctx.ForwardCancellation();
    if (ctx.stop.StopRequested()) {
      return StopStatus(ctx.stop, root_.StopRequested(),
                        absl::StrCat("replan of mission '", id,
                                     "' (waiting for the replan under way; nothing recorded)"));
    }
    if (ShuttingDown()) {
      return absl::UnavailableError("replan not started: the server is shutting down");
    }
    const std::uint64_t generation = notifier_.Generation(id);
    SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(id));
    if (IsFinalState(record.state)) {
      return absl::FailedPreconditionError(
          absl::StrCat("mission '", id, "' is ", StateName(record.state), "; nothing to replan"));
    }
    SEAPLAN_ASSIGN_OR_RETURN(
        lease, cluster_.work->RequestAndClaim(id, reason, holder_, options_.lease_ttl));
    if (lease) break;
    if (!waited) log::Info("mission {}: replan '{}' waits for the replan under way", id, reason);
    // The other replan's version wakes this; its lease ends just after.
    (void)notifier_.Wait(id, generation, options_.watch_poll);
  }
  const storage::WorkFence fence{lease->holder, lease->token};
  {
    std::lock_guard lock(jobs_mu_);
    held_[id] = *lease;
    operator_replans_[id] = ctx.stop;
  }
  bool stopped = false;
  absl::StatusOr<v1::PlanVersion> version = absl::UnknownError("replanning did not run");
  absl::StatusOr<storage::MissionRecord> claimed_record = repo_.Get(id);
  if (!claimed_record.ok()) {
    version = claimed_record.status();
  } else if (IsFinalState(claimed_record->state)) {  // cancelled just before the claim
    version = absl::FailedPreconditionError(absl::StrCat(
        "mission '", id, "' is ", StateName(claimed_record->state), "; nothing to replan"));
  } else if (absl::Status st = SetState(id, mission::MissionState::kReplanning,
                                        absl::StrCat("replanning: ", reason), "", fence,
                                        AuditEntry(ctx, id, reason));
             !st.ok()) {
    version = st;
  } else {
    version = Replan(
        id, reason, ctx.stop,
        [&](std::function<void()> work) {
          return pool_.Run(std::move(work), ctx.stop, [&] { ctx.ForwardCancellation(); });
        },
        &stopped, fence);
  }
  bool lost = false;
  {
    std::lock_guard lock(jobs_mu_);
    auto it = held_.find(id);
    lost = it == held_.end() || it->second.token != lease->token;
    if (!lost) held_.erase(it);
    operator_replans_.erase(id);
  }
  if (stopped && ShuttingDown()) {
    // The request stays pending, the mission REPLANNING: another process's
    // sweep takes the work over.
    if (absl::Status st = cluster_.work->Release(*lease); !st.ok())
      log::Warn("mission {}: work not handed back ({}); it is taken over on expiry", id,
                st.ToString());
    return absl::UnavailableError(absl::StrCat(
        "replan of mission '", id, "' handed to another server: this one is shutting down"));
  }
  if (!version.ok() && !stopped &&
      (absl::IsResourceExhausted(version.status()) || absl::IsUnavailable(version.status()))) {
    EndReplanning(id, absl::StrCat("replan not started: ", version.status().message()), fence);
  }
  absl::StatusOr<bool> more = cluster_.work->Complete(*lease);
  if (!more.ok()) {
    log::Warn("mission {}: work lease lost: {}", id, more.status().ToString());
  } else if (*more) {
    // Reports that needed a replan came meanwhile: their work is pending;
    // run it here now rather than at the next sweep.
    std::lock_guard lock(jobs_mu_);
    if (!stopping_) {
      jobs_.push_back({id, reason, lease->base_version, std::nullopt});
      jobs_cv_.notify_one();
    }
  }
  if (stopped && lost) {
    return absl::AbortedError(
        absl::StrCat("replan of mission '", id,
                     "' stopped: this server lost the mission's work lease (it stalled past it)"));
  }
  if (stopped) {
    if (auto record = repo_.Get(id); record.ok() && IsFinalState(record->state)) {
      return absl::FailedPreconditionError(absl::StrCat(
          "mission '", id, "' became ", StateName(record->state), " while replanning"));
    }
    return StopStatus(ctx.stop, root_.StopRequested(), "replanning");
  }
  return version;
}

void MissionCoordinator::BackgroundLoop() {
  const auto sweep_every = options_.sweep_interval;
  auto next_sweep = StopToken::Clock::now() + sweep_every;
  while (true) {
    ReplanJob job;
    StopToken stop;
    {
      std::unique_lock lock(jobs_mu_);
      if (cluster_.work == nullptr) {
        jobs_cv_.wait(lock, [&] { return stopping_ || !jobs_.empty(); });
      } else {
        jobs_cv_.wait_until(lock, next_sweep, [&] { return stopping_ || !jobs_.empty(); });
      }
      if (stopping_) return;
      if (jobs_.empty()) {  // Cluster: idle until the sweep is due
        lock.unlock();
        next_sweep = StopToken::Clock::now() + sweep_every;
        Sweep();
        continue;
      }
      job = std::move(jobs_.front());
      jobs_.pop_front();
      stop = root_.Child(StopToken::Clock::now() + options_.background_replan_timeout);
      running_replans_[job.mission_id] = stop;
      running_bases_[job.mission_id] = job.base_version;
    }
    const std::string id = job.mission_id;
    if (cluster_.work == nullptr) {
      RunJob(std::move(job), stop);
    } else {
      RunLeasedJob(std::move(job), stop);
    }
    std::lock_guard lock(jobs_mu_);
    running_replans_.erase(id);
    running_bases_.erase(id);
  }
}

void MissionCoordinator::RunJob(ReplanJob job, const StopToken& stop) {
  // A trigger about a version that was replanned meanwhile (the job was
  // queued just as an earlier replan of the same base ended) is stale.
  if (auto record = repo_.Get(job.mission_id);
      record.ok() && record->current_version != job.base_version) {
    log::Info("mission {}: replan '{}' skipped: version {} was already replanned", job.mission_id,
              job.reason, job.base_version);
    return;
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
    EndReplanning(job.mission_id, absl::StrCat("replan not started: ", version.status().message()));
  }
  if (!version.ok()) {
    log::Warn("mission {}: replan '{}' ended without a new version: {}", job.mission_id, job.reason,
              version.status().ToString());
  }
}

void MissionCoordinator::RunLeasedJob(ReplanJob job, const StopToken& stop) {
  const std::string& id = job.mission_id;
  std::optional<storage::WorkLease> lease = std::move(job.lease);
  while (true) {
    if (!lease) {
      auto claimed = cluster_.work->Claim(id, holder_, options_.lease_ttl);
      if (!claimed.ok()) {
        log::Warn("mission {}: replan '{}' not claimed ({}); a sweep retries it", id, job.reason,
                  claimed.status().ToString());
        return;
      }
      if (!claimed->has_value()) {
        log::Info("mission {}: replan '{}' left to the server holding its work (or done)", id,
                  job.reason);
        return;
      }
      lease = std::move(**claimed);
    }
    {
      std::lock_guard lock(jobs_mu_);
      held_[id] = *lease;
    }
    const storage::WorkFence fence{lease->holder, lease->token};
    // The reason of the latest request (what the ship reported last).
    const std::string reason = lease->reason.empty() ? job.reason : lease->reason;
    absl::StatusOr<storage::MissionRecord> record = repo_.Get(id);
    bool hand_back = !record.ok();  // storage unreachable: someone retries later
    if (record.ok() && !IsFinalState(record->state) &&
        record->current_version == lease->base_version) {
      bool stopped = false;
      auto version = Replan(
          id, reason, stop,
          [&](std::function<void()> work) { return pool_.RunWhenFree(std::move(work), stop); },
          &stopped, fence);
      hand_back = stopped && ShuttingDown();
      if (!version.ok() && !hand_back &&
          (absl::IsUnavailable(version.status()) || (!stopped && stop.StopRequested()))) {
        EndReplanning(id, absl::StrCat("replan not started: ", version.status().message()), fence);
      }
      if (!version.ok()) {
        log::Warn("mission {}: replan '{}' ended without a new version: {}", id, reason,
                  version.status().ToString());
      }
    } else if (record.ok() && record->current_version != lease->base_version) {
      log::Info("mission {}: replan '{}' skipped: version {} was already replanned", id, reason,
                lease->base_version);
    }
    {
      std::lock_guard lock(jobs_mu_);
      held_.erase(id);
    }
    if (hand_back) {
      if (absl::Status st = cluster_.work->Release(*lease); !st.ok())
        log::Warn("mission {}: work not handed back ({}); it is taken over on expiry", id,
                  st.ToString());
      return;
    }
    absl::StatusOr<bool> more = cluster_.work->Complete(*lease);
    if (!more.ok()) {
      log::Warn("mission {}: work lease lost: {}", id, more.status().ToString());
      return;
    }
    if (!*more || stop.StopRequested()) return;
    // Requests came while this ran: claim again; the base check above tells
    // a new trigger from one the version just appended already answered.
    lease.reset();
  }
}

void MissionCoordinator::Sweep() {
  auto claimed = cluster_.work->ClaimNext(holder_, options_.lease_ttl, 1);
  if (!claimed.ok()) {
    log::Warn("work sweep failed: {}", claimed.status().ToString());
    return;
  }
  std::lock_guard lock(jobs_mu_);
  for (storage::WorkLease& lease : *claimed) {
    log::Warn("mission {}: taking over replan '{}' of version {} (nobody held it)",
              lease.mission_id, lease.reason, lease.base_version);
    std::string id = lease.mission_id, reason = lease.reason;
    const int base = lease.base_version;
    jobs_.push_back({std::move(id), std::move(reason), base, std::move(lease)});
  }
}

void MissionCoordinator::RenewLoop() {
  std::unique_lock lock(jobs_mu_);
  while (true) {
    renew_cv_.wait_for(lock, options_.lease_ttl / 3, [&] { return stopping_; });
    if (stopping_) return;
    const std::map<std::string, storage::WorkLease> leases = held_;
    lock.unlock();
    for (const auto& [id, lease] : leases) {
      absl::StatusOr<storage::WorkLease> renewed = cluster_.work->Renew(lease, options_.lease_ttl);
      std::lock_guard relock(jobs_mu_);
      auto it = held_.find(id);
      const bool same = it != held_.end() && it->second.token == lease.token;
      if (renewed.ok()) {
        if (same) it->second = *renewed;
      } else if (absl::IsAborted(renewed.status())) {
        // Taken over (this process stalled past the TTL): stop planning; the
        // fenced write would be refused anyway.
        log::Warn("mission {}: work lease lost, its replan here stops: {}", id,
                  renewed.status().ToString());
        if (same) held_.erase(it);
        if (auto r = running_replans_.find(id); r != running_replans_.end()) r->second.Cancel();
        if (auto r = operator_replans_.find(id); r != operator_replans_.end()) r->second.Cancel();
      } else {
        log::Warn("mission {}: work lease not renewed: {}", id, renewed.status().ToString());
      }
    }
    lock.lock();
  }
}

}  // namespace seaplan::server
