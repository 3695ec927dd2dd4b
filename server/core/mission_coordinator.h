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
//   RequestReplan  synchronous replan on the WorkPool: one new version per
//                  call (with Cluster, under the mission's work lease).
//   WatchMission   plan versions, log events and mission state changes,
//                  resumable from (after_version, after_event_id).
//   ListFeedback   the stored feedback reports, paged by arrival order.
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
// Several server processes on one database (Cluster set): a report that
// needs a replan records a work request in its own transaction; the
// triggered replan runs only under the mission's work lease (claimed in the
// database, renewed while planning, its token checked by the write that
// appends the version), so exactly one process replans a mission at a time.
// An operator's RequestReplan records its request and claims the lease in
// one write, waiting while another replan holds it, and plans on the
// process that received it; if that process dies the request is pending
// work like any other and a sweep elsewhere plans it.
// Every process sweeps for work nobody holds (a holder that died and whose
// lease expired, work handed back by a process shutting down, a request
// whose receiver died before claiming it) while it has nothing queued.
// Shutdown hands running work back (the mission stays REPLANNING) instead of
// ending it. Watchers wait on the database's change feed, so a commit of any
// process wakes them.
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
#include <optional>
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

// Per-mission change counters that watchers wait on: the store's change
// feed when there is one (commits of every process), else counters bumped
// by this process's commits.
class MissionNotifier {
 public:
  explicit MissionNotifier(storage::ChangeFeed* feed = nullptr) : feed_(feed) {}
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
  storage::ChangeFeed* feed_;
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
    // Lease on a mission's replan (Cluster): renewed every third of it while
    // planning. Longer rides out longer stalls of a holder (a pause longer
    // than two thirds of it loses the work to another process); shorter
    // hands a dead holder's work over sooner.
    std::chrono::milliseconds lease_ttl{5000};
    // How often an idle process looks for work nobody holds (Cluster): a
    // dead holder's work is taken over at most lease_ttl + sweep_interval
    // after its last renewal. Each sweep is one query per process.
    std::chrono::milliseconds sweep_interval{2500};

    // InvalidArgument naming the field: lease_ttl under 100 ms (renewals
    // every third of it would flood the database), sweep_interval under
    // 10 ms or not shorter than lease_ttl (takeover would wait on the sweep
    // more than on the expiry).
    absl::Status Validate() const;
  };

  // The shared database's work leases and change feed, for several server
  // processes on one database. Without them (both null) replans are queued
  // in this process only and watchers are woken by its own commits.
  struct Cluster {
    storage::WorkLeaseRepository* work = nullptr;
    storage::ChangeFeed* changes = nullptr;
    // This process's name in leases; "" = host, pid and a random part.
    std::string holder;
  };

  // `engine` must not be null.
  MissionCoordinator(storage::MissionRepository& repo, WorkPool& pool, StopToken root,
                     std::shared_ptr<mission::MissionEngine> engine, Options options,
                     Cluster cluster);
  MissionCoordinator(storage::MissionRepository& repo, WorkPool& pool, StopToken root,
                     std::shared_ptr<mission::MissionEngine> engine, Options options)
      : MissionCoordinator(repo, pool, std::move(root), std::move(engine), options, Cluster()) {}
  MissionCoordinator(storage::MissionRepository& repo, WorkPool& pool, StopToken root,
                     std::shared_ptr<mission::MissionEngine> engine)
      : MissionCoordinator(repo, pool, std::move(root), std::move(engine), Options{}) {}
  ~MissionCoordinator();  // Shutdown()
  MissionCoordinator(const MissionCoordinator&) = delete;
  MissionCoordinator& operator=(const MissionCoordinator&) = delete;

  absl::StatusOr<v1::Mission> CreateMission(const v1::CreateMissionRequest& request,
                                            const CallContext& ctx);
  // NotFound when the mission is absent; PermissionDenied when ctx's caller
  // is a vessel token, or presents a vessel's client certificate, of
  // another vessel than the mission's.
  absl::Status CheckVesselAccess(const std::string& mission_id, const CallContext& ctx);
  absl::StatusOr<v1::Mission> GetMission(const v1::GetMissionRequest& request,
                                         const CallContext& ctx);
  absl::StatusOr<v1::ListMissionsResponse> ListMissions(const v1::ListMissionsRequest& request,
                                                        const CallContext& ctx);
  absl::StatusOr<v1::Mission> CancelMission(const v1::CancelMissionRequest& request,
                                            const CallContext& ctx);
  // A chart was deleted: the engine drops its routings of it.
  void ForgetChart(const std::string& chart_id) { adapter_.ForgetChart(chart_id); }
  // Ends OK when the mission reached a final state and everything was sent;
  // Unavailable when the server shuts down; Cancelled when the client left.

  absl::Status WatchMission(const v1::WatchMissionRequest& request, const CallContext& ctx,
                            const StreamSink<v1::MissionEvent>& sink);
  absl::StatusOr<v1::ReportFeedbackResponse> ReportFeedback(
      const v1::ReportFeedbackRequest& request, const CallContext& ctx);
  absl::StatusOr<v1::RequestReplanResponse> RequestReplan(const v1::RequestReplanRequest& request,
                                                          const CallContext& ctx);
  // Stored feedback, a page at a time in arrival order (storage's cursor).
  absl::StatusOr<v1::ListFeedbackResponse> ListFeedback(const v1::ListFeedbackRequest& request,
                                                        const CallContext& ctx);

  // Ends watch streams, cancels background replans, joins the threads and
  // hands this process's work leases back.
  void Shutdown();

  MissionNotifier& notifier() { return notifier_; }
  const std::string& holder() const { return holder_; }

 private:
  struct ReplanJob {
    std::string mission_id;
    std::string reason;
    int base_version = 0;  // the plan version the trigger was about
    // Set when the work was claimed by the sweeper (Cluster only).
    std::optional<storage::WorkLease> lease;
  };

  std::shared_ptr<std::mutex> MissionLock(const std::string& mission_id);
  // Shutdown() was called or the server cancels all work.
  bool ShuttingDown();
  absl::StatusOr<MissionRuntimeState> LoadRuntime(const std::string& mission_id);
  // Replans now; `run` executes the engine call (on the pool or inline).
  absl::StatusOr<v1::PlanVersion> Replan(
      const std::string& mission_id, const std::string& reason, const StopToken& stop,
      const std::function<absl::Status(std::function<void()>)>& run, bool* stopped,
      const std::optional<storage::WorkFence>& fence = std::nullopt);
  // Sets the state and logs `message`; `audit` (an audited call's row) is
  // stored in the same transaction.
  absl::Status SetState(const std::string& mission_id, mission::MissionState state,
                        const std::string& message, const std::string& failure_reason = "",
                        const std::optional<storage::WorkFence>& fence = std::nullopt,
                        std::optional<storage::AuditRecord> audit = std::nullopt);
  // REPLANNING -> ACTIVE with `message` logged; a mission cancelled
  // meanwhile keeps its state (only the message is logged).
  void EndReplanning(const std::string& mission_id, const std::string& message,
                     const std::optional<storage::WorkFence>& fence = std::nullopt);
  void BackgroundLoop();
  // One triggered replan (without Cluster: as it is).
  void RunJob(ReplanJob job, const StopToken& stop);
  // RequestReplan without Cluster: replans at once.
  absl::StatusOr<v1::PlanVersion> LocalOperatorReplan(const std::string& mission_id,
                                                      const std::string& reason,
                                                      const CallContext& ctx);
  // RequestReplan with Cluster: requests and claims the mission's work
  // (waiting while another replan holds it), replans under the lease,
  // completes it, or hands it back when this process shuts down.
  absl::StatusOr<v1::PlanVersion> LeasedOperatorReplan(const std::string& mission_id,
                                                       const std::string& reason,
                                                       const CallContext& ctx);
  // Cluster: claims the job's work (unless the sweeper did), replans under
  // the lease and completes it, again while requests came meanwhile.
  void RunLeasedJob(ReplanJob job, const StopToken& stop);
  // Cluster: claims work nobody holds when this process is idle.
  void Sweep();
  // Cluster: renews the held leases; a lost one cancels its replan.
  void RenewLoop();

  storage::MissionRepository& repo_;
  WorkPool& pool_;
  StopToken root_;
  MissionAdapter adapter_;
  Options options_;
  Cluster cluster_;
  std::string holder_;
  MissionNotifier notifier_;

  std::mutex locks_mu_;
  std::map<std::string, std::shared_ptr<std::mutex>> locks_;

  std::mutex jobs_mu_;
  std::condition_variable jobs_cv_;
  std::condition_variable renew_cv_;
  std::deque<ReplanJob> jobs_;
  std::map<std::string, StopToken> running_replans_;  // mission -> token of its background replan
  // mission -> base version of its running background replan. A trigger for
  // a base version already pending or running is the same situation
  // reported twice (two feedbacks in one step): it must not replan again.
  std::map<std::string, int> running_bases_;
  // Cluster: mission -> stop token of the operator's replan holding its lease.
  std::map<std::string, StopToken> operator_replans_;
  bool stopping_ = false;
  bool leases_released_ = false;
  // Cluster: leases held now, renewed by renewer_.
  std::map<std::string, storage::WorkLease> held_;
  std::thread background_;
  std::thread renewer_;
};

// The API view of a stored mission.
v1::Mission MissionFromRecord(const storage::MissionRecord& record);
bool IsFinalState(int state);

}  // namespace seaplan::server
