// The SQLite implementation of the repositories (repositories.h).
//
//   auto store = seaplan::storage::SqliteStore::Open("data/seaplan.db");
//   if (!store.ok()) ...;
//   (*store)->missions().Get(id);
//
// Database set-up: journal_mode=WAL (readers never block the writer),
// synchronous=FULL (a committed write survives a power cut: every write an
// RPC acknowledges is durable), foreign_keys=ON, busy_timeout 5 s.
//
// Schema migrations: the schema version lives in PRAGMA user_version. Open()
// applies every migration in kMigrations (sqlite_store.cc, numbered as the
// PostgreSQL ones) above the file's
// version in order, each in its own transaction together with the bump of
// user_version, so a crash mid-migration leaves the previous version intact.
// A file whose version is newer than this binary knows is refused
// (FailedPrecondition) rather than written to.
//
// Thread-safety: one connection, guarded by a mutex. Every repository call
// holds it for its whole transaction, so calls from any number of threads
// are serialised. Why not one connection per thread: the writes of this
// server are small (a mission, a version, a feedback row), a single writer is
// what SQLite allows anyway, and the one lock keeps read-your-write trivially
// true for the watch streams.
#pragma once

#include <memory>
#include <string>

#include "seaplan/storage/repositories.h"

namespace seaplan::storage {

struct SqliteOptions {
  int busy_timeout_ms = 5000;
  // FULL: fsync at every commit (acknowledged writes survive power loss).
  // NORMAL is faster in WAL mode but may lose the last commits on power loss.
  bool synchronous_full = true;
};

class SqliteStore final : public Store {
 public:
  // Opens (creating if needed) the database at `path` (":memory:" for a
  // private in-memory database) and migrates it to LatestSchemaVersion().
  static absl::StatusOr<std::unique_ptr<SqliteStore>> Open(const std::string& path,
                                                           const SqliteOptions& options = {});

  ~SqliteStore() override;
  SqliteStore(const SqliteStore&) = delete;
  SqliteStore& operator=(const SqliteStore&) = delete;

  ChartRepository& charts() override;
  MissionRepository& missions() override;
  WorkLeaseRepository& work() override;
  // Bumped by this store after each of its commits: one process owns a
  // SQLite database, so no other process has watchers to wake.
  ChangeFeed& changes() override;
  TokenRepository& tokens() override;
  AuditRepository& audit() override;
  absl::Status Close() override;

  // PRAGMA user_version of the open database.
  absl::StatusOr<int> SchemaVersion();
  // PRAGMA integrity_check == "ok" (used by shutdown tests and operators).
  absl::Status CheckIntegrity();

  struct Impl;

 private:
  class Work;
  class Access;
  explicit SqliteStore(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<Work> work_;
  std::unique_ptr<Access> access_;
};

}  // namespace seaplan::storage
