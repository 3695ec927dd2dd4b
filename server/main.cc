// seaplan-server: reads the configuration (flags, env), opens the database,
// serves gRPC and HTTP/JSON until SIGTERM or SIGINT, then drains and exits 0.
#include <signal.h>

#include <cstdio>
#include <string>

#include "absl/strings/str_cat.h"
#include "seaplan/common/file_replace.h"
#include "seaplan/common/log.h"
#include "seaplan/storage/open_store.h"
#include "server/auth/bootstrap.h"
#include "server/config/config.h"
#include "server/server.h"

int main(int argc, char** argv) {
  using namespace seaplan;
  // Block the stop signals in every thread (the ones gRPC and httplib start
  // inherit the mask); the main thread takes them with sigwait.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGTERM);
  sigaddset(&stop_signals, SIGINT);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  signal(SIGPIPE, SIG_IGN);  // a client that hangs up must not kill the server

  server::ParsedConfig parsed = server::ParseConfig(argc, argv);
  if (parsed.exit) {
    std::fputs(parsed.message.c_str(), parsed.exit_code == 0 ? stdout : stderr);
    return parsed.exit_code;
  }
  const server::ServerConfig& config = parsed.config;
  log::SetLevel(config.log_level);

  auto opened = storage::OpenStore(config.database, config.data_dir);
  if (!opened.ok()) {
    log::Error("{}", opened.status().ToString());
    return 1;
  }
  auto store = std::move(opened->store);
  log::Info("database {} (schema version {})", opened->description, storage::LatestSchemaVersion());

  {
    const server::auth::Authenticator auth(store->tokens());
    auto admin = server::auth::EnsureAdminToken(auth, store->tokens(), config.admin_token_file,
                                                config.data_dir);
    if (!admin.ok()) {
      log::Error("admin token: {}", admin.status().ToString());
      return 1;
    }
    if (!admin->created_bearer.empty()) {
      // Shown once; the file keeps it for scripts on this machine.
      std::printf(
          "seaplan-server: first start: created the admin token (also in %s, mode 0600):\n%s\n",
          admin->created_file.c_str(), admin->created_bearer.c_str());
      std::fflush(stdout);
    }
  }

  auto server = server::Server::Start(config.server, *store);
  if (!server.ok()) {
    log::Error("cannot start: {}", server.status().ToString());
    return 1;
  }
  if (!config.port_file.empty()) {
    const absl::Status written = ReplaceFile(
        config.port_file,
        absl::StrCat("grpc=", (*server)->grpc_port(), "\nhttp=", (*server)->http_port(), "\n"));
    if (!written.ok()) {
      log::Error("cannot write port file: {}", std::string(written.message()));
      return 1;
    }
  }

  int signal_number = 0;
  sigwait(&stop_signals, &signal_number);
  log::Info("received signal {}", signal_number);
  (*server)->Shutdown();
  server->reset();
  absl::Status closed = store->Close();
  if (!closed.ok()) {
    log::Error("closing the database: {}", closed.ToString());
    return 1;
  }
  log::Info("database closed; bye");
  return 0;
}
