// MissionService: the flow around the mission engine.
//
// Overview
//   CreateMission  validate -> engine.PlanInitial (on the WorkPool) -> store
//                  mission + version 1 + log events in one transaction.
//   ReportFeedback idempotent by (vessel_id, sequence_number): engine
//                  decides (OnFeedback), then the report, its log events and
//                  the mission update are committed together before the RPC
//                  returns; a replan it triggers is queued, run on the
//                  WorkPool (waiting for a free worker) by the coordinator's
//                  background thread, and its version reaches the watchers.
//   RequestReplan  synchronous replan on the WorkPool.
//   WatchMission   plan versions, log events and mission state changes,
//                  resumable from (after_version, after_event_id).
//
// Watch without gap or duplicate: every commit bumps a per-mission
// generation counter AFTER the commit. A watcher reads the generation first,
// then reads storage for everything after the last version / event id it
// sent, then waits until the generation moves. A commit that lands during
// the read either is seen by the read or bumps the generation after it, so
// nothing is missed; ids only grow, so nothing is sent twice.
//
// Versions of one mission are appended under a per-mission lock and
// storage checks that each is current + 1 (MissionRepository::AppendVersion).
//
// The mission itself (what a report means, the states and which change is
// allowed, planning and replanning) is the mission engine's
// (engine/mission); this class keeps transactions, locking, notification
// and the queue of triggered replans, and MissionAdapter translates.
//
// Thread-safety: all methods may be called from any thread.
#pragma once

#include <condition_variable>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <unordered_map>

#include "seaplan/common/stop_token.h"
#include "seaplan/mission/mission_engine.h"
#include "seaplan/storage/repositories.h"
#include "seaplan/v1/mission.pb.h"
#include "server/core/call_context.h"
#include "server/core/mission_engine_adapter.h"
#include "server/core/work_pool.h"

namespace seaplan::server {

// Per-mission change counters that watchers wait on.
class MissionNotifier {
 public:
  std::uint64_t Generation(const std::string& mission_id);
  void Notify(const std::string& mission_id);
  // Waits until the generation differs from `seen`, `timeout` passes or
  // Close() is called; returns the current generation.
  std::uint64_t Wait(const std::string& mission_id, std::uint64_t seen,
                     std::chrono::milliseconds timeout);
  void Close();
  bool closed();

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  std::unordered_map<std::string, std::uint64_t> generation_;
  bool closed_ = false;
};

class MissionCoordinator {
 public:
  struct Options {
    // Time budget of a replan triggered by feedback (no client deadline).
    std::chrono::seconds background_replan_timeout{300};
    // Triggered replans waiting to run; more are refused with a log event.
    int max_pending_replans = 64;
    // How often watchers re-check cancellation while idle.
    std::chrono::milliseconds watch_poll{100};
    // Feedback reports handed to the engine as recent history.
    int feedback_history = 200;
  };

  // `engine` must not be null.
  MissionCoordinator(storage::MissionRepository& repo, WorkPool& pool, StopToken root,
                     std::shared_ptr<mission::MissionEngine> engine, Options options);
  MissionCoordinator(storage::MissionRepository& repo, WorkPool& pool, StopToken root,
                     std::shared_ptr<mission::MissionEngine> engine)
      : MissionCoordinator(repo, pool, std::move(root), std::move(engine), Options{}) {}
  ~MissionCoordinator();  // Shutdown()
  MissionCoordinator(const MissionCoordinator&) = delete;
  MissionCoordinator& operator=(const MissionCoordinator&) = delete;

  absl::StatusOr<v1::Mission> CreateMission(const v1::CreateMissionRequest& request,
                                            const CallContext& ctx);
  absl::StatusOr<v1::Mission> GetMission(const v1::GetMissionRequest& request,
                                         const CallContext& ctx);
  absl::StatusOr<v1::ListMissionsResponse> ListMissions(const v1::ListMissionsRequest& request,
                                                        const CallContext& ctx);
  absl::StatusOr<v1::Mission> CancelMission(const v1::CancelMissionRequest& request,
                                            const CallContext& ctx);
  // Ends OK when the mission reached a final state and everything was sent;
  // Unavailable when the server shuts down; Cancelled when the client left.
  // A caller with a vessel's client certificate acts only on that vessel's
  // missions: PermissionDenied otherwise (OK without a certificate).
  absl::Status CheckVesselCaller(const CallContext& ctx, const std::string& mission_id);

  absl::Status WatchMission(const v1::WatchMissionRequest& request, const CallContext& ctx,
                            const StreamSink<v1::MissionEvent>& sink);
  absl::StatusOr<v1::ReportFeedbackResponse> ReportFeedback(
      const v1::ReportFeedbackRequest& request, const CallContext& ctx);
  absl::StatusOr<v1::RequestReplanResponse> RequestReplan(const v1::RequestReplanRequest& request,
                                                          const CallContext& ctx);

  // Ends watch streams, cancels background replans, joins the thread.
  void Shutdown();

  MissionNotifier& notifier() { return notifier_; }

 private:
  struct ReplanJob {
    std::string mission_id;
    std::string reason;
    int base_version = 0;  // the plan version the trigger was about
  };

  std::shared_ptr<std::mutex> MissionLock(const std::string& mission_id);
  absl::StatusOr<MissionRuntimeState> LoadRuntime(const std::string& mission_id);
  // Replans now; `run` executes the engine call (on the pool or inline).
  absl::StatusOr<v1::PlanVersion> Replan(
      const std::string& mission_id, const std::string& reason, const StopToken& stop,
      const std::function<absl::Status(std::function<void()>)>& run, bool* stopped);
  absl::Status SetState(const std::string& mission_id, mission::MissionState state,
                        const std::string& message, const std::string& failure_reason = "");
  // REPLANNING -> ACTIVE with `message` logged; a mission cancelled
  // meanwhile keeps its state (only the message is logged).
  void EndReplanning(const std::string& mission_id, const std::string& message);
  void BackgroundLoop();

  storage::MissionRepository& repo_;
  WorkPool& pool_;
  StopToken root_;
  MissionAdapter adapter_;
  Options options_;
  MissionNotifier notifier_;

  std::mutex locks_mu_;
  std::map<std::string, std::shared_ptr<std::mutex>> locks_;

  std::mutex jobs_mu_;
  std::condition_variable jobs_cv_;
  std::deque<ReplanJob> jobs_;
  std::map<std::string, StopToken> running_replans_;  // mission -> token of its background replan
  // mission -> base version of its running background replan. A trigger for
  // a base version already pending or running is the same situation
  // reported twice (two feedbacks in one step): it must not replan again.
  std::map<std::string, int> running_bases_;
  bool stopping_ = false;
  std::thread background_;
};

// The API view of a stored mission.
v1::Mission MissionFromRecord(const storage::MissionRecord& record);
bool IsFinalState(int state);

}  // namespace seaplan::server
