// seaplan-remote: the operator CLI against a server (gRPC client). `seaplan`
// hands every command given --server (or SEAPLAN_SERVER) to it.
#include <iostream>
#include <string>

#include "cli.h"
#include "output.h"

int main(int argc, char** argv) {
  using namespace seaplan::cli;
  CliExecutable executable;
  executable.runs = [](const std::string&, const std::string& server) { return !server.empty(); };
  executable.make_backend = MakeRemoteBackend;
  executable.hand_over = [](const std::string& command, const std::string&, char**) {
    std::cerr << "error: seaplan-remote runs " << command
              << " against a server: give --server HOST:PORT, or run seaplan\n";
    return static_cast<int>(kExitBadInput);
  };
  return RunCli(argc, argv, executable);
}
