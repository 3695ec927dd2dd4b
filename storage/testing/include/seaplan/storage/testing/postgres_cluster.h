// A throwaway PostgreSQL cluster for tests and benchmarks: initdb + pg_ctl
// in a temporary folder, listening on a free loopback port, trust
// authentication for the superuser "seaplan", removed again at the end.
//
// Binaries: $SEAPLAN_PG_BINDIR, else the newest /usr/lib/postgresql/*/bin
// (Debian's postgresql package). Start() answers NotFound when there is
// none, so a caller can tell "not installed" from "failed to start".
//
// Root: initdb and postgres refuse to run as root, so when this process is
// root the cluster runs as an unprivileged account ($SEAPLAN_PG_USER, else
// "postgres", which Debian's package creates, else "nobody") through
// runuser, and its folder is handed to that account.
//
// Stopping even on failure: Start() also spawns a guardian process in its own
// session that waits on a pipe from this process. The pipe closes when this
// process ends in any way (return, abort, SIGKILL), and the guardian then
// stops the server ("immediate" mode) and removes the folder. Stop() does
// the same at once and waits for it.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <string>

#include "seaplan/common/status.h"

namespace seaplan::storage::testing {

struct PostgresClusterOptions {
  // Flush the WAL at commit like a production server. Off in tests (they
  // check semantics, not power loss, and fsync is slow on a shared machine);
  // on in benchmarks that compare durable commits.
  bool fsync = false;
  int max_connections = 200;
  std::chrono::seconds start_timeout{120};
};

class TemporaryPostgresCluster {
 public:
  static absl::StatusOr<std::unique_ptr<TemporaryPostgresCluster>> Start(
      const PostgresClusterOptions& options = {});
  ~TemporaryPostgresCluster();  // Stop()
  TemporaryPostgresCluster(const TemporaryPostgresCluster&) = delete;
  TemporaryPostgresCluster& operator=(const TemporaryPostgresCluster&) = delete;

  // Stops the server and removes the folder; idempotent.
  absl::Status Stop();

  int port() const { return port_; }
  const std::filesystem::path& folder() const { return folder_; }
  // postgresql://seaplan@127.0.0.1:<port>/<database>
  std::string Url(const std::string& database = "postgres") const;
  // Creates a fresh, empty database and returns its URL.
  absl::StatusOr<std::string> CreateDatabase();
  // Runs SQL (several statements allowed) on a database as the superuser.
  absl::Status Execute(const std::string& url, const std::string& sql) const;
  // The first column of the first row of a query, as text.
  absl::StatusOr<std::string> QueryValue(const std::string& url, const std::string& sql) const;

 private:
  TemporaryPostgresCluster() = default;
  std::filesystem::path folder_;
  std::filesystem::path bindir_;
  std::string run_as_;  // empty: this process's own user
  int port_ = 0;
  int guardian_pipe_ = -1;
  pid_t guardian_ = -1;
  int databases_created_ = 0;
};

// A free TCP port on 127.0.0.1 (free when this returns; the caller binds
// it next). 0 when none could be found.
int FreeLoopbackPort();

// One cluster shared by every test of this process, started on first use
// and stopped at exit (or by its guardian). NotFound when PostgreSQL is not
// installed; the reason in the status is meant to be printed.
absl::StatusOr<TemporaryPostgresCluster*> ProcessCluster();

}  // namespace seaplan::storage::testing
