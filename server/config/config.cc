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
                 "planning/route jobs at once; more are refused with RESOURCE_EXHAUSTED")
      ->envname("SEAPLAN_PLANNING_THREADS")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
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
  return parsed;
}

}  // namespace seaplan::server
