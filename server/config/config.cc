#include "server/config/config.h"

#include <CLI/CLI.hpp>
#include <filesystem>
#include <sstream>

namespace seaplan::server {
namespace {

// The console is installed beside the binary (build/bin/console).
std::string DefaultConsoleDir() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return "";
  return (exe.parent_path() / "console").string();
}

}  // namespace

ParsedConfig ParseConfig(int argc, const char* const* argv) {
  ParsedConfig parsed;
  ServerConfig& c = parsed.config;
  CLI::App app{"seaplan-server: mission planning for autonomous ships over gRPC and HTTP/JSON"};
  app.set_version_flag("--version", "seaplan-server 0.1.0");
  std::string log_level = "info";
  int grace_ms = static_cast<int>(c.server.shutdown_grace.count());
  app.add_option("--grpc-addr", c.server.grpc_address,
                 "gRPC listen address host:port (port 0 = any free)")
      ->envname("SEAPLAN_GRPC_ADDR")
      ->capture_default_str();
  app.add_option("--http-addr", c.server.http_address,
                 "HTTP/JSON listen address host:port; empty disables")
      ->envname("SEAPLAN_HTTP_ADDR")
      ->capture_default_str();
  app.add_option("--data-dir", c.data_dir, "folder of the SQLite database (created if missing)")
      ->envname("SEAPLAN_DATA_DIR")
      ->capture_default_str();
  app.add_option("--database", c.database,
                 "postgresql://user:password@host:port/db to store in PostgreSQL (several servers "
                 "may share it); empty: SQLite in --data-dir")
      ->envname("SEAPLAN_DATABASE");
  app.add_option("--worker-threads", c.server.worker_threads,
                 "HTTP worker threads (gRPC thread cap: 4x)")
      ->envname("SEAPLAN_WORKER_THREADS")
      ->check(CLI::Range(1, 1024))
      ->capture_default_str();
  app.add_option("--max-request-bytes", c.server.max_request_bytes,
                 "largest request message accepted")
      ->envname("SEAPLAN_MAX_REQUEST_BYTES")
      ->check(CLI::Range(std::size_t{1024}, std::size_t{(1u << 31) - 1}))
      ->capture_default_str();
  app.add_option("--planning-threads", c.server.core.planning_threads,
                 "planning/route jobs at once; more wait in the planning queue")
      ->envname("SEAPLAN_PLANNING_THREADS")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_option("--planning-queue", c.server.core.planning_queue,
                 "calls waiting for a planning worker (each holds a transport thread); more are "
                 "refused with RESOURCE_EXHAUSTED / 429")
      ->envname("SEAPLAN_PLANNING_QUEUE")
      ->check(CLI::Range(0, 1024))
      ->capture_default_str();
  app.add_option("--rate-limit", c.server.core.rate_limit.calls_per_s,
                 "calls per second per caller (credentials, else address); over it: "
                 "RESOURCE_EXHAUSTED / 429 with a retry-after; 0 = no limit")
      ->envname("SEAPLAN_RATE_LIMIT")
      ->check(CLI::Range(0.0, 1e6))
      ->capture_default_str();
  app.add_option("--rate-burst", c.server.core.rate_limit.burst,
                 "calls a caller may make at once after being idle")
      ->envname("SEAPLAN_RATE_BURST")
      ->check(CLI::Range(1.0, 1e6))
      ->capture_default_str();
  app.add_option("--max-plan-time-s", c.server.core.budgets.max_plan_time_s,
                 "largest planner time limit a request may ask for")
      ->envname("SEAPLAN_MAX_PLAN_TIME_S")
      ->check(CLI::Range(1.0, 86400.0))
      ->capture_default_str();
  app.add_option("--max-plan-memory-mb", c.server.core.budgets.max_plan_memory_mb,
                 "largest planner memory limit a request may ask for")
      ->envname("SEAPLAN_MAX_PLAN_MEMORY_MB")
      ->check(CLI::Range(std::size_t{64}, std::size_t{1} << 20))
      ->capture_default_str();
  app.add_option("--max-route-time-s", c.server.core.budgets.max_route_time_s,
                 "largest route optimizer time limit a request may ask for")
      ->envname("SEAPLAN_MAX_ROUTE_TIME_S")
      ->check(CLI::Range(1.0, 86400.0))
      ->capture_default_str();
  int read_timeout_ms = static_cast<int>(c.server.http_read_timeout.count());
  int write_timeout_ms = static_cast<int>(c.server.http_write_timeout.count());
  int max_body_time_s = static_cast<int>(
      std::chrono::duration_cast<std::chrono::seconds>(c.server.http_max_body_time).count());
  app.add_option("--http-read-timeout-ms", read_timeout_ms,
                 "HTTP: a connection whose client sends nothing for this long, or whose request "
                 "head has not arrived this long after its first byte, is closed")
      ->envname("SEAPLAN_HTTP_READ_TIMEOUT_MS")
      ->check(CLI::Range(100, 600000))
      ->capture_default_str();
  app.add_option("--http-write-timeout-ms", write_timeout_ms,
                 "HTTP: a connection whose client takes nothing for this long is closed")
      ->envname("SEAPLAN_HTTP_WRITE_TIMEOUT_MS")
      ->check(CLI::Range(100, 600000))
      ->capture_default_str();
  app.add_option("--http-min-body-rate", c.server.http_min_body_bytes_per_s,
                 "HTTP: bytes/s a request body must arrive at, on average, after the head "
                 "(slower: the connection is closed)")
      ->envname("SEAPLAN_HTTP_MIN_BODY_RATE")
      ->check(CLI::Range(std::size_t{1}, std::size_t{1} << 30))
      ->capture_default_str();
  app.add_option("--http-max-body-time-s", max_body_time_s,
                 "HTTP: seconds a request body may take in all, after the head (longer: the "
                 "connection is closed), so a large body at the minimum rate cannot hold a "
                 "worker thread for size / rate")
      ->envname("SEAPLAN_HTTP_MAX_BODY_TIME_S")
      ->check(CLI::Range(1, 86400))
      ->capture_default_str();
  app.add_option("--tls-cert", c.server.tls.cert_file,
                 "server certificate chain (PEM): TLS on both the gRPC and the HTTP port")
      ->envname("SEAPLAN_TLS_CERT");
  app.add_option("--tls-key", c.server.tls.key_file, "private key of --tls-cert (PEM)")
      ->envname("SEAPLAN_TLS_KEY");
  app.add_option("--tls-client-ca", c.server.tls.client_ca_file,
                 "CA (PEM) for mutual TLS: clients present a certificate it signed; its subject "
                 "CN names the vessel, which may act only on its own missions")
      ->envname("SEAPLAN_TLS_CLIENT_CA");
  bool client_cert_optional = false;
  app.add_flag("--tls-client-cert-optional", client_cert_optional,
               "with --tls-client-ca: also accept clients without a certificate")
      ->envname("SEAPLAN_TLS_CLIENT_CERT_OPTIONAL");
  app.add_flag("--insecure", c.server.insecure,
               "serve plaintext (no TLS) on a non-loopback address (logs a warning)")
      ->envname("SEAPLAN_INSECURE");
  app.add_option("--log-level", log_level, "debug, info, warn, error or off")
      ->envname("SEAPLAN_LOG_LEVEL")
      ->capture_default_str();
  app.add_option("--port-file", c.port_file,
                 "write \"grpc=PORT\\nhttp=PORT\\n\" here once listening")
      ->envname("SEAPLAN_PORT_FILE");
  c.server.console_dir = DefaultConsoleDir();
  app.add_option("--console-dir", c.server.console_dir,
                 "operator console files served at / (default: console/ beside the binary)")
      ->envname("SEAPLAN_CONSOLE_DIR")
      ->capture_default_str();
  app.add_option("--admin-token-file", c.admin_token_file,
                 "file holding an admin token to accept (created elsewhere, e.g. by a "
                 "deployment's secret store); without it the first start writes one to "
                 "<data-dir>/admin.token")
      ->envname("SEAPLAN_ADMIN_TOKEN_FILE");
  app.add_option("--shutdown-grace-ms", grace_ms,
                 "time running requests get on SIGTERM before cancellation")
      ->envname("SEAPLAN_SHUTDOWN_GRACE_MS")
      ->check(CLI::Range(0, 600000))
      ->capture_default_str();
  int lease_ms = static_cast<int>(c.server.core.missions.lease_ttl.count());
  int sweep_ms = static_cast<int>(c.server.core.missions.sweep_interval.count());
  app.add_option("--lease-ms", lease_ms,
                 "replicas (--database postgresql://): the work lease on a mission's replan, "
                 "renewed every third of it; a dead replica's work waits for its expiry")
      ->envname("SEAPLAN_LEASE_MS")
      ->check(CLI::Range(100, 3600000))
      ->capture_default_str();
  app.add_option("--sweep-ms", sweep_ms,
                 "replicas: how often an idle replica looks for work nobody holds (shorter "
                 "than --lease-ms)")
      ->envname("SEAPLAN_SWEEP_MS")
      ->check(CLI::Range(10, 3600000))
      ->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::ostringstream out, err;
    parsed.exit = true;
    parsed.exit_code = app.exit(e, out, err);
    parsed.message = out.str() + err.str();
    return parsed;
  }
  if (!log::ParseLevel(log_level, &c.log_level)) {
    parsed.exit = true;
    parsed.exit_code = 2;
    parsed.message =
        "--log-level: unknown level '" + log_level + "' (debug, info, warn, error, off)\n";
    return parsed;
  }
  c.server.shutdown_grace = std::chrono::milliseconds(grace_ms);
  c.server.core.missions.lease_ttl = std::chrono::milliseconds(lease_ms);
  c.server.core.missions.sweep_interval = std::chrono::milliseconds(sweep_ms);
  if (absl::Status st = c.server.core.missions.Validate(); !st.ok()) {
    parsed.exit = true;
    parsed.exit_code = 2;
    parsed.message = "--lease-ms / --sweep-ms: " + std::string(st.message()) + "\n";
    return parsed;
  }
  c.server.http_read_timeout = std::chrono::milliseconds(read_timeout_ms);
  c.server.http_write_timeout = std::chrono::milliseconds(write_timeout_ms);
  c.server.http_max_body_time = std::chrono::seconds(max_body_time_s);
  c.server.tls.require_client_cert = !client_cert_optional;
  if (c.server.tls.cert_file.empty() != c.server.tls.key_file.empty() ||
      (!c.server.tls.client_ca_file.empty() && c.server.tls.cert_file.empty())) {
    parsed.exit = true;
    parsed.exit_code = 2;
    parsed.message = "--tls-cert and --tls-key go together; --tls-client-ca needs both\n";
    return parsed;
  }
  return parsed;
}

}  // namespace seaplan::server
