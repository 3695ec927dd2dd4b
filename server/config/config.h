// Every setting of seaplan-server in one place: command-line flags, with
// environment variables as fallbacks (a flag given wins over its variable,
// the variable over the default). Only main() calls ParseConfig; the rest of
// the server gets plain option structs.
//
//   flag                   env                         default
//   --grpc-addr            SEAPLAN_GRPC_ADDR           127.0.0.1:50051
//   --http-addr            SEAPLAN_HTTP_ADDR           127.0.0.1:8080 ("" disables HTTP)
//   --data-dir             SEAPLAN_DATA_DIR            ./data   (database: <dir>/seaplan.db)
//   --database             SEAPLAN_DATABASE            none     (postgresql://...: PostgreSQL
//   instead of SQLite in --data-dir)
//   --worker-threads       SEAPLAN_WORKER_THREADS      16
//   --max-request-bytes    SEAPLAN_MAX_REQUEST_BYTES   67108864 (64 MiB: charts)
//   --planning-threads     SEAPLAN_PLANNING_THREADS    2        (pool size; more wait)
//   --planning-queue       SEAPLAN_PLANNING_QUEUE      12       (calls waiting for a worker;
//   more -> RESOURCE_EXHAUSTED)
//   --rate-limit           SEAPLAN_RATE_LIMIT          100      (calls/s per caller; 0 = off)
//   --rate-burst           SEAPLAN_RATE_BURST          200      (calls at once per caller)
//   --max-plan-time-s      SEAPLAN_MAX_PLAN_TIME_S     600      (a request's planner time limit)
//   --max-plan-memory-mb   SEAPLAN_MAX_PLAN_MEMORY_MB  8192     (its memory limit)
//   --max-route-time-s     SEAPLAN_MAX_ROUTE_TIME_S    300      (a route's optimizer time limit)
//   --http-read-timeout-ms SEAPLAN_HTTP_READ_TIMEOUT_MS  10000  (idle read closes a connection)
//   --http-write-timeout-ms SEAPLAN_HTTP_WRITE_TIMEOUT_MS 10000
//   --tls-cert             SEAPLAN_TLS_CERT            none     (PEM chain: TLS on both ports)
//   --tls-key              SEAPLAN_TLS_KEY             none     (PEM private key)
//   --tls-client-ca        SEAPLAN_TLS_CLIENT_CA       none     (PEM: mutual TLS; cert CN =
//   vessel id)
//   --tls-client-cert-optional SEAPLAN_TLS_CLIENT_CERT_OPTIONAL off (with a client CA: accept
//   clients without a certificate)
//   --insecure             SEAPLAN_INSECURE            off      (plaintext on a non-loopback
//   address)
//   --log-level            SEAPLAN_LOG_LEVEL           info     (debug, info, warn, error, off)
//   --port-file            SEAPLAN_PORT_FILE           none     (writes "grpc=P\nhttp=P\n" once
//   listening)
//   --console-dir          SEAPLAN_CONSOLE_DIR         <binary's folder>/console
//   --shutdown-grace-ms    SEAPLAN_SHUTDOWN_GRACE_MS   2000
//   --lease-ms             SEAPLAN_LEASE_MS            5000     (replicas: work lease on a replan,
//   renewed every third of it; 100..3600000)
//   --sweep-ms             SEAPLAN_SWEEP_MS            2500     (replicas: idle look for work
//   nobody holds; 10.., shorter than --lease-ms)
//   --admin-token-file     SEAPLAN_ADMIN_TOKEN_FILE    none     (an admin token to accept;
//   without it the first start writes a new one to <data-dir>/admin.token, mode 0600)
//
// Port 0 in an address picks a free port; the bound ports are logged and
// written to the port file.
#pragma once

#include <string>
#include <vector>

#include "seaplan/common/log.h"
#include "seaplan/common/status.h"
#include "server/server.h"

namespace seaplan::server {

struct ServerConfig {
  ServerOptions server;
  std::string data_dir = "./data";
  // Empty: SQLite in data_dir. postgresql://...: that PostgreSQL database
  // (several servers may share it).
  std::string database;
  std::string port_file;
  // An admin token to store (if new) and accept; empty: the first start
  // creates one in data_dir/admin.token.
  std::string admin_token_file;
  log::Level log_level = log::Level::kInfo;
};

struct ParsedConfig {
  ServerConfig config;
  // Set when main should exit at once (--help, --version, or a bad flag)
  // with this code after printing `message`.
  bool exit = false;
  int exit_code = 0;
  std::string message;
};

ParsedConfig ParseConfig(int argc, const char* const* argv);

}  // namespace seaplan::server
