// seaplan-charts: the operator CLI in-process with the server's whole core
// (chart engine with GDAL and GEOS, routes, risk, in-memory storage).
// `seaplan` hands chart, route and risk without --server to it.
#include <iostream>
#include <string>

#include "cli.h"
#include "output.h"

int main(int argc, char** argv) {
  using namespace seaplan::cli;
  CliExecutable executable;
  executable.runs = [](const std::string&, const std::string& server) { return server.empty(); };
  executable.make_backend = [](const std::string&, double, const std::string&,
                                const seaplan::client::TlsFiles&) {
    return MakeLocalBackend();
  };
  executable.hand_over = [](const std::string& command, const std::string&, char**) {
    std::cerr << "error: seaplan-charts runs " << command
              << " in-process: without --server, or run seaplan\n";
    return static_cast<int>(kExitBadInput);
  };
  return RunCli(argc, argv, executable);
}
