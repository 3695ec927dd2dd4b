// The operator CLI's command tree, shared by the three executables that run
// it: `seaplan` (plan and validate in-process: links only the planning
// engine), `seaplan-remote` (every command against a server: links the gRPC
// client) and `seaplan-charts` (chart, route and risk in-process: links the
// chart engine, GDAL and GEOS). Each parses the whole command line, so usage
// errors, --help and exit codes are the same whichever runs; a command the
// executable does not link a backend for is handed over to the one that does.
//
// Exit codes: 0 success, 1 no plan / plan invalid, 2 bad input or usage,
// 3 the server is unreachable or failed.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "backend.h"
#include "tls_channel.h"

namespace seaplan::cli {

struct CliExecutable {
  // Whether this executable runs `command` ("plan", "chart upload", ...)
  // against `server` (empty: in-process).
  std::function<bool(const std::string& command, const std::string& server)> runs;
  // The backend of a command it runs (`timeout_s` <= 0: no deadline;
  // `token`: the API token a server backend presents; `tls` checked with
  // client::CheckTlsFiles).
  std::function<std::unique_ptr<Backend>(const std::string& server, double timeout_s,
                                         const std::string& token,
                                         const client::TlsFiles& tls)>
      make_backend;
  // Runs the whole command line `argv` in the executable that runs
  // `command`; returns an exit code only when that cannot be done.
  std::function<int(const std::string& command, const std::string& server, char** argv)> hand_over;
};

int RunCli(int argc, char** argv, const CliExecutable& executable);

}  // namespace seaplan::cli
