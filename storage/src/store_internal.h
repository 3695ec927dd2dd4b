// What the SQLite and PostgreSQL backends share: the schema history (one
// numbering for both), the encoding of completed tasks, argument checks, the
// clock, and the in-process change feed. Not part of the public API.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "seaplan/storage/repositories.h"

namespace seaplan::storage::internal {

// One entry per schema version, in order. Each backend has its own SQL for
// every entry (the dialects differ) under the same number and description;
// a released entry is never edited, a change is a new entry.
struct SchemaStep {
  int version;
  const char* description;
};
std::span<const SchemaStep> SchemaHistory();

// Completed task ids are stored as one text, '\n'-separated.
std::string JoinTasks(const std::vector<std::string>& tasks);

absl::Status CheckPageSize(int page_size);
absl::Status CheckLeaseArguments(const std::string& holder, std::chrono::milliseconds ttl);

// Milliseconds since the Unix epoch on this process's clock.
TimestampMs NowMs();
// The latest event time, or `fallback` when later (or there are no events).
TimestampMs LatestTime(const std::vector<NewLogEvent>& events, TimestampMs fallback);

// "<what> '<id>' not found".
std::string NotFoundMessage(const std::string& what, const std::string& id);

// The FailedPrecondition of a chart deletion refused because `missions`
// use the chart.
absl::Status ChartInUseError(const std::string& chart_id, const std::vector<std::string>& missions);

// `states` as an SQL list "(1, 2, 3)"; "(NULL)" when empty (matches nothing).
std::string SqlIntList(const std::vector<int>& states);
// Aborted: a write fenced by a lease that is no longer held.
absl::Status LostLeaseError(const std::string& mission_id, const WorkFence& fence);

// A query that returns a row when a usable admin token is stored: role
// admin, not revoked, not expired at the time bound to the statement's first
// parameter, which the backend's SQL writes as `now_param` ("?1", "$1").
// Both backends' InsertFirstAdmin use it; the authenticator
// (server/auth/authenticator.cc) refuses a revoked or expired token by the
// same rule, so keep the two alike.
std::string UsableAdminTokenQuery(const char* now_param);

// ---- Column lists and row readers shared by the backends ----
// A `Row` offers Int(col), Real(col) and Bytes(col) (text and blobs as
// bytes), columns 0-based in the order of the list (or of the comment).
inline constexpr const char* kMissionColumns =
    "seq, id, name, vessel_id, COALESCE(request_id, ''), spec, state, current_version, "
    "created_at_ms, updated_at_ms, last_state, completed_tasks, failure_reason";
inline constexpr const char* kWorkColumns =
    "mission_id, reason, base_version, COALESCE(holder, ''), token, requests, claimed_requests, "
    "done_requests, COALESCE(lease_expires_at_ms, 0)";

inline constexpr const char* kTokenColumns =
    "id, secret_hash, role, vessel_id, description, created_by, created_at_ms, expires_at_ms, "
    "revoked_at_ms";
inline constexpr const char* kAuditColumns =
    "seq, time_ms, token_id, role, vessel_id, action, target, detail";

template <typename Row>
TokenRecord ReadToken(const Row& r) {
  return {r.Bytes(0), r.Bytes(1), r.Bytes(2), r.Bytes(3), r.Bytes(4),
          r.Bytes(5), r.Int(6),   r.Int(7),   r.Int(8)};
}

template <typename Row>
AuditRecord ReadAudit(const Row& r) {
  return {r.Int(0),   r.Int(1),   r.Bytes(2), r.Bytes(3),
          r.Bytes(4), r.Bytes(5), r.Bytes(6), r.Bytes(7)};
}

// seq, id, name, format, options, summary, created_at_ms[, obstacles, source_files]
template <typename Row>
ChartRecord ReadChart(const Row& r, bool with_blobs) {
  ChartRecord c;
  c.seq = r.Int(0);
  c.id = r.Bytes(1);
  c.name = r.Bytes(2);
  c.format = static_cast<int>(r.Int(3));
  c.options = r.Bytes(4);
  c.summary = r.Bytes(5);
  c.created_at_ms = r.Int(6);
  if (with_blobs) {
    c.obstacles = r.Bytes(7);
    c.source_files = r.Bytes(8);
  }
  return c;
}

std::vector<std::string> SplitTasks(const std::string& text);

template <typename Row>
MissionRecord ReadMission(const Row& r) {
  MissionRecord m;
  m.seq = r.Int(0);
  m.id = r.Bytes(1);
  m.name = r.Bytes(2);
  m.vessel_id = r.Bytes(3);
  m.request_id = r.Bytes(4);
  m.spec = r.Bytes(5);
  m.state = static_cast<int>(r.Int(6));
  m.current_version = static_cast<int>(r.Int(7));
  m.created_at_ms = r.Int(8);
  m.updated_at_ms = r.Int(9);
  m.last_state = r.Bytes(10);
  m.completed_tasks = SplitTasks(r.Bytes(11));
  m.failure_reason = r.Bytes(12);
  return m;
}

// mission_id, version, reason, created_at_ms, content, engine_state
template <typename Row>
PlanVersionRecord ReadVersion(const Row& r) {
  return {r.Bytes(0), static_cast<int>(r.Int(1)), r.Bytes(2), r.Int(3), r.Bytes(4), r.Bytes(5)};
}

// mission_id, vessel_id, sequence_number, kind, payload, received_at_ms, seq
inline constexpr char kFeedbackColumns[] =
    "mission_id, vessel_id, sequence_number, kind, payload, received_at_ms, seq";
template <typename Row>
FeedbackRecord ReadFeedback(const Row& r) {
  return {r.Bytes(0), r.Bytes(1), r.Int(2), static_cast<int>(r.Int(3)),
          r.Bytes(4), r.Int(5),   r.Int(6)};
}

// mission_id, event_id, time_ms, mission_time_s, source, message
template <typename Row>
LogEventRecord ReadEvent(const Row& r) {
  return {r.Bytes(0), r.Int(1), r.Int(2), r.Real(3), r.Bytes(4), r.Bytes(5)};
}

template <typename Row>
WorkLease ReadWork(const Row& r) {
  WorkLease w;
  w.mission_id = r.Bytes(0);
  w.reason = r.Bytes(1);
  w.base_version = static_cast<int>(r.Int(2));
  w.holder = r.Bytes(3);
  w.token = r.Int(4);
  w.requests = r.Int(5);
  w.claimed_requests = r.Int(6);
  w.done_requests = r.Int(7);
  w.expires_at_ms = r.Int(8);
  return w;
}

// The lease logic both backends share; each supplies the two statements.
class WorkLeaseBase : public WorkLeaseRepository {
 public:
  absl::StatusOr<std::optional<WorkLease>> Claim(const std::string& mission_id,
                                                 const std::string& holder,
                                                 std::chrono::milliseconds ttl) final;
  absl::StatusOr<std::optional<WorkLease>> RequestAndClaim(const std::string& mission_id,
                                                           const std::string& reason,
                                                           const std::string& holder,
                                                           std::chrono::milliseconds ttl) final;
  absl::StatusOr<std::vector<WorkLease>> ClaimNext(const std::string& holder,
                                                   std::chrono::milliseconds ttl, int limit) final;
  absl::StatusOr<WorkLease> Renew(const WorkLease& lease, std::chrono::milliseconds ttl) final;
  absl::Status Release(const WorkLease& lease) final;
  absl::StatusOr<bool> Complete(const WorkLease& lease) final;

 protected:
  enum class LeaseChange { kRenew, kRelease, kComplete };
  // The SET clause of a change; `new_expiry` is the backend's expression
  // for now + ttl (used by kRenew).
  static std::string SetClause(LeaseChange change, const std::string& new_expiry);
  // Claims pending items that are free or expired (of `mission_id`, or of
  // any mission when empty), at most `limit`, oldest request first.
  virtual absl::StatusOr<std::vector<WorkLease>> ClaimPending(const std::string& mission_id,
                                                              const std::string& holder,
                                                              std::chrono::milliseconds ttl,
                                                              int limit) = 0;
  // Records a request (`reason`, the current version) and claims the
  // mission's item unless a live lease is on it (then nothing is written
  // and nothing returned), in one transaction.
  virtual absl::StatusOr<std::vector<WorkLease>> RequestAndClaimFree(
      const std::string& mission_id, const std::string& reason, const std::string& holder,
      std::chrono::milliseconds ttl) = 0;
  // Applies `change` if `lease` (holder and token) still holds the item;
  // the updated row, or nothing when the lease was lost.
  virtual absl::StatusOr<std::vector<WorkLease>> UpdateHeld(const WorkLease& lease,
                                                            LeaseChange change,
                                                            std::chrono::milliseconds ttl) = 0;

 private:
  absl::StatusOr<WorkLease> Change(const WorkLease& lease, LeaseChange change,
                                   std::chrono::milliseconds ttl);
};

// The in-process ChangeFeed: a generation per mission plus an epoch that
// BumpAll() moves for every mission at once. The SQLite store bumps it after
// each commit; the PostgreSQL store's listener thread bumps it for every
// notification. Thread-safe.
class LocalChangeFeed final : public ChangeFeed {
 public:
  std::uint64_t Generation(const std::string& mission_id) override;
  std::uint64_t Wait(const std::string& mission_id, std::uint64_t seen,
                     std::chrono::milliseconds timeout) override;
  void Bump(const std::string& mission_id);
  void BumpAll();
  // Wakes every waiter; later waits return at once.
  void Close();

 private:
  std::uint64_t GenerationLocked(const std::string& mission_id);
  std::mutex mu_;
  std::condition_variable cv_;
  std::unordered_map<std::string, std::uint64_t> generation_;
  std::uint64_t epoch_ = 0;
  bool closed_ = false;
};

}  // namespace seaplan::storage::internal
