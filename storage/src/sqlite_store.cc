#include "seaplan/storage/sqlite_store.h"

#include <sqlite3.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <optional>
#include <string_view>
#include <thread>

#include "absl/strings/str_cat.h"
#include "seaplan/common/log.h"
#include "store_internal.h"

namespace seaplan::storage {
namespace {

using internal::CheckPageSize;
using internal::JoinTasks;
using internal::kMissionColumns;
using internal::LatestTime;
using internal::NotFoundMessage;
using internal::NowMs;
using internal::SplitTasks;

// The SQLite migrations, one per entry of internal::SchemaHistory() with the
// same version. NEVER edit a released entry: add a new one. Each runs in one
// transaction with the bump of PRAGMA user_version to `version`.
struct Migration {
  int version;
  const char* sql;
};

constexpr Migration kMigrations[] = {
    {1, R"sql(
CREATE TABLE charts (
  seq INTEGER PRIMARY KEY AUTOINCREMENT,
  id TEXT NOT NULL UNIQUE,
  name TEXT NOT NULL,
  format INTEGER NOT NULL,
  options BLOB NOT NULL,
  summary BLOB NOT NULL,
  obstacles BLOB NOT NULL,
  created_at_ms INTEGER NOT NULL);
CREATE TABLE missions (
  seq INTEGER PRIMARY KEY AUTOINCREMENT,
  id TEXT NOT NULL UNIQUE,
  name TEXT NOT NULL,
  vessel_id TEXT NOT NULL,
  spec BLOB NOT NULL,
  state INTEGER NOT NULL,
  current_version INTEGER NOT NULL DEFAULT 0,
  created_at_ms INTEGER NOT NULL,
  updated_at_ms INTEGER NOT NULL,
  last_state BLOB NOT NULL DEFAULT x'',
  failure_reason TEXT NOT NULL DEFAULT '');
CREATE INDEX missions_by_state ON missions(state, seq);
CREATE TABLE plan_versions (
  mission_id TEXT NOT NULL REFERENCES missions(id),
  version INTEGER NOT NULL CHECK (version >= 1),
  reason TEXT NOT NULL,
  created_at_ms INTEGER NOT NULL,
  content BLOB NOT NULL,
  PRIMARY KEY (mission_id, version)) WITHOUT ROWID;
CREATE TRIGGER plan_versions_no_update BEFORE UPDATE ON plan_versions
  BEGIN SELECT RAISE(ABORT, 'plan versions are immutable'); END;
CREATE TRIGGER plan_versions_no_delete BEFORE DELETE ON plan_versions
  BEGIN SELECT RAISE(ABORT, 'plan versions are immutable'); END;
CREATE TABLE feedback (
  seq INTEGER PRIMARY KEY AUTOINCREMENT,
  mission_id TEXT NOT NULL REFERENCES missions(id),
  vessel_id TEXT NOT NULL,
  sequence_number INTEGER NOT NULL,
  kind INTEGER NOT NULL,
  payload BLOB NOT NULL,
  received_at_ms INTEGER NOT NULL,
  UNIQUE (vessel_id, sequence_number));
CREATE INDEX feedback_by_mission ON feedback(mission_id, seq);
CREATE TABLE log_events (
  mission_id TEXT NOT NULL REFERENCES missions(id),
  event_id INTEGER NOT NULL CHECK (event_id >= 1),
  time_ms INTEGER NOT NULL,
  mission_time_s REAL NOT NULL,
  source TEXT NOT NULL CHECK (length(source) > 0),
  message TEXT NOT NULL,
  PRIMARY KEY (mission_id, event_id)) WITHOUT ROWID;
)sql"},
    {2, R"sql(
ALTER TABLE missions ADD COLUMN request_id TEXT;
CREATE UNIQUE INDEX missions_by_request_id ON missions(request_id) WHERE request_id IS NOT NULL;
ALTER TABLE missions ADD COLUMN completed_tasks TEXT NOT NULL DEFAULT '';
ALTER TABLE charts ADD COLUMN source_files BLOB NOT NULL DEFAULT x'';
ALTER TABLE plan_versions ADD COLUMN engine_state BLOB NOT NULL DEFAULT x'';
)sql"},
    // Change notifications need no schema on SQLite (one process: the store
    // wakes its own watchers after each commit).
    {3, R"sql(
CREATE TABLE mission_work (
  mission_id TEXT PRIMARY KEY REFERENCES missions(id),
  reason TEXT NOT NULL,
  base_version INTEGER NOT NULL,
  requested_at_ms INTEGER NOT NULL,
  requests INTEGER NOT NULL CHECK (requests >= 1),
  done_requests INTEGER NOT NULL DEFAULT 0,
  claimed_requests INTEGER NOT NULL DEFAULT 0,
  holder TEXT CHECK (holder IS NULL OR length(holder) > 0),
  token INTEGER NOT NULL DEFAULT 0,
  lease_expires_at_ms INTEGER,
  CHECK ((holder IS NULL) = (lease_expires_at_ms IS NULL))) WITHOUT ROWID;
CREATE INDEX mission_work_pending ON mission_work(requested_at_ms) WHERE requests > done_requests;
)sql"},
    {4, R"sql(
CREATE TABLE api_tokens (
  id TEXT PRIMARY KEY CHECK (length(id) > 0),
  secret_hash TEXT NOT NULL CHECK (length(secret_hash) = 64),
  role TEXT NOT NULL CHECK (role IN ('admin', 'operator', 'viewer', 'vessel')),
  vessel_id TEXT NOT NULL DEFAULT '',
  description TEXT NOT NULL DEFAULT '',
  created_by TEXT NOT NULL DEFAULT '',
  created_at_ms INTEGER NOT NULL,
  expires_at_ms INTEGER NOT NULL DEFAULT 0,
  revoked_at_ms INTEGER NOT NULL DEFAULT 0,
  CHECK ((role = 'vessel') = (length(vessel_id) > 0))) WITHOUT ROWID;
CREATE TABLE audit_log (
  seq INTEGER PRIMARY KEY AUTOINCREMENT,
  time_ms INTEGER NOT NULL,
  token_id TEXT NOT NULL,
  role TEXT NOT NULL,
  vessel_id TEXT NOT NULL,
  action TEXT NOT NULL CHECK (length(action) > 0),
  target TEXT NOT NULL,
  detail TEXT NOT NULL);
CREATE TRIGGER audit_log_no_update BEFORE UPDATE ON audit_log
  BEGIN SELECT RAISE(ABORT, 'the audit log is append-only'); END;
CREATE TRIGGER audit_log_no_delete BEFORE DELETE ON audit_log
  BEGIN SELECT RAISE(ABORT, 'the audit log is append-only'); END;
)sql"},
};
static_assert(std::size(kMigrations) == 4, "one SQLite migration per schema history entry");

absl::Status SqliteError(sqlite3* db, int rc, const char* what) {
  const std::string msg = absl::StrCat(what, ": ", db ? sqlite3_errmsg(db) : sqlite3_errstr(rc));
  switch (rc & 0xff) {
    case SQLITE_CONSTRAINT:
      if (rc == SQLITE_CONSTRAINT_UNIQUE || rc == SQLITE_CONSTRAINT_PRIMARYKEY) {
        return absl::AlreadyExistsError(msg);
      }
      return absl::InvalidArgumentError(msg);
    case SQLITE_BUSY:
    case SQLITE_LOCKED:
      return absl::UnavailableError(msg);
    // The disk, not the request: the transaction was rolled back whole and
    // the same call succeeds once an operator fixed the storage.
    case SQLITE_FULL:
      return absl::UnavailableError(
          absl::StrCat(msg,
                       " (the database's disk is full: nothing was stored; free space and "
                       "retry)"));
    case SQLITE_READONLY:
      return absl::UnavailableError(absl::StrCat(
          msg,
          " (the database is read-only: nothing was stored; make the database file, its -wal and "
          "-shm files and its folder writable and retry)"));
    case SQLITE_IOERR:
    case SQLITE_CANTOPEN:
      return absl::UnavailableError(absl::StrCat(
          msg, " (the database's storage failed: nothing was stored; check the disk and retry)"));
    default:
      return absl::InternalError(msg);
  }
}

// A prepared statement (RAII). Bind indexes are 1-based, columns 0-based.
class Stmt {
 public:
  Stmt(sqlite3* db, std::string_view sql) : db_(db) {
    const int rc =
        sqlite3_prepare_v2(db, sql.data(), static_cast<int>(sql.size()), &stmt_, nullptr);
    if (rc != SQLITE_OK) status_ = SqliteError(db, rc, "prepare");
  }
  ~Stmt() { sqlite3_finalize(stmt_); }
  Stmt(const Stmt&) = delete;
  Stmt& operator=(const Stmt&) = delete;

  const absl::Status& status() const { return status_; }

  Stmt& Int(int i, std::int64_t v) { return Check(sqlite3_bind_int64(stmt_, i, v)); }
  Stmt& Real(int i, double v) { return Check(sqlite3_bind_double(stmt_, i, v)); }
  Stmt& Text(int i, std::string_view v) {
    return Check(
        sqlite3_bind_text(stmt_, i, v.data(), static_cast<int>(v.size()), SQLITE_TRANSIENT));
  }
  Stmt& Blob(int i, std::string_view v) {
    // A zero-length blob must not bind as NULL (NOT NULL columns).
    if (v.empty()) return Check(sqlite3_bind_zeroblob(stmt_, i, 0));
    return Check(sqlite3_bind_blob64(stmt_, i, v.data(), v.size(), SQLITE_TRANSIENT));
  }
  Stmt& Null(int i) { return Check(sqlite3_bind_null(stmt_, i)); }

  // True when a row is available, false when done.
  absl::StatusOr<bool> Step() {
    if (!status_.ok()) return status_;
    const int rc = sqlite3_step(stmt_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    status_ = SqliteError(db_, sqlite3_extended_errcode(db_), "step");
    return status_;
  }
  // Runs a statement that returns no rows.
  absl::Status Run() { return Step().status(); }

  std::int64_t ColInt(int c) const { return sqlite3_column_int64(stmt_, c); }
  double ColReal(int c) const { return sqlite3_column_double(stmt_, c); }
  std::string ColText(int c) const {
    const auto* p = reinterpret_cast<const char*>(sqlite3_column_text(stmt_, c));
    return p ? std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(stmt_, c)))
             : std::string();
  }
  std::string ColBlob(int c) const {
    const auto* p = static_cast<const char*>(sqlite3_column_blob(stmt_, c));
    return p ? std::string(p, static_cast<std::size_t>(sqlite3_column_bytes(stmt_, c)))
             : std::string();
  }

 private:
  Stmt& Check(int rc) {
    if (rc != SQLITE_OK && status_.ok()) status_ = SqliteError(db_, rc, "bind");
    return *this;
  }
  sqlite3* db_;
  sqlite3_stmt* stmt_ = nullptr;
  absl::Status status_;
};

// A statement's current row as the shared row readers (store_internal.h)
// want it. sqlite3_column_blob gives a text column's bytes too.
struct StmtRow {
  const Stmt& s;
  std::int64_t Int(int c) const { return s.ColInt(c); }
  double Real(int c) const { return s.ColReal(c); }
  std::string Bytes(int c) const { return s.ColBlob(c); }
};

// Steps `s` (a query with LIMIT page_size + 1) into a page; `read` turns
// the current row into a record with a seq.
template <typename T, typename Read>
absl::StatusOr<Page<T>> StepPage(Stmt& s, int page_size, Read&& read) {
  Page<T> page;
  while (true) {
    SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
    if (!row) break;
    if (static_cast<int>(page.items.size()) == page_size) {
      page.next_after = page.items.back().seq;
      break;
    }
    page.items.push_back(read(StmtRow{s}));
  }
  return page;
}

absl::Status Exec(sqlite3* db, const char* sql) {
  char* err = nullptr;
  const int rc = sqlite3_exec(db, sql, nullptr, nullptr, &err);
  if (rc == SQLITE_OK) return absl::OkStatus();
  std::string msg = err ? err : sqlite3_errstr(rc);
  sqlite3_free(err);
  absl::Status base = SqliteError(nullptr, sqlite3_extended_errcode(db), "exec");
  return absl::Status(base.code(), absl::StrCat("sqlite: ", msg));
}

// Runs `body` inside BEGIN IMMEDIATE ... COMMIT; rolls back on any error so
// nothing of a failed multi-statement write remains.
template <typename F>
absl::Status InTransaction(sqlite3* db, F&& body) {
  SEAPLAN_RETURN_IF_ERROR(Exec(db, "BEGIN IMMEDIATE"));
  absl::Status status = body();
  if (status.ok()) status = Exec(db, "COMMIT");
  if (!status.ok()) {
    // ROLLBACK may fail if SQLite already rolled back (e.g. on SQLITE_FULL);
    // that is fine: the transaction is gone either way.
    (void)Exec(db, "ROLLBACK");
  }
  return status;
}

// Appends an audit row; the caller is inside the transaction of the change
// it records. Returns its seq.
absl::StatusOr<std::int64_t> InsertAudit(sqlite3* db, const AuditRecord& r) {
  Stmt s(db,
         "INSERT INTO audit_log(time_ms, token_id, role, vessel_id, action, target, detail) "
         "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7)");
  s.Int(1, r.time_ms)
      .Text(2, r.token_id)
      .Text(3, r.role)
      .Text(4, r.vessel_id)
      .Text(5, r.action)
      .Text(6, r.target)
      .Text(7, r.detail);
  SEAPLAN_RETURN_IF_ERROR(s.Run());
  return sqlite3_last_insert_rowid(db);
}

// The audit row of a write, when it has one (same transaction).
absl::Status InsertAuditIfAny(sqlite3* db, const AuditRecord* audit) {
  if (audit == nullptr) return absl::OkStatus();
  return InsertAudit(db, *audit).status();
}

}  // namespace

struct SqliteStore::Impl final : ChartRepository, MissionRepository {
  sqlite3* db = nullptr;
  std::mutex mu;
  // Bumped after each commit that touches a mission (outside mu).
  internal::LocalChangeFeed feed;

  ~Impl() override { CloseLocked(); }

  void CloseLocked() {
    if (db == nullptr) return;
    // Checkpoint so the main file holds everything and the -wal file is
    // truncated: a clean close leaves one self-contained file.
    sqlite3_wal_checkpoint_v2(db, nullptr, SQLITE_CHECKPOINT_TRUNCATE, nullptr, nullptr);
    sqlite3_close_v2(db);
    db = nullptr;
  }

  absl::Status Usable() const {
    if (db == nullptr) return absl::FailedPreconditionError("database is closed");
    return absl::OkStatus();
  }

  absl::StatusOr<int> UserVersion() {
    Stmt s(db, "PRAGMA user_version");
    SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
    if (!row) return absl::InternalError("PRAGMA user_version returned nothing");
    return static_cast<int>(s.ColInt(0));
  }

  absl::Status Migrate() {
    SEAPLAN_ASSIGN_OR_RETURN(int current, UserVersion());
    if (current > LatestSchemaVersion()) {
      return absl::FailedPreconditionError(
          absl::StrCat("database schema version ", current, " is newer than this server knows (",
                       LatestSchemaVersion(), "); refusing to touch it"));
    }
    const auto history = internal::SchemaHistory();
    if (history.size() != std::size(kMigrations)) {
      return absl::InternalError("SQLite migrations do not match the schema history");
    }
    for (std::size_t i = 0; i < history.size(); ++i) {
      const Migration& m = kMigrations[i];
      const char* description = history[i].description;
      if (m.version != history[i].version) {
        return absl::InternalError("SQLite migrations do not match the schema history");
      }
      if (m.version <= current) continue;
      bool applied = false;
      absl::Status st = InTransaction(db, [&]() -> absl::Status {
        // Read again under the write lock: another process opening the same
        // file at once may have applied this migration since the read above.
        SEAPLAN_ASSIGN_OR_RETURN(current, UserVersion());
        if (m.version <= current) return absl::OkStatus();
        SEAPLAN_RETURN_IF_ERROR(Exec(db, m.sql));
        applied = true;
        return Exec(db, absl::StrCat("PRAGMA user_version = ", m.version).c_str());
      });
      if (!st.ok()) {
        return absl::Status(st.code(), absl::StrCat("schema migration to version ", m.version, " (",
                                                    description, ") failed: ", st.message()));
      }
      if (applied) log::Info("storage: migrated schema to version {} ({})", m.version, description);
    }
    return absl::OkStatus();
  }

  // ---- log events (caller holds mu and is inside a transaction) ----
  absl::StatusOr<std::vector<LogEventRecord>> AppendEventsLocked(
      const std::string& mission_id, const std::vector<NewLogEvent>& events) {
    std::vector<LogEventRecord> out;
    if (events.empty()) return out;
    Stmt next(db, "SELECT COALESCE(MAX(event_id), 0) FROM log_events WHERE mission_id = ?1");
    next.Text(1, mission_id);
    SEAPLAN_ASSIGN_OR_RETURN(bool row, next.Step());
    std::int64_t id = row ? next.ColInt(0) : 0;
    for (const NewLogEvent& e : events) {
      Stmt ins(
          db,
          "INSERT INTO log_events(mission_id, event_id, time_ms, mission_time_s, source, message) "
          "VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
      ins.Text(1, mission_id)
          .Int(2, ++id)
          .Int(3, e.time_ms)
          .Real(4, e.mission_time_s)
          .Text(5, e.source)
          .Text(6, e.message);
      SEAPLAN_RETURN_IF_ERROR(ins.Run());
      out.push_back({mission_id, id, e.time_ms, e.mission_time_s, e.source, e.message});
    }
    return out;
  }

  absl::Status ApplyUpdateLocked(const std::string& id, const MissionUpdate& u,
                                 TimestampMs now_ms) {
    if (u.fence) {
      Stmt f(db, "SELECT 1 FROM mission_work WHERE mission_id = ?1 AND holder = ?2 AND token = ?3");
      f.Text(1, id).Text(2, u.fence->holder).Int(3, u.fence->token);
      SEAPLAN_ASSIGN_OR_RETURN(bool held, f.Step());
      if (!held) return internal::LostLeaseError(id, *u.fence);
    }
    Stmt s(
        db,
        "UPDATE missions SET state = COALESCE(?2, state), last_state = COALESCE(?3, last_state), "
        "completed_tasks = COALESCE(?4, completed_tasks), failure_reason = COALESCE(?5, "
        "failure_reason), "
        "updated_at_ms = ?6 WHERE id = ?1");
    s.Text(1, id);
    if (u.state)
      s.Int(2, *u.state);
    else
      s.Null(2);
    if (u.last_state)
      s.Blob(3, *u.last_state);
    else
      s.Null(3);
    if (u.completed_tasks)
      s.Text(4, JoinTasks(*u.completed_tasks));
    else
      s.Null(4);
    if (u.failure_reason)
      s.Text(5, *u.failure_reason);
    else
      s.Null(5);
    s.Int(6, now_ms);
    SEAPLAN_RETURN_IF_ERROR(s.Run());
    if (sqlite3_changes(db) == 0) return absl::NotFoundError(NotFoundMessage("mission", id));
    if (u.request_work) SEAPLAN_RETURN_IF_ERROR(RequestWorkLocked(id, *u.request_work).status());
    return InsertAuditIfAny(db, u.audit ? &*u.audit : nullptr);
  }

  // Runs a write of mission `id` in one transaction and wakes its watchers
  // after the commit. Caller holds mu.
  template <typename F>
  absl::Status MissionWriteLocked(const std::string& id, F&& body) {
    absl::Status st = InTransaction(db, std::forward<F>(body));
    if (st.ok()) feed.Bump(id);
    return st;
  }

  // ---- work leases (caller holds mu) ----
  // Returns true when the mission had no pending work before.
  absl::StatusOr<bool> RequestWorkLocked(const std::string& mission_id, const WorkRequest& r) {
    Stmt s(db, absl::StrCat(
                   "INSERT INTO mission_work(mission_id, reason, base_version, requested_at_ms, "
                   "requests) VALUES (?1, ?2, ?3, ?4, 1) "
                   "ON CONFLICT(mission_id) DO UPDATE SET reason = excluded.reason, "
                   "base_version = excluded.base_version, requests = requests + 1, "
                   "requested_at_ms = CASE WHEN requests > done_requests THEN requested_at_ms "
                   "ELSE excluded.requested_at_ms END "
                   "RETURNING requests - done_requests"));
    s.Text(1, mission_id).Text(2, r.reason).Int(3, r.base_version).Int(4, NowMs());
    absl::StatusOr<bool> row = s.Step();
    if (!row.ok() && sqlite3_extended_errcode(db) == SQLITE_CONSTRAINT_FOREIGNKEY) {
      return absl::NotFoundError(NotFoundMessage("mission", mission_id));
    }
    SEAPLAN_RETURN_IF_ERROR(row.status());
    if (!*row) return absl::InternalError("work request returned no row");
    return s.ColInt(0) == 1;
  }

  // Runs an UPDATE ... RETURNING on the work table; the leases it returns.
  absl::StatusOr<std::vector<WorkLease>> WorkRowsLocked(Stmt& s) {
    std::vector<WorkLease> out;
    while (true) {
      SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
      if (!row) break;
      out.push_back(internal::ReadWork(StmtRow{s}));
    }
    return out;
  }

  // ---- ChartRepository ----
  absl::StatusOr<ChartRecord> Insert(ChartRecord c, const AuditRecord* audit) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    const absl::Status written = InTransaction(db, [&]() -> absl::Status {
      SEAPLAN_RETURN_IF_ERROR(InsertChartLocked(c));
      return InsertAuditIfAny(db, audit);
    });
    if (!written.ok()) return written;
    return c;
  }

  // Inserts `c` and sets its seq. Caller holds mu.
  absl::Status InsertChartLocked(ChartRecord& c) {
    Stmt s(db,
           "INSERT INTO charts(id, name, format, options, summary, obstacles, source_files, "
           "created_at_ms) "
           "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)");
    s.Text(1, c.id)
        .Text(2, c.name)
        .Int(3, c.format)
        .Blob(4, c.options)
        .Blob(5, c.summary)
        .Blob(6, c.obstacles)
        .Blob(7, c.source_files)
        .Int(8, c.created_at_ms);
    absl::Status st = s.Run();
    if (absl::IsAlreadyExists(st))
      return absl::AlreadyExistsError(absl::StrCat("chart '", c.id, "' exists"));
    SEAPLAN_RETURN_IF_ERROR(st);
    c.seq = sqlite3_last_insert_rowid(db);
    return absl::OkStatus();
  }

  absl::StatusOr<ChartRecord> Get(const std::string& id, bool with_blobs) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    Stmt s(db, with_blobs
                   ? "SELECT seq, id, name, format, options, summary, created_at_ms, obstacles, "
                     "source_files FROM charts WHERE id = ?1"
                   : "SELECT seq, id, name, format, options, summary, created_at_ms FROM charts "
                     "WHERE id = ?1");
    s.Text(1, id);
    SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
    if (!row) return absl::NotFoundError(absl::StrCat("chart '", id, "' not found"));
    return internal::ReadChart(StmtRow{s}, with_blobs);
  }

  absl::StatusOr<Page<ChartRecord>> List(int page_size, std::int64_t after) override {
    SEAPLAN_RETURN_IF_ERROR(CheckPageSize(page_size));
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    Stmt s(db,
           "SELECT seq, id, name, format, options, summary, created_at_ms FROM charts "
           "WHERE seq > ?1 ORDER BY seq LIMIT ?2");
    s.Int(1, after).Int(2, page_size + 1);
    return StepPage<ChartRecord>(
        s, page_size, [](const StmtRow& row) { return internal::ReadChart(row, false); });
  }

  absl::Status Delete(const std::string& id, const ChartUse& use,
                      const AuditRecord* audit) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    return InTransaction(db, [&]() -> absl::Status {
      {
        Stmt exists(db, "SELECT 1 FROM charts WHERE id = ?1");
        exists.Text(1, id);
        SEAPLAN_ASSIGN_OR_RETURN(bool found, exists.Step());
        if (!found) return absl::NotFoundError(internal::NotFoundMessage("chart", id));
      }
      Stmt active(db, absl::StrCat("SELECT id, spec FROM missions WHERE state IN ",
                                   internal::SqlIntList(use.active_states), " ORDER BY seq"));
      std::vector<std::string> users;
      while (true) {
        SEAPLAN_ASSIGN_OR_RETURN(bool row, active.Step());
        if (!row) break;
        if (use.spec_uses_chart && use.spec_uses_chart(active.ColBlob(1), id))
          users.push_back(active.ColText(0));
      }
      if (!users.empty()) return internal::ChartInUseError(id, users);
      Stmt del(db, "DELETE FROM charts WHERE id = ?1");
      del.Text(1, id);
      SEAPLAN_RETURN_IF_ERROR(del.Run());
      return InsertAuditIfAny(db, audit);
    });
  }

  // ---- MissionRepository ----
  absl::Status InsertVersionLocked(const PlanVersionRecord& v) {
    Stmt s(db,
           "INSERT INTO plan_versions(mission_id, version, reason, created_at_ms, content, "
           "engine_state) "
           "VALUES (?1, ?2, ?3, ?4, ?5, ?6)");
    s.Text(1, v.mission_id)
        .Int(2, v.version)
        .Text(3, v.reason)
        .Int(4, v.created_at_ms)
        .Blob(5, v.content)
        .Blob(6, v.engine_state);
    return s.Run();
  }

  absl::Status Create(const MissionRecord& m, const PlanVersionRecord& first,
                      const std::vector<NewLogEvent>& events, const AuditRecord* audit,
                      const std::string& chart_id) override {
    if (first.version != 1 || first.mission_id != m.id) {
      return absl::InvalidArgumentError(
          "the first plan version must be version 1 of the same mission");
    }
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    return MissionWriteLocked(m.id, [&]() -> absl::Status {
      // BEGIN IMMEDIATE holds the database's write lock from the start, so
      // a chart deletion (a write) commits wholly before or after this.
      if (!chart_id.empty()) {
        Stmt chart(db, "SELECT 1 FROM charts WHERE id = ?1");
        chart.Text(1, chart_id);
        SEAPLAN_ASSIGN_OR_RETURN(bool found, chart.Step());
        if (!found) return absl::NotFoundError(NotFoundMessage("chart", chart_id));
      }
      Stmt s(db,
             "INSERT INTO missions(id, name, vessel_id, request_id, spec, state, current_version, "
             "created_at_ms, "
             "updated_at_ms, last_state, completed_tasks, failure_reason) "
             "VALUES (?1, ?2, ?3, ?4, ?5, ?6, 1, ?7, ?8, ?9, ?10, ?11)");
      s.Text(1, m.id).Text(2, m.name).Text(3, m.vessel_id);
      if (m.request_id.empty())
        s.Null(4);
      else
        s.Text(4, m.request_id);
      s.Blob(5, m.spec)
          .Int(6, m.state)
          .Int(7, m.created_at_ms)
          .Int(8, m.updated_at_ms)
          .Blob(9, m.last_state)
          .Text(10, JoinTasks(m.completed_tasks))
          .Text(11, m.failure_reason);
      absl::Status st = s.Run();
      if (absl::IsAlreadyExists(st)) {
        return absl::AlreadyExistsError(
            absl::StrCat("mission '", m.id, "' or request id '", m.request_id, "' exists"));
      }
      SEAPLAN_RETURN_IF_ERROR(st);
      SEAPLAN_RETURN_IF_ERROR(InsertVersionLocked(first));
      SEAPLAN_RETURN_IF_ERROR(AppendEventsLocked(m.id, events).status());
      return InsertAuditIfAny(db, audit);
    });
  }

  absl::StatusOr<MissionRecord> Get(const std::string& id) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    Stmt s(db, absl::StrCat("SELECT ", kMissionColumns, " FROM missions WHERE id = ?1"));
    s.Text(1, id);
    SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
    if (!row) return absl::NotFoundError(absl::StrCat("mission '", id, "' not found"));
    return internal::ReadMission(StmtRow{s});
  }

  absl::StatusOr<std::optional<MissionRecord>> FindByRequestId(
      const std::string& request_id) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    Stmt s(db, absl::StrCat("SELECT ", kMissionColumns, " FROM missions WHERE request_id = ?1"));
    s.Text(1, request_id);
    SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
    if (!row) return std::optional<MissionRecord>();
    return std::optional<MissionRecord>(internal::ReadMission(StmtRow{s}));
  }

  absl::StatusOr<Page<MissionRecord>> List(int state, int page_size, std::int64_t after) override {
    SEAPLAN_RETURN_IF_ERROR(CheckPageSize(page_size));
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    Stmt s(db,
           absl::StrCat(
               "SELECT ", kMissionColumns,
               " FROM missions WHERE seq > ?1 AND (?2 = 0 OR state = ?2) ORDER BY seq LIMIT ?3"));
    s.Int(1, after).Int(2, state).Int(3, page_size + 1);
    return StepPage<MissionRecord>(s, page_size,
                                   [](const StmtRow& row) { return internal::ReadMission(row); });
  }

  absl::Status Update(const std::string& id, const MissionUpdate& update,
                      const std::vector<NewLogEvent>& events) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    return MissionWriteLocked(id, [&]() -> absl::Status {
      SEAPLAN_RETURN_IF_ERROR(ApplyUpdateLocked(id, update, LatestTime(events, NowMs())));
      return AppendEventsLocked(id, events).status();
    });
  }

  absl::Status AppendVersion(const PlanVersionRecord& v, const MissionUpdate& update,
                             const std::vector<NewLogEvent>& events) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    return MissionWriteLocked(v.mission_id, [&]() -> absl::Status {
      Stmt cur(db, "SELECT current_version FROM missions WHERE id = ?1");
      cur.Text(1, v.mission_id);
      SEAPLAN_ASSIGN_OR_RETURN(bool row, cur.Step());
      if (!row) return absl::NotFoundError(NotFoundMessage("mission", v.mission_id));
      const std::int64_t current = cur.ColInt(0);
      if (v.version != current + 1) {
        return absl::AbortedError(absl::StrCat("plan version ", v.version, " of mission '",
                                               v.mission_id, "' is not next (current is ", current,
                                               ")"));
      }
      SEAPLAN_RETURN_IF_ERROR(InsertVersionLocked(v));
      Stmt bump(db, "UPDATE missions SET current_version = ?2 WHERE id = ?1");
      bump.Text(1, v.mission_id).Int(2, v.version);
      SEAPLAN_RETURN_IF_ERROR(bump.Run());
      SEAPLAN_RETURN_IF_ERROR(AppendEventsLocked(v.mission_id, events).status());
      return ApplyUpdateLocked(v.mission_id, update,
                               std::max(v.created_at_ms, LatestTime(events, 0)));
    });
  }

  absl::StatusOr<PlanVersionRecord> GetVersion(const std::string& mission_id,
                                               int version) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    Stmt s(db,
           "SELECT mission_id, version, reason, created_at_ms, content, engine_state FROM "
           "plan_versions "
           "WHERE mission_id = ?1 AND version = ?2");
    s.Text(1, mission_id).Int(2, version);
    SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
    if (!row)
      return absl::NotFoundError(
          absl::StrCat("plan version ", version, " of mission '", mission_id, "' not found"));
    return internal::ReadVersion(StmtRow{s});
  }

  absl::StatusOr<std::vector<PlanVersionRecord>> ListVersions(const std::string& mission_id,
                                                              int after_version,
                                                              int limit) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    Stmt s(db,
           "SELECT mission_id, version, reason, created_at_ms, content, engine_state FROM "
           "plan_versions "
           "WHERE mission_id = ?1 AND version > ?2 ORDER BY version LIMIT ?3");
    s.Text(1, mission_id).Int(2, after_version).Int(3, limit);
    std::vector<PlanVersionRecord> out;
    while (true) {
      SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
      if (!row) break;
      out.push_back(internal::ReadVersion(StmtRow{s}));
    }
    return out;
  }

  absl::StatusOr<bool> RecordFeedback(const FeedbackRecord& f, const MissionUpdate& update,
                                      const std::vector<NewLogEvent>& events) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    bool inserted = false;
    absl::Status result = MissionWriteLocked(f.mission_id, [&]() -> absl::Status {
      Stmt s(db,
             "INSERT INTO feedback(mission_id, vessel_id, sequence_number, kind, payload, "
             "received_at_ms) "
             "VALUES (?1, ?2, ?3, ?4, ?5, ?6) ON CONFLICT(vessel_id, sequence_number) DO NOTHING");
      s.Text(1, f.mission_id)
          .Text(2, f.vessel_id)
          .Int(3, f.sequence_number)
          .Int(4, f.kind)
          .Blob(5, f.payload)
          .Int(6, f.received_at_ms);
      absl::Status st = s.Run();
      if (!st.ok()) {
        // A foreign-key failure here means the mission does not exist.
        if (sqlite3_extended_errcode(db) == SQLITE_CONSTRAINT_FOREIGNKEY) {
          return absl::NotFoundError(NotFoundMessage("mission", f.mission_id));
        }
        return st;
      }
      inserted = sqlite3_changes(db) == 1;
      if (!inserted) return absl::OkStatus();  // duplicate: change nothing
      SEAPLAN_RETURN_IF_ERROR(AppendEventsLocked(f.mission_id, events).status());
      return ApplyUpdateLocked(f.mission_id, update,
                               std::max(f.received_at_ms, LatestTime(events, 0)));
    });
    if (!result.ok()) return result;
    return inserted;
  }

  absl::StatusOr<std::optional<FeedbackRecord>> FindFeedback(
      const std::string& vessel_id, std::int64_t sequence_number) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    Stmt s(db, absl::StrCat("SELECT ", internal::kFeedbackColumns,
                            " FROM feedback WHERE vessel_id = ?1 AND sequence_number = ?2"));
    s.Text(1, vessel_id).Int(2, sequence_number);
    SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
    if (!row) return std::optional<FeedbackRecord>();
    return std::optional<FeedbackRecord>(internal::ReadFeedback(StmtRow{s}));
  }

  absl::StatusOr<std::vector<FeedbackRecord>> ListFeedback(const std::string& mission_id,
                                                           int limit) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    // The latest `limit` rows, returned oldest first.
    Stmt s(db, absl::StrCat("SELECT * FROM (SELECT ", internal::kFeedbackColumns,
                            " FROM feedback WHERE mission_id = ?1 ORDER BY seq DESC LIMIT ?2) "
                            "ORDER BY seq"));
    s.Text(1, mission_id).Int(2, limit);
    std::vector<FeedbackRecord> out;
    while (true) {
      SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
      if (!row) break;
      out.push_back(internal::ReadFeedback(StmtRow{s}));
    }
    return out;
  }

  absl::StatusOr<Page<FeedbackRecord>> ListFeedbackPage(const std::string& mission_id,
                                                        std::int64_t after,
                                                        int page_size) override {
    SEAPLAN_RETURN_IF_ERROR(CheckPageSize(page_size));
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    Stmt s(db, absl::StrCat("SELECT ", internal::kFeedbackColumns,
                            " FROM feedback WHERE mission_id = ?1 AND seq > ?2 ORDER BY seq "
                            "LIMIT ?3"));
    s.Text(1, mission_id).Int(2, after).Int(3, page_size + 1);
    return StepPage<FeedbackRecord>(s, page_size,
                                    [](const StmtRow& r) { return internal::ReadFeedback(r); });
  }

  absl::StatusOr<std::vector<LogEventRecord>> AppendEvents(
      const std::string& mission_id, const std::vector<NewLogEvent>& events) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    std::vector<LogEventRecord> out;
    absl::Status result = MissionWriteLocked(mission_id, [&]() -> absl::Status {
      Stmt exists(db, "SELECT 1 FROM missions WHERE id = ?1");
      exists.Text(1, mission_id);
      SEAPLAN_ASSIGN_OR_RETURN(bool row, exists.Step());
      if (!row) return absl::NotFoundError(NotFoundMessage("mission", mission_id));
      SEAPLAN_ASSIGN_OR_RETURN(out, AppendEventsLocked(mission_id, events));
      return absl::OkStatus();
    });
    if (!result.ok()) return result;
    return out;
  }

  absl::StatusOr<std::vector<LogEventRecord>> ListEvents(const std::string& mission_id,
                                                         std::int64_t after_event_id,
                                                         int limit) override {
    std::lock_guard lock(mu);
    SEAPLAN_RETURN_IF_ERROR(Usable());
    Stmt s(db,
           "SELECT mission_id, event_id, time_ms, mission_time_s, source, message FROM log_events "
           "WHERE mission_id = ?1 AND event_id > ?2 ORDER BY event_id LIMIT ?3");
    s.Text(1, mission_id).Int(2, after_event_id).Int(3, limit);
    std::vector<LogEventRecord> out;
    while (true) {
      SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
      if (!row) break;
      out.push_back(internal::ReadEvent(StmtRow{s}));
    }
    return out;
  }
};

// The work leases over the same connection and mutex (a separate object:
// its Get() would clash with MissionRepository::Get()).
class SqliteStore::Work final : public internal::WorkLeaseBase {
 public:
  explicit Work(Impl& impl) : impl_(impl) {}

  absl::StatusOr<bool> Request(const std::string& mission_id, const WorkRequest& r) override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    bool was_idle = false;
    const absl::Status written = InTransaction(impl_.db, [&]() -> absl::Status {
      SEAPLAN_ASSIGN_OR_RETURN(was_idle, impl_.RequestWorkLocked(mission_id, r));
      return absl::OkStatus();
    });
    if (!written.ok()) return written;
    return was_idle;
  }

  absl::StatusOr<int> ReleaseAll(const std::string& holder) override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    Stmt s(impl_.db,
           "UPDATE mission_work SET holder = NULL, lease_expires_at_ms = NULL WHERE holder = ?1");
    s.Text(1, holder);
    SEAPLAN_RETURN_IF_ERROR(s.Run());
    return sqlite3_changes(impl_.db);
  }

  absl::StatusOr<std::optional<WorkLease>> Get(const std::string& mission_id) override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    Stmt s(impl_.db, absl::StrCat("SELECT ", internal::kWorkColumns,
                                  " FROM mission_work WHERE mission_id = ?1"));
    s.Text(1, mission_id);
    SEAPLAN_ASSIGN_OR_RETURN(std::vector<WorkLease> rows, impl_.WorkRowsLocked(s));
    if (rows.empty()) return std::optional<WorkLease>();
    return std::optional<WorkLease>(std::move(rows[0]));
  }

 private:
  // One writer at a time (the mutex, and BEGIN IMMEDIATE against other
  // connections), so two claimers never get the same item.
  absl::StatusOr<std::vector<WorkLease>> ClaimPending(const std::string& mission_id,
                                                      const std::string& holder,
                                                      std::chrono::milliseconds ttl,
                                                      int limit) override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    std::vector<WorkLease> out;
    const absl::Status written = InTransaction(impl_.db, [&]() -> absl::Status {
      const TimestampMs now = NowMs();
      Stmt s(impl_.db,
             absl::StrCat("UPDATE mission_work SET holder = ?1, token = token + 1, "
                          "claimed_requests = requests, lease_expires_at_ms = ?2 "
                          "WHERE mission_id IN (SELECT mission_id FROM mission_work WHERE "
                          "(?4 = '' OR mission_id = ?4) AND requests > done_requests AND "
                          "(holder IS NULL OR lease_expires_at_ms <= ?3) "
                          "ORDER BY requested_at_ms, mission_id LIMIT ?5) RETURNING ",
                          internal::kWorkColumns));
      s.Text(1, holder).Int(2, now + ttl.count()).Int(3, now).Text(4, mission_id).Int(5, limit);
      SEAPLAN_ASSIGN_OR_RETURN(out, impl_.WorkRowsLocked(s));
      return absl::OkStatus();
    });
    if (!written.ok()) return written;
    return out;
  }

  absl::StatusOr<std::vector<WorkLease>> RequestAndClaimFree(
      const std::string& mission_id, const std::string& reason, const std::string& holder,
      std::chrono::milliseconds ttl) override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    std::vector<WorkLease> out;
    const absl::Status written = InTransaction(impl_.db, [&]() -> absl::Status {
      const TimestampMs now = NowMs();
      int current = 0;
      {
        Stmt mission(impl_.db, "SELECT current_version FROM missions WHERE id = ?1");
        mission.Text(1, mission_id);
        SEAPLAN_ASSIGN_OR_RETURN(bool found, mission.Step());
        if (!found) return absl::NotFoundError(NotFoundMessage("mission", mission_id));
        current = static_cast<int>(mission.ColInt(0));
      }
      {
        Stmt held(impl_.db,
                  "SELECT 1 FROM mission_work WHERE mission_id = ?1 AND holder IS NOT NULL AND "
                  "lease_expires_at_ms > ?2");
        held.Text(1, mission_id).Int(2, now);
        SEAPLAN_ASSIGN_OR_RETURN(bool is_held, held.Step());
        if (is_held) return absl::OkStatus();  // a live lease: nothing recorded
      }
      SEAPLAN_RETURN_IF_ERROR(impl_.RequestWorkLocked(mission_id, {reason, current}).status());
      Stmt s(impl_.db, absl::StrCat("UPDATE mission_work SET holder = ?2, token = token + 1, "
                                    "claimed_requests = requests, lease_expires_at_ms = ?3 "
                                    "WHERE mission_id = ?1 RETURNING ",
                                    internal::kWorkColumns));
      s.Text(1, mission_id).Text(2, holder).Int(3, now + ttl.count());
      SEAPLAN_ASSIGN_OR_RETURN(out, impl_.WorkRowsLocked(s));
      return absl::OkStatus();
    });
    if (!written.ok()) return written;
    return out;
  }

  absl::StatusOr<std::vector<WorkLease>> UpdateHeld(const WorkLease& lease, LeaseChange change,
                                                    std::chrono::milliseconds ttl) override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    Stmt s(impl_.db,
           absl::StrCat("UPDATE mission_work SET ", SetClause(change, "?4"),
                        " WHERE mission_id = ?1 AND holder = ?2 AND token = ?3 RETURNING ",
                        internal::kWorkColumns));
    s.Text(1, lease.mission_id).Text(2, lease.holder).Int(3, lease.token);
    if (change == LeaseChange::kRenew) s.Int(4, NowMs() + ttl.count());
    return impl_.WorkRowsLocked(s);
  }

  Impl& impl_;
};

// ---------------------------------------------------------------------------
class SqliteStore::Access final : public TokenRepository, public AuditRepository {
 public:
  explicit Access(Impl& impl) : impl_(impl) {}

  absl::Status Insert(const TokenRecord& t, const AuditRecord* audit) override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    return InTransaction(impl_.db, [&]() -> absl::Status {
      SEAPLAN_RETURN_IF_ERROR(InsertLocked(t));
      return InsertAuditIfAny(impl_.db, audit);
    });
  }

  absl::StatusOr<TokenRecord> Get(const std::string& id) override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    return GetLocked(id);
  }

  absl::StatusOr<std::vector<TokenRecord>> List() override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    Stmt s(impl_.db, absl::StrCat("SELECT ", internal::kTokenColumns,
                                  " FROM api_tokens ORDER BY created_at_ms, id"));
    std::vector<TokenRecord> out;
    while (true) {
      SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
      if (!row) break;
      out.push_back(internal::ReadToken(StmtRow{s}));
    }
    return out;
  }

  absl::StatusOr<TokenRecord> Revoke(const std::string& id, TimestampMs at_ms,
                                     const AuditRecord* audit) override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    absl::StatusOr<TokenRecord> revoked = absl::UnknownError("token revocation did not run");
    const absl::Status written = InTransaction(impl_.db, [&]() -> absl::Status {
      Stmt s(impl_.db,
             "UPDATE api_tokens SET revoked_at_ms = ?2 WHERE id = ?1 AND revoked_at_ms = 0");
      s.Text(1, id).Int(2, at_ms);
      SEAPLAN_RETURN_IF_ERROR(s.Run());
      revoked = GetLocked(id);  // NotFound for an unknown id: nothing is audited
      SEAPLAN_RETURN_IF_ERROR(revoked.status());
      return InsertAuditIfAny(impl_.db, audit);
    });
    if (!written.ok()) return written;
    return revoked;
  }

  absl::StatusOr<bool> InsertFirstAdmin(const TokenRecord& admin, TimestampMs now_ms) override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    bool inserted = false;
    // BEGIN IMMEDIATE takes the database's write lock before the check, so
    // another process's check waits for this insert to commit (or roll back).
    const absl::Status written = InTransaction(impl_.db, [&]() -> absl::Status {
      Stmt usable(impl_.db, internal::UsableAdminTokenQuery("?1"));
      usable.Int(1, now_ms);
      SEAPLAN_ASSIGN_OR_RETURN(bool exists, usable.Step());
      if (exists) return absl::OkStatus();
      SEAPLAN_RETURN_IF_ERROR(InsertLocked(admin));
      inserted = true;
      return absl::OkStatus();
    });
    if (!written.ok()) return written;
    return inserted;
  }

  absl::StatusOr<AuditRecord> Append(AuditRecord r) override {
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    SEAPLAN_ASSIGN_OR_RETURN(r.seq, InsertAudit(impl_.db, r));
    return r;
  }

  absl::StatusOr<Page<AuditRecord>> ListAudit(int page_size, std::int64_t after) override {
    SEAPLAN_RETURN_IF_ERROR(CheckPageSize(page_size));
    std::lock_guard lock(impl_.mu);
    SEAPLAN_RETURN_IF_ERROR(impl_.Usable());
    Stmt s(impl_.db, absl::StrCat("SELECT ", internal::kAuditColumns,
                                  " FROM audit_log WHERE seq > ?1 ORDER BY seq LIMIT ?2"));
    s.Int(1, after).Int(2, page_size + 1);
    return StepPage<AuditRecord>(s, page_size,
                                 [](const StmtRow& row) { return internal::ReadAudit(row); });
  }

 private:
  // The caller holds mu and is inside a transaction.
  absl::Status InsertLocked(const TokenRecord& t) {
    Stmt s(impl_.db, absl::StrCat("INSERT INTO api_tokens(", internal::kTokenColumns,
                                  ") VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9)"));
    s.Text(1, t.id)
        .Text(2, t.secret_hash)
        .Text(3, t.role)
        .Text(4, t.vessel_id)
        .Text(5, t.description)
        .Text(6, t.created_by)
        .Int(7, t.created_at_ms)
        .Int(8, t.expires_at_ms)
        .Int(9, t.revoked_at_ms);
    absl::Status st = s.Run();
    if (absl::IsAlreadyExists(st)) {
      return absl::AlreadyExistsError(absl::StrCat("token '", t.id, "' exists"));
    }
    return st;
  }

  absl::StatusOr<TokenRecord> GetLocked(const std::string& id) {
    Stmt s(impl_.db,
           absl::StrCat("SELECT ", internal::kTokenColumns, " FROM api_tokens WHERE id = ?1"));
    s.Text(1, id);
    SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
    if (!row) return absl::NotFoundError(NotFoundMessage("token", id));
    return internal::ReadToken(StmtRow{s});
  }

  Impl& impl_;
};

SqliteStore::SqliteStore(std::unique_ptr<Impl> impl)
    : impl_(std::move(impl)),
      work_(std::make_unique<Work>(*impl_)),
      access_(std::make_unique<Access>(*impl_)) {}
SqliteStore::~SqliteStore() = default;

absl::StatusOr<std::unique_ptr<SqliteStore>> SqliteStore::Open(const std::string& path,
                                                               const SqliteOptions& options) {
  auto impl = std::make_unique<Impl>();
  const int rc =
      sqlite3_open_v2(path.c_str(), &impl->db,
                      SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE | SQLITE_OPEN_FULLMUTEX, nullptr);
  if (rc != SQLITE_OK) {
    absl::Status st = absl::UnavailableError(
        absl::StrCat("cannot open database '", path,
                     "': ", impl->db ? sqlite3_errmsg(impl->db) : sqlite3_errstr(rc)));
    sqlite3_close_v2(impl->db);
    impl->db = nullptr;
    return st;
  }
  sqlite3_extended_result_codes(impl->db, 1);
  sqlite3_busy_timeout(impl->db, options.busy_timeout_ms);
  auto fail = [&](const absl::Status& st) {
    // SQLite says "unable to open database file" for a read-only folder or
    // file system: say which, so an operator knows what to fix.
    std::string why;
    const std::string folder = std::filesystem::path(path).parent_path().string();
    if (::access(folder.empty() ? "." : folder.c_str(), W_OK) != 0) {
      why = absl::StrCat(" (its folder is not writable: ", std::strerror(errno), ")");
    } else if (::access(path.c_str(), F_OK) == 0 && ::access(path.c_str(), W_OK) != 0) {
      why = absl::StrCat(" (the file is not writable: ", std::strerror(errno), ")");
    }
    return absl::Status(st.code(), absl::StrCat("database '", path, "'", why, ": ", st.message()));
  };
  // journal_mode returns a row; an in-memory database stays "memory".
  // Switching a new file to WAL needs an exclusive lock, and SQLite answers
  // SQLITE_BUSY at once (no busy handler) while another process opening the
  // same new file holds a lock on it: retry within the busy timeout.
  for (const auto give_up =
           std::chrono::steady_clock::now() + std::chrono::milliseconds(options.busy_timeout_ms);
       ;) {
    Stmt wal(impl->db, "PRAGMA journal_mode = WAL");
    auto row = wal.Step();
    if (row.ok()) break;
    const int code = sqlite3_extended_errcode(impl->db) & 0xff;
    const bool busy = code == SQLITE_BUSY || code == SQLITE_LOCKED;
    if (!busy || std::chrono::steady_clock::now() >= give_up) return fail(row.status());
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  absl::Status st = Exec(impl->db, options.synchronous_full
                                       ? "PRAGMA synchronous = FULL; PRAGMA foreign_keys = ON"
                                       : "PRAGMA synchronous = NORMAL; PRAGMA foreign_keys = ON");
  if (!st.ok()) return fail(st);
  st = impl->Migrate();
  if (!st.ok()) return fail(st);
  return std::unique_ptr<SqliteStore>(new SqliteStore(std::move(impl)));
}

ChartRepository& SqliteStore::charts() {
  return *impl_;
}
MissionRepository& SqliteStore::missions() {
  return *impl_;
}
WorkLeaseRepository& SqliteStore::work() {
  return *work_;
}
ChangeFeed& SqliteStore::changes() {
  return impl_->feed;
}
TokenRepository& SqliteStore::tokens() {
  return *access_;
}
AuditRepository& SqliteStore::audit() {
  return *access_;
}

absl::Status SqliteStore::Close() {
  std::lock_guard lock(impl_->mu);
  impl_->CloseLocked();
  impl_->feed.Close();
  return absl::OkStatus();
}

absl::StatusOr<int> SqliteStore::SchemaVersion() {
  std::lock_guard lock(impl_->mu);
  SEAPLAN_RETURN_IF_ERROR(impl_->Usable());
  return impl_->UserVersion();
}

absl::Status SqliteStore::CheckIntegrity() {
  std::lock_guard lock(impl_->mu);
  SEAPLAN_RETURN_IF_ERROR(impl_->Usable());
  Stmt s(impl_->db, "PRAGMA integrity_check");
  SEAPLAN_ASSIGN_OR_RETURN(bool row, s.Step());
  if (!row || s.ColText(0) != "ok")
    return absl::DataLossError(absl::StrCat("integrity_check: ", row ? s.ColText(0) : ""));
  return absl::OkStatus();
}

}  // namespace seaplan::storage
