// Persistence interfaces of the seaplan server: charts, missions, plan
// versions, feedback and the mission log.
//
// Overview
//   The server talks to storage only through these abstract repositories, so
//   the backend is chosen at start-up without touching the service layer:
//   SQLite (sqlite_store.h, one process, the embedded default) or PostgreSQL
//   (postgres_store.h, any number of server processes on one database);
//   open_store.h picks one from a setting. Both apply the same numbered
//   schema migrations and give the guarantees below. Records are plain structs; structured payloads
//   (the mission spec, a plan version, a feedback report, chart summaries) are opaque byte blobs
//   that the caller serialises (the server stores serialised seaplan.v1 protos), so storage never
//   interprets them.
//
// Durability and atomicity
//   Every method that writes commits before it returns OK: when a caller has
//   an OK it may acknowledge the write to its client. Every method that
//   writes several rows (a mission with its first version and log events, a
//   feedback report with its log events and the mission update) does so in
//   one transaction: on any error nothing of it is stored.
//
// Audited writes
//   The writes of audited actions (a chart, a mission, a mission update, a
//   token, a revocation) take the AuditRecord of the action and append it in
//   the same transaction: the change and its audit row are stored together
//   or not at all (a failing audit insert rolls the change back; a crash
//   leaves neither or both).
//
// Errors
//   NotFound (no such mission / chart / version), AlreadyExists (duplicate
//   id or request id), Aborted (a concurrent writer got there first, e.g. the
//   expected plan version is no longer next), InvalidArgument (bad page
//   token, a value a constraint rejects), Internal / Unavailable (the
//   database itself failed).
//
// Several processes: on PostgreSQL, writers in different processes are
//   serialised per mission by row locks and unique constraints (plan
//   versions stay 1, 2, 3 ... without gap or duplicate, a feedback report is
//   stored once), WorkLeaseRepository hands each mission's work to one
//   holder, and ChangeFeed wakes watchers of every process.
//
// Thread-safety: implementations must be safe to call from any thread.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "seaplan/common/status.h"

namespace seaplan::storage {

// Milliseconds since the Unix epoch (UTC).
using TimestampMs = std::int64_t;

// A page of a listing. `next_after` is the cursor to pass as `after` for the
// next page; 0 when this page is the last one.
template <typename T>
struct Page {
  std::vector<T> items;
  std::int64_t next_after = 0;
};

// Who did what, and when: one row per audited action (see "Audited writes").
struct AuditRecord {
  std::int64_t seq = 0;  // assigned by storage; listing cursor
  TimestampMs time_ms = 0;
  std::string token_id;  // the caller's token; empty for the server itself
  std::string role;
  std::string vessel_id;
  std::string action;  // e.g. "CreateMission", "RevokeToken"
  std::string target;  // what it acted on: a mission, chart or token id
  std::string detail;
};

struct ChartRecord {
  std::int64_t seq = 0;  // insertion order (assigned by storage; listing cursor)
  std::string id;
  std::string name;
  int format = 0;            // seaplan.v1.ChartFormat value
  std::string options;       // opaque blob (load options)
  std::string summary;       // opaque blob (obstacle summary)
  std::string obstacles;     // opaque blob (serialised obstacle map); may be large
  std::string source_files;  // opaque blob (original upload); may be empty
  TimestampMs created_at_ms = 0;
};

// Which missions keep a chart from being deleted: those whose state is one
// of `active_states` and whose spec blob `spec_uses_chart` says refers to
// the chart (storage does not read specs). Checked inside the deleting
// transaction against every committed mission (PostgreSQL: with mission
// writes locked out meanwhile). A mission being created on the chart
// cannot slip past it: MissionRepository::Create checks, in its own
// transaction, that the chart it is given (its `chart_id`) still exists (PostgreSQL: locking
// the chart row against a deletion until it commits), so whichever commits
// second sees the other: the deletion is refused for the new mission, or
// the creation for the deleted chart.
struct ChartUse {
  std::vector<int> active_states;
  std::function<bool(const std::string& spec, const std::string& chart_id)> spec_uses_chart;
};

class ChartRepository {
 public:
  virtual ~ChartRepository() = default;
  // Stores a new chart (seq is assigned), and `audit` when given in the
  // same transaction. AlreadyExists when the id is taken.
  virtual absl::StatusOr<ChartRecord> Insert(ChartRecord chart,
                                             const AuditRecord* audit = nullptr) = 0;
  // NotFound when absent. `with_blobs` false leaves obstacles and
  // source_files empty (listing screens do not need megabytes).
  virtual absl::StatusOr<ChartRecord> Get(const std::string& id, bool with_blobs) = 0;
  // Charts with seq > after, oldest first, at most page_size (1..1000), without blobs.
  virtual absl::StatusOr<Page<ChartRecord>> List(int page_size, std::int64_t after) = 0;
  // Deletes the chart and appends `audit` (when given) in one transaction,
  // unless a mission still uses it (see ChartUse): then FailedPrecondition
  // naming those missions, and nothing changes. NotFound when absent.
  virtual absl::Status Delete(const std::string& id, const ChartUse& use,
                              const AuditRecord* audit = nullptr) = 0;
};

struct MissionRecord {
  std::int64_t seq = 0;  // insertion order (assigned by storage)
  std::string id;
  std::string name;
  std::string vessel_id;
  std::string request_id;   // client idempotency key; empty = none
  std::string spec;         // opaque blob (the mission spec)
  int state = 0;            // seaplan.v1.MissionState value
  int current_version = 0;  // 0 = no plan yet
  TimestampMs created_at_ms = 0;
  TimestampMs updated_at_ms = 0;
  std::string last_state;  // opaque blob (last reported ship state); may be empty
  std::vector<std::string> completed_tasks;
  std::string failure_reason;
};

// Work a mission needs done by some server process (a replan), recorded in
// the database so that it survives the process that accepted it.
struct WorkRequest {
  std::string reason;
  int base_version = 0;  // the plan version the request is about
};

// The lease a write is made under (WorkLeaseRepository): the write is
// refused with Aborted unless the mission's work item still has this holder
// and token, i.e. nobody took the work over since the claim.
struct WorkFence {
  std::string holder;
  std::int64_t token = 0;
};

// A partial update of a mission; unset fields keep their value.
struct MissionUpdate {
  std::optional<int> state;
  std::optional<std::string> last_state;
  std::optional<std::vector<std::string>> completed_tasks;
  std::optional<std::string> failure_reason;
  // Records work for the mission (WorkLeaseRepository::Request) in the same
  // transaction, so an acknowledged report that needs a replan cannot lose it.
  std::optional<WorkRequest> request_work;
  // Checked first, in the same transaction (fencing a stale lease holder).
  std::optional<WorkFence> fence;
  // Appended to the audit log in the same transaction (an audited action:
  // a cancel, a replan request).
  std::optional<AuditRecord> audit;
};

struct PlanVersionRecord {
  std::string mission_id;
  int version = 0;  // 1, 2, 3 ... per mission, never reused, never changed
  std::string reason;
  TimestampMs created_at_ms = 0;
  std::string content;  // opaque blob (the plan version)
  // Opaque state the mission engine keeps with a version (e.g. locations a
  // replan added); empty when it keeps none.
  std::string engine_state;
};

struct FeedbackRecord {
  std::string mission_id;
  std::string vessel_id;
  std::int64_t sequence_number = 0;  // unique per vessel
  int kind = 0;                      // seaplan.v1.Feedback.Kind value
  std::string payload;               // opaque blob (the report)
  TimestampMs received_at_ms = 0;
  std::int64_t seq = 0;  // arrival order (assigned by storage; listing cursor)
};

// A log event to append; the event id is assigned by storage.
struct NewLogEvent {
  TimestampMs time_ms = 0;
  double mission_time_s = 0.0;
  std::string source;  // "server" or a vessel id; must not be empty
  std::string message;
};

struct LogEventRecord {
  std::string mission_id;
  std::int64_t event_id = 0;  // 1, 2, 3 ... per mission
  TimestampMs time_ms = 0;
  double mission_time_s = 0.0;
  std::string source;
  std::string message;
};

class MissionRepository {
 public:
  virtual ~MissionRepository() = default;

  // Stores a new mission together with its first plan version (version must
  // be 1; mission.current_version is set to 1), log events and `audit`
  // (when given), atomically. AlreadyExists when the id or the non-empty
  // request_id is taken. `chart_id`, when not empty, is the chart the
  // mission's spec names: NotFound, with nothing stored, unless it exists
  // when this transaction commits (see ChartUse).
  virtual absl::Status Create(const MissionRecord& mission, const PlanVersionRecord& first_version,
                              const std::vector<NewLogEvent>& events,
                              const AuditRecord* audit = nullptr,
                              const std::string& chart_id = {}) = 0;
  virtual absl::StatusOr<MissionRecord> Get(const std::string& id) = 0;
  // The mission created with this idempotency key, if any.
  virtual absl::StatusOr<std::optional<MissionRecord>> FindByRequestId(
      const std::string& request_id) = 0;
  // Missions with seq > after (oldest first), optionally only in `state`
  // (0 = all), at most page_size (1..1000).
  virtual absl::StatusOr<Page<MissionRecord>> List(int state, int page_size,
                                                   std::int64_t after) = 0;

  // Applies `update` and appends `events` atomically. NotFound when absent.
  virtual absl::Status Update(const std::string& id, const MissionUpdate& update,
                              const std::vector<NewLogEvent>& events) = 0;

  // Appends plan version `version.version`, which must be the mission's
  // current_version + 1 (Aborted otherwise: someone else appended first),
  // sets current_version to it, applies `update` and appends `events`, all
  // in one transaction. Versions are immutable once stored.
  virtual absl::Status AppendVersion(const PlanVersionRecord& version, const MissionUpdate& update,
                                     const std::vector<NewLogEvent>& events) = 0;
  virtual absl::StatusOr<PlanVersionRecord> GetVersion(const std::string& mission_id,
                                                       int version) = 0;
  // Versions > after_version in order, at most `limit`.
  virtual absl::StatusOr<std::vector<PlanVersionRecord>> ListVersions(const std::string& mission_id,
                                                                      int after_version,
                                                                      int limit) = 0;

  // Stores a feedback report unless (vessel_id, sequence_number) is already
  // stored. When new: also applies `update` and appends `events` in the same
  // transaction, and returns true. When already stored: changes nothing and
  // returns false (the caller answers "duplicate").
  virtual absl::StatusOr<bool> RecordFeedback(const FeedbackRecord& feedback,
                                              const MissionUpdate& update,
                                              const std::vector<NewLogEvent>& events) = 0;
  virtual absl::StatusOr<std::optional<FeedbackRecord>> FindFeedback(
      const std::string& vessel_id, std::int64_t sequence_number) = 0;
  // The latest `limit` feedback reports of a mission, in arrival order.
  virtual absl::StatusOr<std::vector<FeedbackRecord>> ListFeedback(const std::string& mission_id,
                                                                   int limit) = 0;
  // A mission's feedback reports with seq > after, in arrival order, at most
  // page_size (1..1000). An unknown mission has none.
  virtual absl::StatusOr<Page<FeedbackRecord>> ListFeedbackPage(const std::string& mission_id,
                                                                std::int64_t after,
                                                                int page_size) = 0;

  // Appends log events (ids assigned in order) and returns them.
  virtual absl::StatusOr<std::vector<LogEventRecord>> AppendEvents(
      const std::string& mission_id, const std::vector<NewLogEvent>& events) = 0;
  // Events with id > after_event_id in order, at most `limit`.
  virtual absl::StatusOr<std::vector<LogEventRecord>> ListEvents(const std::string& mission_id,
                                                                 std::int64_t after_event_id,
                                                                 int limit) = 0;
};

// A mission's work with an expiring lease: exactly one holder (a server
// process, named by a unique id) runs a mission's work at a time, and the
// work of a holder that died is taken over once its lease expires.
//
// A mission has at most one work item. Request() records that work is
// needed; requests that arrive while the item is pending or running are
// counted into it, so none is lost: Complete() covers the requests seen at
// claim time and leaves the item pending when more came meanwhile.
// Claim()/ClaimNext() hand a pending item to a holder for `ttl`; the holder
// Renew()s while it works, Complete()s when done, or Release()s to hand it
// back unfinished (graceful shutdown). Once a lease has expired anyone may
// claim the item; every claim increments the item's token, and the old
// holder's Renew/Release/Complete with its stale token answer Aborted.
//
// Expiry is measured on the database's clock on PostgreSQL (processes on
// machines with skewed clocks agree) and on this process's clock on SQLite.
struct WorkLease {
  std::string mission_id;
  std::string reason;                 // of the latest request
  int base_version = 0;               // of the latest request
  std::string holder;                 // empty when nobody holds the item
  std::int64_t token = 0;             // grows at every claim of this mission's work
  std::int64_t requests = 0;          // requests ever made for the mission
  std::int64_t claimed_requests = 0;  // requests the current claim covers
  std::int64_t done_requests = 0;     // requests covered by completed runs
  TimestampMs expires_at_ms = 0;      // 0 when nobody holds the item
  bool pending() const { return requests > done_requests; }
};

class WorkLeaseRepository {
 public:
  virtual ~WorkLeaseRepository() = default;
  // Records work for a mission (NotFound when absent). Returns true when the
  // mission had no pending work, false when the request joined pending work.
  virtual absl::StatusOr<bool> Request(const std::string& mission_id,
                                       const WorkRequest& request) = 0;
  // Claims this mission's pending work for `holder`; nullopt when there is
  // none or another lease on it has not expired.
  virtual absl::StatusOr<std::optional<WorkLease>> Claim(const std::string& mission_id,
                                                         const std::string& holder,
                                                         std::chrono::milliseconds ttl) = 0;
  // Records a request about the mission's current version (read in the
  // same transaction) and claims the work for `holder`, in one transaction,
  // so that no other process can take the request first: the lease covers
  // every request pending so far. When a live lease of any holder (this one
  // included) is on the work, nothing is recorded and the answer is
  // nullopt. NotFound when the mission is absent.
  virtual absl::StatusOr<std::optional<WorkLease>> RequestAndClaim(
      const std::string& mission_id, const std::string& reason, const std::string& holder,
      std::chrono::milliseconds ttl) = 0;
  // Claims up to `limit` (1..1000) pending items that nobody holds or whose
  // lease expired, oldest request first. Concurrent callers get disjoint
  // items (PostgreSQL: FOR UPDATE SKIP LOCKED).
  virtual absl::StatusOr<std::vector<WorkLease>> ClaimNext(const std::string& holder,
                                                           std::chrono::milliseconds ttl,
                                                           int limit) = 0;
  // Extends a lease to now + ttl. Aborted when it was lost.
  virtual absl::StatusOr<WorkLease> Renew(const WorkLease& lease,
                                          std::chrono::milliseconds ttl) = 0;
  // Hands the work back unfinished: pending and free at once. Aborted when
  // the lease was lost.
  virtual absl::Status Release(const WorkLease& lease) = 0;
  // The work is done for the requests the claim covered. Returns true when
  // the mission still has pending work (requests came meanwhile). Aborted
  // when the lease was lost (someone else may have done the work).
  virtual absl::StatusOr<bool> Complete(const WorkLease& lease) = 0;
  // Releases every lease of `holder` (graceful shutdown); returns how many.
  virtual absl::StatusOr<int> ReleaseAll(const std::string& holder) = 0;
  // The mission's work item, if it ever had one.
  virtual absl::StatusOr<std::optional<WorkLease>> Get(const std::string& mission_id) = 0;
};

// Wakes watchers when a mission changes. Every commit that touches a mission
// (its row, a plan version, feedback, a log event) increments the mission's
// generation AFTER the commit, in every process that has the database open
// (PostgreSQL: LISTEN/NOTIFY; SQLite: in this process). A watcher reads the
// generation, then reads storage, then waits for the generation to move: a
// commit the read missed moves it afterwards, so nothing is missed. When
// notifications may have been lost (the PostgreSQL listener reconnected)
// every generation moves, and watchers re-read.
class ChangeFeed {
 public:
  virtual ~ChangeFeed() = default;
  virtual std::uint64_t Generation(const std::string& mission_id) = 0;
  // Waits until the generation differs from `seen`, `timeout` passes or the
  // store is closed; returns the current generation.
  virtual std::uint64_t Wait(const std::string& mission_id, std::uint64_t seen,
                             std::chrono::milliseconds timeout) = 0;
};

// An API token. The token itself is never stored: only the SHA-256 of its
// secret part, so a copy of the database does not let anyone in.
struct TokenRecord {
  std::string id;           // public part of the token, unique
  std::string secret_hash;  // hex SHA-256 of the secret part
  std::string role;         // "admin", "operator", "viewer" or "vessel"
  std::string vessel_id;    // the vessel a "vessel" token is bound to; empty otherwise
  std::string description;
  std::string created_by;  // token id of the creator; empty for the first admin token
  TimestampMs created_at_ms = 0;
  TimestampMs expires_at_ms = 0;  // 0 = never expires
  TimestampMs revoked_at_ms = 0;  // 0 = not revoked
};

class TokenRepository {
 public:
  virtual ~TokenRepository() = default;
  // Stores the token and `audit` (when given) in one transaction.
  // AlreadyExists when the id is taken.
  virtual absl::Status Insert(const TokenRecord& token, const AuditRecord* audit = nullptr) = 0;
  // NotFound when absent.
  virtual absl::StatusOr<TokenRecord> Get(const std::string& id) = 0;
  // Every token (revoked ones too), oldest first.
  virtual absl::StatusOr<std::vector<TokenRecord>> List() = 0;
  // Marks the token revoked at `at_ms` (a second revocation keeps the first
  // time), appends `audit` (when given) in the same transaction and returns
  // the token. NotFound when absent (nothing is stored).
  virtual absl::StatusOr<TokenRecord> Revoke(const std::string& id, TimestampMs at_ms,
                                             const AuditRecord* audit = nullptr) = 0;
  // Stores `admin` (a token of role "admin") unless a usable admin token
  // (not revoked, not expired at `now_ms`) is stored, and returns whether it
  // stored it. The check and the insert are one transaction that excludes
  // every other call of this method on the database, from any process: of
  // servers starting at once on an empty database, exactly one creates the
  // first admin token.
  virtual absl::StatusOr<bool> InsertFirstAdmin(const TokenRecord& admin, TimestampMs now_ms) = 0;
};

// The audit log (AuditRecord); audited writes append their row themselves.
class AuditRepository {
 public:
  virtual ~AuditRepository() = default;
  // Appends a record (seq is assigned) and returns it.
  virtual absl::StatusOr<AuditRecord> Append(AuditRecord record) = 0;
  // Records with seq > after, oldest first, at most page_size (1..1000).
  virtual absl::StatusOr<Page<AuditRecord>> ListAudit(int page_size, std::int64_t after) = 0;
};

// The schema version this binary migrates to (the same numbering on every
// backend).
int LatestSchemaVersion();

// One open database: the repositories over it.
class Store {
 public:
  virtual ~Store() = default;
  virtual ChartRepository& charts() = 0;
  virtual MissionRepository& missions() = 0;
  virtual WorkLeaseRepository& work() = 0;
  virtual ChangeFeed& changes() = 0;
  virtual TokenRepository& tokens() = 0;
  virtual AuditRepository& audit() = 0;
  // Flushes and closes; later calls fail with FailedPrecondition. Also done
  // by the destructor.
  virtual absl::Status Close() = 0;
};

}  // namespace seaplan::storage
