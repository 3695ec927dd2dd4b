// The PostgreSQL implementation of the repositories (repositories.h), for
// several server processes sharing one database.
//
//   auto store = seaplan::storage::PostgresStore::Open("postgresql://seaplan@db/seaplan");
//   if (!store.ok()) ...;
//   (*store)->missions().Get(id);
//
// Connections: a pool of up to PostgresOptions::pool_size libpq connections
// (one per call in flight; a libpq connection serves one thread at a time),
// opened on demand and reopened after a failure. A call that finds the
// server gone answers Unavailable; when the connection is lost during a
// COMMIT the outcome is unknown and the call answers Unavailable too (the
// client retries; feedback is idempotent).
//
// Durability: every write commits before the call returns OK, with
// synchronous_commit at least "on" (a session whose server default is "off"
// or "local" is raised to "on"): acknowledged writes are flushed to the WAL.
//
// Several processes: every write to a mission first locks its row
// (SELECT ... FOR UPDATE), so plan versions and log event ids are numbered
// without gap or duplicate whichever process writes; unique constraints keep
// feedback single per (vessel, sequence) and ids unique. Work items are
// claimed with FOR UPDATE SKIP LOCKED; lease expiry uses the database clock.
//
// Change feed: triggers on missions, plan_versions, feedback and log_events
// send NOTIFY seaplan_mission_changes with the mission id (delivered at
// commit); a listener thread on its own connection LISTENs and bumps the
// in-process generations. When the listener loses its connection it
// reconnects and bumps every generation, because notifications sent
// meanwhile are lost.
//
// Schema migrations: the version lives in the one-row table seaplan_schema.
// Open() applies the missing migrations (numbered as the SQLite ones), each in
// its own transaction under an advisory lock, so replicas starting together
// migrate once. A database newer than this binary is refused
// (FailedPrecondition).
//
// Thread-safety: every method may be called from any thread.
#pragma once

#include <chrono>
#include <memory>
#include <string>

#include "seaplan/storage/repositories.h"

namespace seaplan::storage {

struct PostgresOptions {
  // Connections at most (calls beyond wait for one). Each watcher polls
  // briefly, so a handful serve many calls; PostgreSQL's own limit
  // (max_connections, 100 by default) is shared by every replica.
  int pool_size = 8;
  // How long a call waits for a free connection before Unavailable.
  std::chrono::milliseconds acquire_timeout{10000};
  // Wait between reconnection attempts of the change listener.
  std::chrono::milliseconds listener_retry{500};

  absl::Status Validate() const;
};

class PostgresStore final : public Store {
 public:
  // Connects to `url` (a libpq connection URI, postgresql://user:password@
  // host:port/database?options, or a key=value string) and migrates the
  // database to LatestSchemaVersion().
  static absl::StatusOr<std::unique_ptr<PostgresStore>> Open(const std::string& url,
                                                             const PostgresOptions& options = {});

  ~PostgresStore() override;
  PostgresStore(const PostgresStore&) = delete;
  PostgresStore& operator=(const PostgresStore&) = delete;

  ChartRepository& charts() override;
  MissionRepository& missions() override;
  WorkLeaseRepository& work() override;
  ChangeFeed& changes() override;
  TokenRepository& tokens() override;
  AuditRepository& audit() override;
  absl::Status Close() override;

  // The version in seaplan_schema.
  absl::StatusOr<int> SchemaVersion();

  struct Impl;

 private:
  class Work;
  class Access;
  explicit PostgresStore(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  std::unique_ptr<Work> work_;
  std::unique_ptr<Access> access_;
};

// `url` with its password replaced by "***", for logs.
std::string RedactDatabaseUrl(const std::string& url);

}  // namespace seaplan::storage
