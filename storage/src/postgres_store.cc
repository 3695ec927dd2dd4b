#include "seaplan/storage/postgres_store.h"

#include <endian.h>
#include <fcntl.h>
#include <libpq-fe.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <optional>
#include <thread>

#include "absl/strings/str_cat.h"
#include "absl/strings/strip.h"
#include "seaplan/common/log.h"
#include "store_internal.h"

namespace seaplan::storage {
namespace {

using internal::CheckPageSize;
using internal::JoinTasks;
using internal::kMissionColumns;
using internal::kWorkColumns;
using internal::LatestTime;
using internal::NotFoundMessage;
using internal::NowMs;
using internal::SplitTasks;

constexpr const char* kChangeChannel = "seaplan_mission_changes";
// Serialises schema migrations of replicas that start together.
constexpr std::int64_t kMigrationLockKey = 0x5ea91a40;
// Serialises the first-admin check and insert of replicas that start together.
constexpr std::int64_t kFirstAdminLockKey = 0x5ea91a41;
// The database clock in ms (transaction start: stable within a write).
constexpr const char* kDbNowMs = "(EXTRACT(EPOCH FROM now()) * 1000)::bigint";

// The PostgreSQL migrations, one per entry of internal::SchemaHistory() with
// the same version (the SQLite ones in sqlite_store.cc carry the same
// schema in SQLite's dialect). NEVER edit a released entry: add a new one.
struct Migration {
  int version;
  const char* sql;
};

constexpr Migration kMigrations[] = {
    {1, R"sql(
CREATE TABLE charts (
  seq BIGINT GENERATED ALWAYS AS IDENTITY PRIMARY KEY,
  id TEXT NOT NULL UNIQUE,
  name TEXT NOT NULL,
  format INTEGER NOT NULL,
  options BYTEA NOT NULL,
  summary BYTEA NOT NULL,
  obstacles BYTEA NOT NULL,
  created_at_ms BIGINT NOT NULL);
CREATE TABLE missions (
  seq BIGINT GENERATED ALWAYS AS IDENTITY PRIMARY KEY,
  id TEXT NOT NULL UNIQUE,
  name TEXT NOT NULL,
  vessel_id TEXT NOT NULL,
  spec BYTEA NOT NULL,
  state INTEGER NOT NULL,
  current_version INTEGER NOT NULL DEFAULT 0,
  created_at_ms BIGINT NOT NULL,
  updated_at_ms BIGINT NOT NULL,
  last_state BYTEA NOT NULL DEFAULT '',
  failure_reason TEXT NOT NULL DEFAULT '');
CREATE INDEX missions_by_state ON missions(state, seq);
CREATE TABLE plan_versions (
  mission_id TEXT NOT NULL REFERENCES missions(id),
  version INTEGER NOT NULL CHECK (version >= 1),
  reason TEXT NOT NULL,
  created_at_ms BIGINT NOT NULL,
  content BYTEA NOT NULL,
  PRIMARY KEY (mission_id, version));
CREATE FUNCTION seaplan_plan_versions_immutable() RETURNS trigger LANGUAGE plpgsql AS $$
BEGIN
  RAISE EXCEPTION 'plan versions are immutable';
END $$;
CREATE TRIGGER plan_versions_no_change BEFORE UPDATE OR DELETE ON plan_versions
  FOR EACH ROW EXECUTE FUNCTION seaplan_plan_versions_immutable();
CREATE TRIGGER plan_versions_no_truncate BEFORE TRUNCATE ON plan_versions
  FOR EACH STATEMENT EXECUTE FUNCTION seaplan_plan_versions_immutable();
CREATE TABLE feedback (
  seq BIGINT GENERATED ALWAYS AS IDENTITY PRIMARY KEY,
  mission_id TEXT NOT NULL REFERENCES missions(id),
  vessel_id TEXT NOT NULL,
  sequence_number BIGINT NOT NULL,
  kind INTEGER NOT NULL,
  payload BYTEA NOT NULL,
  received_at_ms BIGINT NOT NULL,
  UNIQUE (vessel_id, sequence_number));
CREATE INDEX feedback_by_mission ON feedback(mission_id, seq);
CREATE TABLE log_events (
  mission_id TEXT NOT NULL REFERENCES missions(id),
  event_id BIGINT NOT NULL CHECK (event_id >= 1),
  time_ms BIGINT NOT NULL,
  mission_time_s DOUBLE PRECISION NOT NULL CHECK (mission_time_s <> 'NaN'),
  source TEXT NOT NULL CHECK (length(source) > 0),
  message TEXT NOT NULL,
  PRIMARY KEY (mission_id, event_id));
)sql"},
    {2, R"sql(
ALTER TABLE missions ADD COLUMN request_id TEXT;
CREATE UNIQUE INDEX missions_by_request_id ON missions(request_id) WHERE request_id IS NOT NULL;
ALTER TABLE missions ADD COLUMN completed_tasks TEXT NOT NULL DEFAULT '';
ALTER TABLE charts ADD COLUMN source_files BYTEA NOT NULL DEFAULT '';
ALTER TABLE plan_versions ADD COLUMN engine_state BYTEA NOT NULL DEFAULT '';
)sql"},
    // NOTIFY payloads are limited to 8000 bytes: a longer mission id sends
    // an empty payload, which wakes every watcher.
    {3, R"sql(
CREATE TABLE mission_work (
  mission_id TEXT PRIMARY KEY REFERENCES missions(id),
  reason TEXT NOT NULL,
  base_version INTEGER NOT NULL,
  requested_at_ms BIGINT NOT NULL,
  requests BIGINT NOT NULL CHECK (requests >= 1),
  done_requests BIGINT NOT NULL DEFAULT 0,
  claimed_requests BIGINT NOT NULL DEFAULT 0,
  holder TEXT CHECK (holder IS NULL OR length(holder) > 0),
  token BIGINT NOT NULL DEFAULT 0,
  lease_expires_at_ms BIGINT,
  CHECK ((holder IS NULL) = (lease_expires_at_ms IS NULL)));
CREATE INDEX mission_work_pending ON mission_work(requested_at_ms) WHERE requests > done_requests;
CREATE FUNCTION seaplan_notify_mission_row() RETURNS trigger LANGUAGE plpgsql AS $$
BEGIN
  PERFORM pg_notify('seaplan_mission_changes',
                    CASE WHEN octet_length(NEW.id) < 7900 THEN NEW.id ELSE '' END);
  RETURN NULL;
END $$;
CREATE FUNCTION seaplan_notify_mission_child() RETURNS trigger LANGUAGE plpgsql AS $$
BEGIN
  PERFORM pg_notify('seaplan_mission_changes',
                    CASE WHEN octet_length(NEW.mission_id) < 7900 THEN NEW.mission_id ELSE '' END);
  RETURN NULL;
END $$;
CREATE TRIGGER missions_notify AFTER INSERT OR UPDATE ON missions
  FOR EACH ROW EXECUTE FUNCTION seaplan_notify_mission_row();
CREATE TRIGGER plan_versions_notify AFTER INSERT ON plan_versions
  FOR EACH ROW EXECUTE FUNCTION seaplan_notify_mission_child();
CREATE TRIGGER feedback_notify AFTER INSERT ON feedback
  FOR EACH ROW EXECUTE FUNCTION seaplan_notify_mission_child();
CREATE TRIGGER log_events_notify AFTER INSERT ON log_events
  FOR EACH ROW EXECUTE FUNCTION seaplan_notify_mission_child();
)sql"},
    {4, R"sql(
CREATE TABLE api_tokens (
  id TEXT PRIMARY KEY CHECK (length(id) > 0),
  secret_hash TEXT NOT NULL CHECK (length(secret_hash) = 64),
  role TEXT NOT NULL CHECK (role IN ('admin', 'operator', 'viewer', 'vessel')),
  vessel_id TEXT NOT NULL DEFAULT '',
  description TEXT NOT NULL DEFAULT '',
  created_by TEXT NOT NULL DEFAULT '',
  created_at_ms BIGINT NOT NULL,
  expires_at_ms BIGINT NOT NULL DEFAULT 0,
  revoked_at_ms BIGINT NOT NULL DEFAULT 0,
  CHECK ((role = 'vessel') = (length(vessel_id) > 0)));
CREATE TABLE audit_log (
  seq BIGINT GENERATED ALWAYS AS IDENTITY PRIMARY KEY,
  time_ms BIGINT NOT NULL,
  token_id TEXT NOT NULL,
  role TEXT NOT NULL,
  vessel_id TEXT NOT NULL,
  action TEXT NOT NULL CHECK (length(action) > 0),
  target TEXT NOT NULL,
  detail TEXT NOT NULL);
CREATE FUNCTION seaplan_audit_log_append_only() RETURNS trigger LANGUAGE plpgsql AS $$
BEGIN
  RAISE EXCEPTION 'the audit log is append-only';
END $$;
CREATE TRIGGER audit_log_no_change BEFORE UPDATE OR DELETE ON audit_log
  FOR EACH ROW EXECUTE FUNCTION seaplan_audit_log_append_only();
CREATE TRIGGER audit_log_no_truncate BEFORE TRUNCATE ON audit_log
  FOR EACH STATEMENT EXECUTE FUNCTION seaplan_audit_log_append_only();
)sql"},
};
static_assert(std::size(kMigrations) == 4, "one PostgreSQL migration per schema history entry");

// Type OIDs of the parameters and results used here (pg_type.h is in the
// server headers, which libpq-dev does not ship).
constexpr Oid kBoolOid = 16;
constexpr Oid kByteaOid = 17;
constexpr Oid kInt8Oid = 20;
constexpr Oid kInt2Oid = 21;
constexpr Oid kInt4Oid = 23;
constexpr Oid kTextOid = 25;
constexpr Oid kFloat8Oid = 701;

std::string TrimMessage(const char* message) {
  return std::string(absl::StripTrailingAsciiWhitespace(message ? message : ""));
}

// Maps an error to a status by its SQLSTATE class.
absl::Status PgStatus(PGconn* conn, const PGresult* result, const std::string& what) {
  if (result == nullptr || PQstatus(conn) != CONNECTION_OK) {
    return absl::UnavailableError(
        absl::StrCat("postgresql ", what, ": ", TrimMessage(PQerrorMessage(conn))));
  }
  const char* state_field = PQresultErrorField(result, PG_DIAG_SQLSTATE);
  const std::string state = state_field ? state_field : "";
  const std::string msg = absl::StrCat("postgresql ", what, ": ",
                                       TrimMessage(PQresultErrorMessage(result)), " [", state, "]");
  if (state == "23505") return absl::AlreadyExistsError(msg);
  if (state.starts_with("23") || state.starts_with("22")) return absl::InvalidArgumentError(msg);
  if (state == "40001" || state == "40P01") return absl::AbortedError(msg);
  if (state.starts_with("08") || state.starts_with("57P") || state == "55P03") {
    return absl::UnavailableError(msg);
  }
  if (state.starts_with("53")) return absl::ResourceExhaustedError(msg);
  return absl::InternalError(msg);
}

// Query parameters, sent in binary.
class Params {
 public:
  Params& I8(std::int64_t v) {
    const std::uint64_t be = htobe64(static_cast<std::uint64_t>(v));
    return Add(kInt8Oid, std::string(reinterpret_cast<const char*>(&be), 8));
  }
  Params& I4(int v) {
    const std::uint32_t be = htobe32(static_cast<std::uint32_t>(v));
    return Add(kInt4Oid, std::string(reinterpret_cast<const char*>(&be), 4));
  }
  Params& F8(double v) {
    const std::uint64_t be = htobe64(std::bit_cast<std::uint64_t>(v));
    return Add(kFloat8Oid, std::string(reinterpret_cast<const char*>(&be), 8));
  }
  Params& Text(std::string_view v) { return Add(kTextOid, std::string(v)); }
  Params& Bytea(std::string_view v) { return Add(kByteaOid, std::string(v)); }
  Params& Null(Oid type) {
    types_.push_back(type);
    values_.emplace_back();
    null_.push_back(true);
    return *this;
  }
  template <typename T, typename F>
  Params& Opt(const std::optional<T>& v, Oid type, F&& add) {
    if (!v) return Null(type);
    return add(*this, *v);
  }

  int size() const { return static_cast<int>(types_.size()); }
  const Oid* types() const { return types_.data(); }
  // Pointers into values_: valid until the next Add.
  void Arrays(std::vector<const char*>* values, std::vector<int>* lengths,
              std::vector<int>* formats) const {
    for (std::size_t i = 0; i < values_.size(); ++i) {
      values->push_back(null_[i] ? nullptr : values_[i].data());
      lengths->push_back(static_cast<int>(values_[i].size()));
      formats->push_back(1);
    }
  }

 private:
  Params& Add(Oid type, std::string value) {
    types_.push_back(type);
    values_.push_back(std::move(value));
    null_.push_back(false);
    return *this;
  }
  std::vector<Oid> types_;
  std::vector<std::string> values_;
  std::vector<bool> null_;
};

// A query result in binary format (RAII). Rows and columns are 0-based.
class Result {
 public:
  explicit Result(PGresult* r) : r_(r) {}
  ~Result() { PQclear(r_); }
  Result(Result&& o) noexcept : r_(std::exchange(o.r_, nullptr)) {}
  Result& operator=(Result&& o) noexcept {
    std::swap(r_, o.r_);
    return *this;
  }

  int rows() const { return PQntuples(r_); }
  // Rows an INSERT/UPDATE/DELETE touched.
  std::int64_t affected() const {
    const char* n = PQcmdTuples(r_);
    return (n && *n) ? std::atoll(n) : 0;
  }
  std::int64_t Int(int row, int col) const {
    if (PQgetisnull(r_, row, col)) return 0;
    const char* p = PQgetvalue(r_, row, col);
    switch (PQftype(r_, col)) {
      case kInt8Oid: {
        std::uint64_t v;
        std::memcpy(&v, p, 8);
        return static_cast<std::int64_t>(be64toh(v));
      }
      case kInt4Oid: {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return static_cast<std::int32_t>(be32toh(v));
      }
      case kInt2Oid: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return static_cast<std::int16_t>(be16toh(v));
      }
      case kBoolOid:
        return *p != 0;
      default:
        return 0;  // a programming error in a query here; every test would catch it
    }
  }
  double Real(int row, int col) const {
    std::uint64_t v;
    std::memcpy(&v, PQgetvalue(r_, row, col), 8);
    return std::bit_cast<double>(be64toh(v));
  }
  // text and bytea arrive as their raw bytes in binary format.
  std::string Bytes(int row, int col) const {
    return std::string(PQgetvalue(r_, row, col),
                       static_cast<std::size_t>(PQgetlength(r_, row, col)));
  }

 private:
  PGresult* r_;
};

// One row of a Result as the shared row readers (store_internal.h) want it.
struct ResultRow {
  const Result& r;
  int row;
  std::int64_t Int(int c) const { return r.Int(row, c); }
  double Real(int c) const { return r.Real(row, c); }
  std::string Bytes(int c) const { return r.Bytes(row, c); }
};

// Runs SQL without parameters (several statements allowed).
absl::Status ExecScript(PGconn* conn, const char* sql) {
  PGresult* r = PQexec(conn, sql);
  const ExecStatusType st = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
  absl::Status status =
      (st == PGRES_COMMAND_OK || st == PGRES_TUPLES_OK) ? absl::OkStatus() : PgStatus(conn, r, sql);
  PQclear(r);
  return status;
}

void IgnoreNotice(void*, const char*) {}

// Opens a connection; `extra` keyword/value pairs are applied on top of the URL.
absl::StatusOr<PGconn*> Connect(const std::string& url,
                                const std::vector<std::pair<const char*, const char*>>& extra) {
  std::vector<const char*> keys = {"fallback_application_name", "dbname"};
  std::vector<const char*> values = {"seaplan", url.c_str()};
  for (const auto& [k, v] : extra) {
    keys.push_back(k);
    values.push_back(v);
  }
  keys.push_back(nullptr);
  values.push_back(nullptr);
  PGconn* conn = PQconnectdbParams(keys.data(), values.data(), /*expand_dbname=*/1);
  if (conn == nullptr) return absl::ResourceExhaustedError("postgresql: out of memory");
  if (PQstatus(conn) != CONNECTION_OK) {
    absl::Status st = absl::UnavailableError(absl::StrCat(
        "cannot connect to ", RedactDatabaseUrl(url), ": ", TrimMessage(PQerrorMessage(conn))));
    PQfinish(conn);
    return st;
  }
  // IF NOT EXISTS and similar notices would go to stderr by default.
  PQsetNoticeProcessor(conn, IgnoreNotice, nullptr);
  return conn;
}

// Raises synchronous_commit to "on" when the server default would
// acknowledge commits before they are flushed.
absl::Status RequireDurableCommits(PGconn* conn) {
  PGresult* r = PQexec(conn, "SHOW synchronous_commit");
  if (PQresultStatus(r) != PGRES_TUPLES_OK) {
    absl::Status st = PgStatus(conn, r, "SHOW synchronous_commit");
    PQclear(r);
    return st;
  }
  const std::string value = PQgetvalue(r, 0, 0);
  PQclear(r);
  if (value == "off" || value == "local") {
    return ExecScript(conn, "SET synchronous_commit = on");
  }
  return absl::OkStatus();
}

// ---------------------------------------------------------------------------
// The connection pool.
class Pool;

// A connection taken from the pool; returned on destruction.
class PooledConn {
 public:
  PooledConn(Pool* pool, PGconn* conn) : pool_(pool), conn_(conn) {}
  PooledConn(PooledConn&& o) noexcept : pool_(o.pool_), conn_(std::exchange(o.conn_, nullptr)) {}
  PooledConn& operator=(PooledConn&&) = delete;
  ~PooledConn();
  PGconn* get() const { return conn_; }

 private:
  Pool* pool_;
  PGconn* conn_;
};

class Pool {
 public:
  Pool(std::string url, const PostgresOptions& options) : url_(std::move(url)), options_(options) {}
  ~Pool() { Close(); }

  absl::StatusOr<PooledConn> Acquire() {
    std::unique_lock lock(mu_);
    const bool ready = cv_.wait_for(lock, options_.acquire_timeout, [&] {
      return closed_ || !idle_.empty() || open_ < options_.pool_size;
    });
    if (closed_) return absl::FailedPreconditionError("database is closed");
    if (!ready) {
      return absl::UnavailableError(absl::StrCat("no free database connection within ",
                                                 options_.acquire_timeout.count(), " ms"));
    }
    if (!idle_.empty()) {
      PGconn* conn = idle_.back();
      idle_.pop_back();
      return PooledConn(this, conn);
    }
    ++open_;
    lock.unlock();
    absl::StatusOr<PGconn*> conn = Connect(url_, {});
    if (conn.ok()) {
      absl::Status st = RequireDurableCommits(*conn);
      if (!st.ok()) {
        PQfinish(*conn);
        conn = st;
      }
    }
    if (!conn.ok()) {
      lock.lock();
      --open_;
      cv_.notify_one();
      return conn.status();
    }
    return PooledConn(this, *conn);
  }

  void Return(PGconn* conn) {
    std::lock_guard lock(mu_);
    // A connection that failed, or is left inside a transaction, is dropped:
    // the next Acquire opens a fresh one.
    if (closed_ || PQstatus(conn) != CONNECTION_OK || PQtransactionStatus(conn) != PQTRANS_IDLE) {
      PQfinish(conn);
      --open_;
    } else {
      idle_.push_back(conn);
    }
    cv_.notify_one();
  }

  void Close() {
    std::lock_guard lock(mu_);
    closed_ = true;
    for (PGconn* conn : idle_) PQfinish(conn);
    open_ -= static_cast<int>(idle_.size());
    idle_.clear();
    cv_.notify_all();
  }

  bool closed() {
    std::lock_guard lock(mu_);
    return closed_;
  }

 private:
  const std::string url_;
  const PostgresOptions options_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::vector<PGconn*> idle_;
  int open_ = 0;  // idle + in use
  bool closed_ = false;
};

PooledConn::~PooledConn() {
  if (conn_ != nullptr) pool_->Return(conn_);
}

// ---------------------------------------------------------------------------
// The LISTEN side of the change feed: one thread on its own connection.
class Listener {
 public:
  Listener(std::string url, internal::LocalChangeFeed& feed, std::chrono::milliseconds retry)
      : url_(std::move(url)), feed_(feed), retry_(retry) {}
  ~Listener() { Stop(); }

  absl::Status Start() {
    if (pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) {
      return absl::InternalError(absl::StrCat("pipe: ", std::strerror(errno)));
    }
    SEAPLAN_ASSIGN_OR_RETURN(conn_, ConnectAndListen());
    thread_ = std::thread([this] { Loop(); });
    return absl::OkStatus();
  }

  void Stop() {
    if (thread_.joinable()) {
      const char byte = 1;
      (void)!write(wake_[1], &byte, 1);
      thread_.join();
    }
    if (conn_ != nullptr) PQfinish(conn_);
    conn_ = nullptr;
    for (int& fd : wake_) {
      if (fd >= 0) close(fd);
      fd = -1;
    }
  }

 private:
  absl::StatusOr<PGconn*> ConnectAndListen() {
    // Keepalives notice a server that vanished without closing the socket.
    SEAPLAN_ASSIGN_OR_RETURN(PGconn * conn, Connect(url_, {{"keepalives_idle", "10"},
                                                           {"keepalives_interval", "5"},
                                                           {"keepalives_count", "3"}}));
    absl::Status st = ExecScript(conn, absl::StrCat("LISTEN ", kChangeChannel).c_str());
    if (!st.ok()) {
      PQfinish(conn);
      return st;
    }
    return conn;
  }

  // Waits for the connection's socket (or only the wake pipe when
  // `socket` < 0) up to `timeout_ms`; false when asked to stop.
  bool WaitReadable(int socket, int timeout_ms) {
    pollfd fds[2] = {{wake_[0], POLLIN, 0}, {socket, POLLIN, 0}};
    const int n = poll(fds, socket >= 0 ? 2 : 1, timeout_ms);
    return !(n > 0 && (fds[0].revents & POLLIN));
  }

  void Loop() {
    while (true) {
      if (conn_ == nullptr) {
        if (!WaitReadable(-1, static_cast<int>(retry_.count()))) return;
        absl::StatusOr<PGconn*> conn = ConnectAndListen();
        if (!conn.ok()) {
          log::Warn("storage: change listener: {}", std::string(conn.status().message()));
          continue;
        }
        conn_ = *conn;
        log::Info("storage: change listener reconnected");
        feed_.BumpAll();  // notifications sent while disconnected are lost
      }
      if (!WaitReadable(PQsocket(conn_), -1)) return;
      const bool alive = PQconsumeInput(conn_) == 1;
      while (PGnotify* n = PQnotifies(conn_)) {
        const std::string mission_id = n->extra ? n->extra : "";
        PQfreemem(n);
        if (mission_id.empty()) {
          feed_.BumpAll();
        } else {
          feed_.Bump(mission_id);
        }
      }
      if (!alive || PQstatus(conn_) != CONNECTION_OK) {
        log::Warn("storage: change listener lost its connection: {}",
                  TrimMessage(PQerrorMessage(conn_)));
        PQfinish(conn_);
        conn_ = nullptr;
        feed_.BumpAll();
      }
    }
  }

  const std::string url_;
  internal::LocalChangeFeed& feed_;
  const std::chrono::milliseconds retry_;
  PGconn* conn_ = nullptr;  // owned by the thread once it runs
  int wake_[2] = {-1, -1};
  std::thread thread_;
};

}  // namespace

// ---------------------------------------------------------------------------
struct PostgresStore::Impl final : ChartRepository, MissionRepository {
  Impl(std::string url_in, const PostgresOptions& options)
      : url(std::move(url_in)), pool(url, options), listener(url, feed, options.listener_retry) {}

  const std::string url;
  Pool pool;
  internal::LocalChangeFeed feed;
  Listener listener;

  // Runs `body(conn)` on a pooled connection.
  template <typename F>
  auto WithConn(F&& body) -> decltype(body(std::declval<PGconn*>())) {
    SEAPLAN_ASSIGN_OR_RETURN(PooledConn conn, pool.Acquire());
    return body(conn.get());
  }

  // Runs `body(conn)` between BEGIN and COMMIT; rolls back on any error.
  template <typename F>
  absl::Status InTransaction(F&& body) {
    SEAPLAN_ASSIGN_OR_RETURN(PooledConn conn, pool.Acquire());
    SEAPLAN_RETURN_IF_ERROR(ExecScript(conn.get(), "BEGIN"));
    absl::Status st = body(conn.get());
    if (!st.ok()) {
      (void)ExecScript(conn.get(), "ROLLBACK");
      return st;
    }
    st = ExecScript(conn.get(), "COMMIT");
    if (!st.ok() && PQstatus(conn.get()) != CONNECTION_OK) {
      return absl::UnavailableError(
          absl::StrCat("the connection was lost during COMMIT, so whether the write was stored "
                       "is unknown (retry it): ",
                       st.message()));
    }
    return st;
  }

  // Runs a statement and checks its status.
  static absl::StatusOr<Result> Run(PGconn* conn, const std::string& sql,
                                    const Params& params = {}) {
    std::vector<const char*> values;
    std::vector<int> lengths, formats;
    params.Arrays(&values, &lengths, &formats);
    PGresult* r = PQexecParams(conn, sql.c_str(), params.size(), params.types(), values.data(),
                               lengths.data(), formats.data(), /*resultFormat=*/1);
    const ExecStatusType st = r ? PQresultStatus(r) : PGRES_FATAL_ERROR;
    if (st != PGRES_COMMAND_OK && st != PGRES_TUPLES_OK) {
      absl::Status status = PgStatus(conn, r, "query");
      PQclear(r);
      return status;
    }
    return Result(r);
  }

  // ---- schema ----
  absl::StatusOr<int> SchemaVersionOn(PGconn* conn) {
    SEAPLAN_ASSIGN_OR_RETURN(Result r, Run(conn, "SELECT version FROM seaplan_schema"));
    return r.rows() == 0 ? 0 : static_cast<int>(r.Int(0, 0));
  }

  absl::Status Migrate() {
    const auto history = internal::SchemaHistory();
    if (history.size() != std::size(kMigrations)) {
      return absl::InternalError("PostgreSQL migrations do not match the schema history");
    }
    for (std::size_t i = 0; i < history.size(); ++i) {
      const Migration& m = kMigrations[i];
      if (m.version != history[i].version) {
        return absl::InternalError("PostgreSQL migrations do not match the schema history");
      }
      bool applied = false;
      absl::Status st = InTransaction([&](PGconn* conn) -> absl::Status {
        SEAPLAN_RETURN_IF_ERROR(
            Run(conn, "SELECT pg_advisory_xact_lock($1)", Params().I8(kMigrationLockKey)).status());
        SEAPLAN_RETURN_IF_ERROR(
            ExecScript(conn,
                       "CREATE TABLE IF NOT EXISTS seaplan_schema ("
                       "one_row BOOLEAN PRIMARY KEY DEFAULT TRUE CHECK (one_row), "
                       "version INTEGER NOT NULL); "
                       "INSERT INTO seaplan_schema(version) VALUES (0) "
                       "ON CONFLICT DO NOTHING"));
        SEAPLAN_ASSIGN_OR_RETURN(int current, SchemaVersionOn(conn));
        if (current > LatestSchemaVersion()) {
          return absl::FailedPreconditionError(absl::StrCat(
              "database schema version ", current, " is newer than this server knows (",
              LatestSchemaVersion(), "); refusing to touch it"));
        }
        if (current >= m.version) return absl::OkStatus();
        SEAPLAN_RETURN_IF_ERROR(ExecScript(conn, m.sql));
        applied = true;
        return Run(conn, "UPDATE seaplan_schema SET version = $1", Params().I4(m.version)).status();
      });
      if (absl::IsFailedPrecondition(st)) return st;
      if (!st.ok()) {
        return absl::Status(st.code(),
                            absl::StrCat("schema migration to version ", m.version, " (",
                                         history[i].description, ") failed: ", st.message()));
      }
      if (applied) {
        log::Info("storage: migrated schema to version {} ({})", m.version, history[i].description);
      }
    }
    return absl::OkStatus();
  }

  // ---- helpers inside a transaction ----
  // Locks the mission's row until the transaction ends, so that writers of
  // one mission in every process take turns; returns current_version.
  static absl::StatusOr<int> LockMission(PGconn* conn, const std::string& id) {
    SEAPLAN_ASSIGN_OR_RETURN(
        Result r, Run(conn, "SELECT current_version FROM missions WHERE id = $1 FOR UPDATE",
                      Params().Text(id)));
    if (r.rows() == 0) return absl::NotFoundError(NotFoundMessage("mission", id));
    return static_cast<int>(r.Int(0, 0));
  }

  // The caller holds the mission's row lock (or has just inserted it).
  static absl::StatusOr<std::vector<LogEventRecord>> AppendEventsLocked(
      PGconn* conn, const std::string& mission_id, const std::vector<NewLogEvent>& events) {
    std::vector<LogEventRecord> out;
    if (events.empty()) return out;
    SEAPLAN_ASSIGN_OR_RETURN(
        Result next,
        Run(conn, "SELECT COALESCE(MAX(event_id), 0) FROM log_events WHERE mission_id = $1",
            Params().Text(mission_id)));
    std::int64_t id = next.Int(0, 0);
    for (const NewLogEvent& e : events) {
      SEAPLAN_RETURN_IF_ERROR(
          Run(conn,
              "INSERT INTO log_events(mission_id, event_id, time_ms, mission_time_s, source, "
              "message) VALUES ($1, $2, $3, $4, $5, $6)",
              Params()
                  .Text(mission_id)
                  .I8(++id)
                  .I8(e.time_ms)
                  .F8(e.mission_time_s)
                  .Text(e.source)
                  .Text(e.message))
              .status());
      out.push_back({mission_id, id, e.time_ms, e.mission_time_s, e.source, e.message});
    }
    return out;
  }

  // Returns true when the mission had no pending work before.
  static absl::StatusOr<bool> RequestWorkLocked(PGconn* conn, const std::string& mission_id,
                                                const WorkRequest& r) {
    SEAPLAN_ASSIGN_OR_RETURN(
        Result res,
        Run(conn,
            absl::StrCat(
                "INSERT INTO mission_work AS w (mission_id, reason, base_version, "
                "requested_at_ms, requests) VALUES ($1, $2, $3, ",
                kDbNowMs,
                ", 1) ON CONFLICT (mission_id) DO UPDATE SET reason = EXCLUDED.reason, "
                "base_version = EXCLUDED.base_version, requests = w.requests + 1, "
                "requested_at_ms = CASE WHEN w.requests > w.done_requests THEN w.requested_at_ms "
                "ELSE EXCLUDED.requested_at_ms END RETURNING w.requests - w.done_requests"),
            Params().Text(mission_id).Text(r.reason).I4(r.base_version)));
    return res.Int(0, 0) == 1;
  }

  // Locks the work row so that a claim cannot slip in before the commit.
  static absl::Status CheckFenceLocked(PGconn* conn, const std::string& id, const WorkFence& f) {
    SEAPLAN_ASSIGN_OR_RETURN(
        Result r, Run(conn,
                      "SELECT 1 FROM mission_work WHERE mission_id = $1 AND holder = $2 AND "
                      "token = $3 FOR UPDATE",
                      Params().Text(id).Text(f.holder).I8(f.token)));
    if (r.rows() == 0) return internal::LostLeaseError(id, f);
    return absl::OkStatus();
  }

  static absl::Status ApplyUpdateLocked(PGconn* conn, const std::string& id, const MissionUpdate& u,
                                        TimestampMs now_ms) {
    if (u.fence) SEAPLAN_RETURN_IF_ERROR(CheckFenceLocked(conn, id, *u.fence));
    Params p;
    p.Text(id);
    p.Opt(u.state, kInt4Oid, [](Params& q, int v) -> Params& { return q.I4(v); });
    p.Opt(u.last_state, kByteaOid,
          [](Params& q, const std::string& v) -> Params& { return q.Bytea(v); });
    if (u.completed_tasks) {
      p.Text(JoinTasks(*u.completed_tasks));
    } else {
      p.Null(kTextOid);
    }
    p.Opt(u.failure_reason, kTextOid,
          [](Params& q, const std::string& v) -> Params& { return q.Text(v); });
    p.I8(now_ms);
    SEAPLAN_ASSIGN_OR_RETURN(
        Result r, Run(conn,
                      "UPDATE missions SET state = COALESCE($2, state), last_state = COALESCE($3, "
                      "last_state), completed_tasks = COALESCE($4, completed_tasks), "
                      "failure_reason = COALESCE($5, failure_reason), updated_at_ms = $6 "
                      "WHERE id = $1",
                      p));
    if (r.affected() == 0) return absl::NotFoundError(NotFoundMessage("mission", id));
    if (u.request_work)
      SEAPLAN_RETURN_IF_ERROR(RequestWorkLocked(conn, id, *u.request_work).status());
    return InsertAuditIfAny(conn, u.audit ? &*u.audit : nullptr);
  }

  // Appends an audit row (inside the transaction of the change it
  // records, when there is one) and returns its seq.
  static absl::StatusOr<std::int64_t> InsertAudit(PGconn* conn, const AuditRecord& a) {
    SEAPLAN_ASSIGN_OR_RETURN(
        Result r, Run(conn,
                      "INSERT INTO audit_log(time_ms, token_id, role, vessel_id, action, "
                      "target, detail) VALUES ($1, $2, $3, $4, $5, $6, $7) RETURNING seq",
                      Params()
                          .I8(a.time_ms)
                          .Text(a.token_id)
                          .Text(a.role)
                          .Text(a.vessel_id)
                          .Text(a.action)
                          .Text(a.target)
                          .Text(a.detail)));
    return r.Int(0, 0);
  }

  static absl::Status InsertAuditIfAny(PGconn* conn, const AuditRecord* audit) {
    if (audit == nullptr) return absl::OkStatus();
    return InsertAudit(conn, *audit).status();
  }

  // ---- ChartRepository ----
  absl::StatusOr<ChartRecord> Insert(ChartRecord c, const AuditRecord* audit) override {
    const absl::Status written = InTransaction([&](PGconn* conn) -> absl::Status {
      absl::StatusOr<Result> r =
          Run(conn,
              "INSERT INTO charts(id, name, format, options, summary, obstacles, source_files, "
              "created_at_ms) VALUES ($1, $2, $3, $4, $5, $6, $7, $8) RETURNING seq",
              Params()
                  .Text(c.id)
                  .Text(c.name)
                  .I4(c.format)
                  .Bytea(c.options)
                  .Bytea(c.summary)
                  .Bytea(c.obstacles)
                  .Bytea(c.source_files)
                  .I8(c.created_at_ms));
      if (absl::IsAlreadyExists(r.status())) {
        return absl::AlreadyExistsError(absl::StrCat("chart '", c.id, "' exists"));
      }
      SEAPLAN_RETURN_IF_ERROR(r.status());
      c.seq = r->Int(0, 0);
      return InsertAuditIfAny(conn, audit);
    });
    if (!written.ok()) return written;
    return c;
  }

  absl::StatusOr<ChartRecord> Get(const std::string& id, bool with_blobs) override {
    return WithConn([&](PGconn* conn) -> absl::StatusOr<ChartRecord> {
      SEAPLAN_ASSIGN_OR_RETURN(
          Result r,
          Run(conn,
              with_blobs ? "SELECT seq, id, name, format, options, summary, "
                           "created_at_ms, obstacles, source_files FROM charts WHERE id = $1"
                         : "SELECT seq, id, name, format, options, summary, "
                           "created_at_ms FROM charts WHERE id = $1",
              Params().Text(id)));
      if (r.rows() == 0) return absl::NotFoundError(NotFoundMessage("chart", id));
      return internal::ReadChart(ResultRow{r, 0}, with_blobs);
    });
  }

  absl::Status Delete(const std::string& id, const ChartUse& use,
                      const AuditRecord* audit) override {
    return InTransaction([&](PGconn* conn) -> absl::Status {
      SEAPLAN_ASSIGN_OR_RETURN(
          Result chart,
          Run(conn, "SELECT 1 FROM charts WHERE id = $1 FOR UPDATE", Params().Text(id)));
      if (chart.rows() == 0) return absl::NotFoundError(NotFoundMessage("chart", id));
      // Mission writes of other processes wait until this commits, so the
      // check below sees every mission that can use the chart.
      SEAPLAN_RETURN_IF_ERROR(Run(conn, "LOCK TABLE missions IN SHARE MODE").status());
      SEAPLAN_ASSIGN_OR_RETURN(
          Result active,
          Run(conn, absl::StrCat("SELECT id, spec FROM missions WHERE state IN ",
                                 internal::SqlIntList(use.active_states), " ORDER BY seq")));
      std::vector<std::string> users;
      for (int row = 0; row < active.rows(); ++row) {
        if (use.spec_uses_chart && use.spec_uses_chart(active.Bytes(row, 1), id))
          users.push_back(active.Bytes(row, 0));
      }
      if (!users.empty()) return internal::ChartInUseError(id, users);
      SEAPLAN_RETURN_IF_ERROR(
          Run(conn, "DELETE FROM charts WHERE id = $1", Params().Text(id)).status());
      return InsertAuditIfAny(conn, audit);
    });
  }

  // Fills a page from rows fetched with LIMIT page_size + 1.
  template <typename T, typename Read>
  static Page<T> ToPage(const Result& r, int page_size, Read&& read) {
    Page<T> page;
    for (int row = 0; row < r.rows(); ++row) {
      if (row == page_size) {
        page.next_after = page.items.back().seq;
        break;
      }
      page.items.push_back(read(r, row));
    }
    return page;
  }

  absl::StatusOr<Page<ChartRecord>> List(int page_size, std::int64_t after) override {
    SEAPLAN_RETURN_IF_ERROR(CheckPageSize(page_size));
    return WithConn([&](PGconn* conn) -> absl::StatusOr<Page<ChartRecord>> {
      SEAPLAN_ASSIGN_OR_RETURN(
          Result r, Run(conn,
                        "SELECT seq, id, name, format, options, summary, created_at_ms FROM charts "
                        "WHERE seq > $1 ORDER BY seq LIMIT $2",
                        Params().I8(after).I8(page_size + 1)));
      return ToPage<ChartRecord>(r, page_size, [](const Result& res, int row) {
        return internal::ReadChart(ResultRow{res, row}, false);
      });
    });
  }

  // ---- MissionRepository ----
  static absl::Status InsertVersionLocked(PGconn* conn, const PlanVersionRecord& v) {
    return Run(conn,
               "INSERT INTO plan_versions(mission_id, version, reason, created_at_ms, content, "
               "engine_state) VALUES ($1, $2, $3, $4, $5, $6)",
               Params()
                   .Text(v.mission_id)
                   .I4(v.version)
                   .Text(v.reason)
                   .I8(v.created_at_ms)
                   .Bytea(v.content)
                   .Bytea(v.engine_state))
        .status();
  }

  absl::Status Create(const MissionRecord& m, const PlanVersionRecord& first,
                      const std::vector<NewLogEvent>& events, const AuditRecord* audit,
                      const std::string& chart_id) override {
    if (first.version != 1 || first.mission_id != m.id) {
      return absl::InvalidArgumentError(
          "the first plan version must be version 1 of the same mission");
    }
    return InTransaction([&](PGconn* conn) -> absl::Status {
      if (!chart_id.empty()) {
        // FOR SHARE conflicts with the FOR UPDATE a deletion takes first: a
        // deletion under way is waited for (the row is then gone), and one
        // that starts later waits for this commit and sees the mission.
        SEAPLAN_ASSIGN_OR_RETURN(
            Result chart,
            Run(conn, "SELECT 1 FROM charts WHERE id = $1 FOR SHARE", Params().Text(chart_id)));
        if (chart.rows() == 0) return absl::NotFoundError(NotFoundMessage("chart", chart_id));
      }
      Params p;
      p.Text(m.id).Text(m.name).Text(m.vessel_id);
      if (m.request_id.empty()) {
        p.Null(kTextOid);
      } else {
        p.Text(m.request_id);
      }
      p.Bytea(m.spec)
          .I4(m.state)
          .I8(m.created_at_ms)
          .I8(m.updated_at_ms)
          .Bytea(m.last_state)
          .Text(JoinTasks(m.completed_tasks))
          .Text(m.failure_reason);
      absl::Status st =
          Run(conn,
              "INSERT INTO missions(id, name, vessel_id, request_id, spec, state, "
              "current_version, created_at_ms, updated_at_ms, last_state, completed_tasks, "
              "failure_reason) VALUES ($1, $2, $3, $4, $5, $6, 1, $7, $8, $9, $10, $11)",
              p)
              .status();
      if (absl::IsAlreadyExists(st)) {
        return absl::AlreadyExistsError(
            absl::StrCat("mission '", m.id, "' or request id '", m.request_id, "' exists"));
      }
      SEAPLAN_RETURN_IF_ERROR(st);
      SEAPLAN_RETURN_IF_ERROR(InsertVersionLocked(conn, first));
      SEAPLAN_RETURN_IF_ERROR(AppendEventsLocked(conn, m.id, events).status());
      return InsertAuditIfAny(conn, audit);
    });
  }

  absl::StatusOr<std::optional<MissionRecord>> FindMission(const char* where,
                                                           const std::string& key) {
    return WithConn([&](PGconn* conn) -> absl::StatusOr<std::optional<MissionRecord>> {
      SEAPLAN_ASSIGN_OR_RETURN(
          Result r,
          Run(conn, absl::StrCat("SELECT ", kMissionColumns, " FROM missions WHERE ", where),
              Params().Text(key)));
      if (r.rows() == 0) return std::optional<MissionRecord>();
      return std::optional<MissionRecord>(internal::ReadMission(ResultRow{r, 0}));
    });
  }

  absl::StatusOr<MissionRecord> Get(const std::string& id) override {
    SEAPLAN_ASSIGN_OR_RETURN(std::optional<MissionRecord> m, FindMission("id = $1", id));
    if (!m) return absl::NotFoundError(NotFoundMessage("mission", id));
    return *std::move(m);
  }

  absl::StatusOr<std::optional<MissionRecord>> FindByRequestId(
      const std::string& request_id) override {
    return FindMission("request_id = $1", request_id);
  }

  absl::StatusOr<Page<MissionRecord>> List(int state, int page_size, std::int64_t after) override {
    SEAPLAN_RETURN_IF_ERROR(CheckPageSize(page_size));
    return WithConn([&](PGconn* conn) -> absl::StatusOr<Page<MissionRecord>> {
      SEAPLAN_ASSIGN_OR_RETURN(
          Result r,
          Run(conn,
              absl::StrCat("SELECT ", kMissionColumns,
                           " FROM missions WHERE seq > $1 AND ($2 = 0 OR state = $2) ORDER BY seq "
                           "LIMIT $3"),
              Params().I8(after).I4(state).I8(page_size + 1)));
      return ToPage<MissionRecord>(r, page_size, [](const Result& res, int row) {
        return internal::ReadMission(ResultRow{res, row});
      });
    });
  }

  absl::Status Update(const std::string& id, const MissionUpdate& update,
                      const std::vector<NewLogEvent>& events) override {
    return InTransaction([&](PGconn* conn) -> absl::Status {
      SEAPLAN_RETURN_IF_ERROR(LockMission(conn, id).status());
      SEAPLAN_RETURN_IF_ERROR(ApplyUpdateLocked(conn, id, update, LatestTime(events, NowMs())));
      return AppendEventsLocked(conn, id, events).status();
    });
  }

  absl::Status AppendVersion(const PlanVersionRecord& v, const MissionUpdate& update,
                             const std::vector<NewLogEvent>& events) override {
    return InTransaction([&](PGconn* conn) -> absl::Status {
      SEAPLAN_ASSIGN_OR_RETURN(int current, LockMission(conn, v.mission_id));
      if (v.version != current + 1) {
        return absl::AbortedError(absl::StrCat("plan version ", v.version, " of mission '",
                                               v.mission_id, "' is not next (current is ", current,
                                               ")"));
      }
      SEAPLAN_RETURN_IF_ERROR(InsertVersionLocked(conn, v));
      SEAPLAN_RETURN_IF_ERROR(Run(conn, "UPDATE missions SET current_version = $2 WHERE id = $1",
                                  Params().Text(v.mission_id).I4(v.version))
                                  .status());
      SEAPLAN_RETURN_IF_ERROR(AppendEventsLocked(conn, v.mission_id, events).status());
      return ApplyUpdateLocked(conn, v.mission_id, update,
                               std::max(v.created_at_ms, LatestTime(events, 0)));
    });
  }

  absl::StatusOr<std::vector<PlanVersionRecord>> QueryVersions(const std::string& mission_id,
                                                               const char* condition, int value,
                                                               int limit) {
    return WithConn([&](PGconn* conn) -> absl::StatusOr<std::vector<PlanVersionRecord>> {
      SEAPLAN_ASSIGN_OR_RETURN(
          Result r, Run(conn,
                        absl::StrCat("SELECT mission_id, version, reason, created_at_ms, content, "
                                     "engine_state FROM plan_versions WHERE mission_id = $1 AND ",
                                     condition, " ORDER BY version LIMIT $3"),
                        Params().Text(mission_id).I4(value).I8(limit)));
      std::vector<PlanVersionRecord> out;
      out.reserve(static_cast<std::size_t>(r.rows()));
      for (int row = 0; row < r.rows(); ++row)
        out.push_back(internal::ReadVersion(ResultRow{r, row}));
      return out;
    });
  }

  absl::StatusOr<PlanVersionRecord> GetVersion(const std::string& mission_id,
                                               int version) override {
    SEAPLAN_ASSIGN_OR_RETURN(std::vector<PlanVersionRecord> v,
                             QueryVersions(mission_id, "version = $2", version, 1));
    if (v.empty()) {
      return absl::NotFoundError(
          absl::StrCat("plan version ", version, " of mission '", mission_id, "' not found"));
    }
    return std::move(v[0]);
  }

  absl::StatusOr<std::vector<PlanVersionRecord>> ListVersions(const std::string& mission_id,
                                                              int after_version,
                                                              int limit) override {
    return QueryVersions(mission_id, "version > $2", after_version, limit);
  }

  absl::StatusOr<bool> RecordFeedback(const FeedbackRecord& f, const MissionUpdate& update,
                                      const std::vector<NewLogEvent>& events) override {
    bool inserted = false;
    const absl::Status written = InTransaction([&](PGconn* conn) -> absl::Status {
      SEAPLAN_RETURN_IF_ERROR(LockMission(conn, f.mission_id).status());
      // A concurrent insert of the same (vessel, sequence) in another
      // process waits for this one and then inserts nothing.
      SEAPLAN_ASSIGN_OR_RETURN(
          Result r, Run(conn,
                        "INSERT INTO feedback(mission_id, vessel_id, sequence_number, kind, "
                        "payload, received_at_ms) VALUES ($1, $2, $3, $4, $5, $6) "
                        "ON CONFLICT (vessel_id, sequence_number) DO NOTHING",
                        Params()
                            .Text(f.mission_id)
                            .Text(f.vessel_id)
                            .I8(f.sequence_number)
                            .I4(f.kind)
                            .Bytea(f.payload)
                            .I8(f.received_at_ms)));
      inserted = r.affected() == 1;
      if (!inserted) return absl::OkStatus();  // duplicate: change nothing
      SEAPLAN_RETURN_IF_ERROR(AppendEventsLocked(conn, f.mission_id, events).status());
      return ApplyUpdateLocked(conn, f.mission_id, update,
                               std::max(f.received_at_ms, LatestTime(events, 0)));
    });
    if (!written.ok()) return written;
    return inserted;
  }

  absl::StatusOr<std::optional<FeedbackRecord>> FindFeedback(
      const std::string& vessel_id, std::int64_t sequence_number) override {
    return WithConn([&](PGconn* conn) -> absl::StatusOr<std::optional<FeedbackRecord>> {
      SEAPLAN_ASSIGN_OR_RETURN(
          Result r,
          Run(conn,
              absl::StrCat("SELECT ", internal::kFeedbackColumns,
                           " FROM feedback WHERE vessel_id = $1 AND sequence_number = $2"),
              Params().Text(vessel_id).I8(sequence_number)));
      if (r.rows() == 0) return std::optional<FeedbackRecord>();
      return std::optional<FeedbackRecord>(internal::ReadFeedback(ResultRow{r, 0}));
    });
  }

  absl::StatusOr<std::vector<FeedbackRecord>> ListFeedback(const std::string& mission_id,
                                                           int limit) override {
    return WithConn([&](PGconn* conn) -> absl::StatusOr<std::vector<FeedbackRecord>> {
      // The latest `limit` rows, returned oldest first.
      SEAPLAN_ASSIGN_OR_RETURN(
          Result r,
          Run(conn,
              absl::StrCat("SELECT * FROM (SELECT ", internal::kFeedbackColumns,
                           " FROM feedback WHERE mission_id = $1 ORDER BY seq DESC LIMIT $2) "
                           "latest ORDER BY seq"),
              Params().Text(mission_id).I8(limit)));
      std::vector<FeedbackRecord> out;
      out.reserve(static_cast<std::size_t>(r.rows()));
      for (int row = 0; row < r.rows(); ++row)
        out.push_back(internal::ReadFeedback(ResultRow{r, row}));
      return out;
    });
  }

  absl::StatusOr<Page<FeedbackRecord>> ListFeedbackPage(const std::string& mission_id,
                                                        std::int64_t after,
                                                        int page_size) override {
    SEAPLAN_RETURN_IF_ERROR(CheckPageSize(page_size));
    return WithConn([&](PGconn* conn) -> absl::StatusOr<Page<FeedbackRecord>> {
      SEAPLAN_ASSIGN_OR_RETURN(Result r,
                               Run(conn,
                                   absl::StrCat("SELECT ", internal::kFeedbackColumns,
                                                " FROM feedback WHERE mission_id = $1 AND seq > $2 "
                                                "ORDER BY seq LIMIT $3"),
                                   Params().Text(mission_id).I8(after).I8(page_size + 1)));
      return ToPage<FeedbackRecord>(r, page_size, [](const Result& res, int row) {
        return internal::ReadFeedback(ResultRow{res, row});
      });
    });
  }

  absl::StatusOr<std::vector<LogEventRecord>> AppendEvents(
      const std::string& mission_id, const std::vector<NewLogEvent>& events) override {
    std::vector<LogEventRecord> out;
    const absl::Status written = InTransaction([&](PGconn* conn) -> absl::Status {
      SEAPLAN_RETURN_IF_ERROR(LockMission(conn, mission_id).status());
      SEAPLAN_ASSIGN_OR_RETURN(out, AppendEventsLocked(conn, mission_id, events));
      return absl::OkStatus();
    });
    if (!written.ok()) return written;
    return out;
  }

  absl::StatusOr<std::vector<LogEventRecord>> ListEvents(const std::string& mission_id,
                                                         std::int64_t after_event_id,
                                                         int limit) override {
    return WithConn([&](PGconn* conn) -> absl::StatusOr<std::vector<LogEventRecord>> {
      SEAPLAN_ASSIGN_OR_RETURN(
          Result r, Run(conn,
                        "SELECT mission_id, event_id, time_ms, mission_time_s, source, message "
                        "FROM log_events WHERE mission_id = $1 AND event_id > $2 "
                        "ORDER BY event_id LIMIT $3",
                        Params().Text(mission_id).I8(after_event_id).I8(limit)));
      std::vector<LogEventRecord> out;
      out.reserve(static_cast<std::size_t>(r.rows()));
      for (int row = 0; row < r.rows(); ++row) {
        out.push_back(internal::ReadEvent(ResultRow{r, row}));
      }
      return out;
    });
  }
};

// ---------------------------------------------------------------------------
class PostgresStore::Work final : public internal::WorkLeaseBase {
 public:
  explicit Work(Impl& impl) : impl_(impl) {}

  absl::StatusOr<bool> Request(const std::string& mission_id, const WorkRequest& r) override {
    bool was_idle = false;
    const absl::Status written = impl_.InTransaction([&](PGconn* conn) -> absl::Status {
      SEAPLAN_RETURN_IF_ERROR(Impl::LockMission(conn, mission_id).status());
      SEAPLAN_ASSIGN_OR_RETURN(was_idle, Impl::RequestWorkLocked(conn, mission_id, r));
      return absl::OkStatus();
    });
    if (!written.ok()) return written;
    return was_idle;
  }

  absl::StatusOr<int> ReleaseAll(const std::string& holder) override {
    return impl_.WithConn([&](PGconn* conn) -> absl::StatusOr<int> {
      SEAPLAN_ASSIGN_OR_RETURN(
          Result r, Impl::Run(conn,
                              "UPDATE mission_work SET holder = NULL, lease_expires_at_ms = NULL "
                              "WHERE holder = $1",
                              Params().Text(holder)));
      return static_cast<int>(r.affected());
    });
  }

  absl::StatusOr<std::optional<WorkLease>> Get(const std::string& mission_id) override {
    SEAPLAN_ASSIGN_OR_RETURN(
        std::vector<WorkLease> rows,
        Query(absl::StrCat("SELECT ", kWorkColumns, " FROM mission_work WHERE mission_id = $1"),
              Params().Text(mission_id)));
    if (rows.empty()) return std::optional<WorkLease>();
    return std::optional<WorkLease>(std::move(rows[0]));
  }

 private:
  absl::StatusOr<std::vector<WorkLease>> Query(const std::string& sql, const Params& params) {
    return impl_.WithConn([&](PGconn* conn) -> absl::StatusOr<std::vector<WorkLease>> {
      SEAPLAN_ASSIGN_OR_RETURN(Result r, Impl::Run(conn, sql, params));
      std::vector<WorkLease> out;
      out.reserve(static_cast<std::size_t>(r.rows()));
      for (int row = 0; row < r.rows(); ++row) out.push_back(internal::ReadWork(ResultRow{r, row}));
      return out;
    });
  }

  // SKIP LOCKED: an item another claimer is taking right now is left to it,
  // so concurrent claimers get disjoint items without waiting. The outer
  // condition repeats the test because a row claimed meanwhile is re-checked
  // against it (not against the subquery) before it is updated.
  absl::StatusOr<std::vector<WorkLease>> ClaimPending(const std::string& mission_id,
                                                      const std::string& holder,
                                                      std::chrono::milliseconds ttl,
                                                      int limit) override {
    const std::string claimable = absl::StrCat(
        "requests > done_requests AND (holder IS NULL OR lease_expires_at_ms <= ", kDbNowMs, ")");
    return Query(absl::StrCat("UPDATE mission_work SET holder = $1, token = token + 1, "
                              "claimed_requests = requests, lease_expires_at_ms = ",
                              kDbNowMs,
                              " + $2 WHERE mission_id IN (SELECT mission_id FROM mission_work "
                              "WHERE ($3 = '' OR mission_id = $3) AND ",
                              claimable,
                              " ORDER BY requested_at_ms, mission_id LIMIT $4 "
                              "FOR UPDATE SKIP LOCKED) AND ",
                              claimable, " RETURNING ", kWorkColumns),
                 Params().Text(holder).I8(ttl.count()).Text(mission_id).I8(limit));
  }

  // The mission's row lock orders this with every other request of the
  // mission; FOR UPDATE on the work row keeps sweepers (SKIP LOCKED) off it.
  absl::StatusOr<std::vector<WorkLease>> RequestAndClaimFree(
      const std::string& mission_id, const std::string& reason, const std::string& holder,
      std::chrono::milliseconds ttl) override {
    std::vector<WorkLease> out;
    const absl::Status written = impl_.InTransaction([&](PGconn* conn) -> absl::Status {
      SEAPLAN_ASSIGN_OR_RETURN(const int current, Impl::LockMission(conn, mission_id));
      SEAPLAN_ASSIGN_OR_RETURN(
          Result held,
          Impl::Run(conn,
                    absl::StrCat("SELECT 1 FROM mission_work WHERE mission_id = $1 AND holder IS "
                                 "NOT NULL AND lease_expires_at_ms > ",
                                 kDbNowMs, " FOR UPDATE"),
                    Params().Text(mission_id)));
      if (held.rows() > 0) return absl::OkStatus();  // a live lease: nothing recorded
      SEAPLAN_RETURN_IF_ERROR(
          Impl::RequestWorkLocked(conn, mission_id, {reason, current}).status());
      SEAPLAN_ASSIGN_OR_RETURN(
          Result claimed,
          Impl::Run(conn,
                    absl::StrCat("UPDATE mission_work SET holder = $2, token = token + 1, "
                                 "claimed_requests = requests, lease_expires_at_ms = ",
                                 kDbNowMs, " + $3 WHERE mission_id = $1 RETURNING ", kWorkColumns),
                    Params().Text(mission_id).Text(holder).I8(ttl.count())));
      for (int row = 0; row < claimed.rows(); ++row)
        out.push_back(internal::ReadWork(ResultRow{claimed, row}));
      return absl::OkStatus();
    });
    if (!written.ok()) return written;
    return out;
  }

  absl::StatusOr<std::vector<WorkLease>> UpdateHeld(const WorkLease& lease, LeaseChange change,
                                                    std::chrono::milliseconds ttl) override {
    Params p;
    p.Text(lease.mission_id).Text(lease.holder).I8(lease.token);
    if (change == LeaseChange::kRenew) p.I8(ttl.count());
    return Query(
        absl::StrCat("UPDATE mission_work SET ", SetClause(change, absl::StrCat(kDbNowMs, " + $4")),
                     " WHERE mission_id = $1 AND holder = $2 AND token = $3 RETURNING ",
                     kWorkColumns),
        p);
  }

  Impl& impl_;
};

// ---------------------------------------------------------------------------
class PostgresStore::Access final : public TokenRepository, public AuditRepository {
 public:
  explicit Access(Impl& impl) : impl_(impl) {}

  absl::Status Insert(const TokenRecord& t, const AuditRecord* audit) override {
    return impl_.InTransaction([&](PGconn* conn) -> absl::Status {
      SEAPLAN_RETURN_IF_ERROR(InsertOn(conn, t));
      return Impl::InsertAuditIfAny(conn, audit);
    });
  }

  absl::StatusOr<bool> InsertFirstAdmin(const TokenRecord& admin, TimestampMs now_ms) override {
    bool inserted = false;
    const absl::Status written = impl_.InTransaction([&](PGconn* conn) -> absl::Status {
      // Held to the end of the transaction; under READ COMMITTED the check
      // below then sees an admin token another process committed meanwhile.
      SEAPLAN_RETURN_IF_ERROR(
          Impl::Run(conn, "SELECT pg_advisory_xact_lock($1)", Params().I8(kFirstAdminLockKey))
              .status());
      SEAPLAN_ASSIGN_OR_RETURN(Result usable, Impl::Run(conn, internal::UsableAdminTokenQuery("$1"),
                                                        Params().I8(now_ms)));
      if (usable.rows() > 0) return absl::OkStatus();
      SEAPLAN_RETURN_IF_ERROR(InsertOn(conn, admin));
      inserted = true;
      return absl::OkStatus();
    });
    if (!written.ok()) return written;
    return inserted;
  }

  absl::StatusOr<TokenRecord> Get(const std::string& id) override {
    return impl_.WithConn([&](PGconn* conn) { return GetOn(conn, id); });
  }

  absl::StatusOr<std::vector<TokenRecord>> List() override {
    return impl_.WithConn([&](PGconn* conn) -> absl::StatusOr<std::vector<TokenRecord>> {
      SEAPLAN_ASSIGN_OR_RETURN(Result r,
                               Impl::Run(conn, absl::StrCat("SELECT ", internal::kTokenColumns,
                                                            " FROM api_tokens ORDER BY "
                                                            "created_at_ms, id")));
      std::vector<TokenRecord> out;
      out.reserve(static_cast<std::size_t>(r.rows()));
      for (int row = 0; row < r.rows(); ++row)
        out.push_back(internal::ReadToken(ResultRow{r, row}));
      return out;
    });
  }

  absl::StatusOr<TokenRecord> Revoke(const std::string& id, TimestampMs at_ms,
                                     const AuditRecord* audit) override {
    absl::StatusOr<TokenRecord> revoked = absl::UnknownError("token revocation did not run");
    const absl::Status written = impl_.InTransaction([&](PGconn* conn) -> absl::Status {
      SEAPLAN_RETURN_IF_ERROR(
          Impl::Run(conn,
                    "UPDATE api_tokens SET revoked_at_ms = $2 WHERE id = $1 AND revoked_at_ms = 0",
                    Params().Text(id).I8(at_ms))
              .status());
      revoked = GetOn(conn, id);  // NotFound for an unknown id: nothing is audited
      SEAPLAN_RETURN_IF_ERROR(revoked.status());
      return Impl::InsertAuditIfAny(conn, audit);
    });
    if (!written.ok()) return written;
    return revoked;
  }

  absl::StatusOr<AuditRecord> Append(AuditRecord a) override {
    return impl_.WithConn([&](PGconn* conn) -> absl::StatusOr<AuditRecord> {
      SEAPLAN_ASSIGN_OR_RETURN(a.seq, Impl::InsertAudit(conn, a));
      return a;
    });
  }

  absl::StatusOr<Page<AuditRecord>> ListAudit(int page_size, std::int64_t after) override {
    SEAPLAN_RETURN_IF_ERROR(CheckPageSize(page_size));
    return impl_.WithConn([&](PGconn* conn) -> absl::StatusOr<Page<AuditRecord>> {
      SEAPLAN_ASSIGN_OR_RETURN(
          Result r, Impl::Run(conn,
                              absl::StrCat("SELECT ", internal::kAuditColumns,
                                           " FROM audit_log WHERE seq > $1 ORDER BY seq LIMIT $2"),
                              Params().I8(after).I8(page_size + 1)));
      return Impl::ToPage<AuditRecord>(r, page_size, [](const Result& res, int row) {
        return internal::ReadAudit(ResultRow{res, row});
      });
    });
  }

 private:
  static absl::Status InsertOn(PGconn* conn, const TokenRecord& t) {
    absl::Status st = Impl::Run(conn,
                                absl::StrCat("INSERT INTO api_tokens(", internal::kTokenColumns,
                                             ") VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9)"),
                                Params()
                                    .Text(t.id)
                                    .Text(t.secret_hash)
                                    .Text(t.role)
                                    .Text(t.vessel_id)
                                    .Text(t.description)
                                    .Text(t.created_by)
                                    .I8(t.created_at_ms)
                                    .I8(t.expires_at_ms)
                                    .I8(t.revoked_at_ms))
                          .status();
    if (absl::IsAlreadyExists(st)) {
      return absl::AlreadyExistsError(absl::StrCat("token '", t.id, "' exists"));
    }
    return st;
  }

  static absl::StatusOr<TokenRecord> GetOn(PGconn* conn, const std::string& id) {
    SEAPLAN_ASSIGN_OR_RETURN(Result r, Impl::Run(conn,
                                                 absl::StrCat("SELECT ", internal::kTokenColumns,
                                                              " FROM api_tokens WHERE id = $1"),
                                                 Params().Text(id)));
    if (r.rows() == 0) return absl::NotFoundError(NotFoundMessage("token", id));
    return internal::ReadToken(ResultRow{r, 0});
  }

  Impl& impl_;
};

// ---------------------------------------------------------------------------
absl::Status PostgresOptions::Validate() const {
  if (pool_size < 1 || pool_size > 1000) {
    return absl::InvalidArgumentError(
        absl::StrCat("postgresql pool size must be 1..1000, got ", pool_size));
  }
  if (acquire_timeout.count() < 1 || listener_retry.count() < 1) {
    return absl::InvalidArgumentError("postgresql timeouts must be positive");
  }
  return absl::OkStatus();
}

std::string RedactDatabaseUrl(const std::string& url) {
  // postgresql://user:password@host/...: hide what lies between the first
  // ':' after the scheme and the '@'.
  const std::size_t scheme = url.find("://");
  if (scheme != std::string::npos) {
    const std::size_t at = url.find('@', scheme + 3);
    const std::size_t colon = url.find(':', scheme + 3);
    if (at != std::string::npos && colon != std::string::npos && colon < at) {
      return absl::StrCat(url.substr(0, colon + 1), "***", url.substr(at));
    }
    return url;
  }
  // key=value form: hide the password value.
  const std::size_t pw = url.find("password=");
  if (pw == std::string::npos) return url;
  const std::size_t end = url.find(' ', pw);
  return absl::StrCat(url.substr(0, pw + 9), "***",
                      end == std::string::npos ? "" : url.substr(end));
}

PostgresStore::PostgresStore(std::unique_ptr<Impl> impl)
    : impl_(std::move(impl)),
      work_(std::make_unique<Work>(*impl_)),
      access_(std::make_unique<Access>(*impl_)) {}

PostgresStore::~PostgresStore() {
  (void)Close();
}

absl::StatusOr<std::unique_ptr<PostgresStore>> PostgresStore::Open(const std::string& url,
                                                                   const PostgresOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  auto impl = std::make_unique<Impl>(url, options);
  auto fail = [&](const absl::Status& st) {
    return absl::Status(st.code(),
                        absl::StrCat("database ", RedactDatabaseUrl(url), ": ", st.message()));
  };
  absl::Status st = impl->Migrate();
  if (!st.ok()) return fail(st);
  // Listen only once the schema (and its NOTIFY triggers) exists.
  st = impl->listener.Start();
  if (!st.ok()) return fail(st);
  return std::unique_ptr<PostgresStore>(new PostgresStore(std::move(impl)));
}

ChartRepository& PostgresStore::charts() {
  return *impl_;
}
MissionRepository& PostgresStore::missions() {
  return *impl_;
}
WorkLeaseRepository& PostgresStore::work() {
  return *work_;
}
ChangeFeed& PostgresStore::changes() {
  return impl_->feed;
}
TokenRepository& PostgresStore::tokens() {
  return *access_;
}
AuditRepository& PostgresStore::audit() {
  return *access_;
}

absl::Status PostgresStore::Close() {
  impl_->listener.Stop();
  impl_->pool.Close();
  impl_->feed.Close();
  return absl::OkStatus();
}

absl::StatusOr<int> PostgresStore::SchemaVersion() {
  return impl_->WithConn([&](PGconn* conn) { return impl_->SchemaVersionOn(conn); });
}

}  // namespace seaplan::storage
