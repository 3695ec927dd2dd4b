// seaplan: the operator CLI. Runs plan and validate in-process with only the
// planning engine linked, so that they start in milliseconds: resolving the
// symbols of gRPC, GDAL and their ~150 shared libraries took 0.1 s of every
// call. Commands against a server are handed to seaplan-remote, chart, route
// and risk in-process to seaplan-charts (both installed beside this file).
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>

#include "cli.h"
#include "output.h"

namespace seaplan::cli {
namespace {

bool RunsHere(const std::string& command, const std::string& server) {
  return server.empty() &&
         (command == "plan" || command == "validate" || command.rfind("mission ", 0) == 0);
}

// Replaces this process with the sibling executable that runs `command`.
int HandOver(const std::string& command, const std::string& server, char** argv) {
  const char* name = server.empty() ? "seaplan-charts" : "seaplan-remote";
  std::error_code error;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", error);
  const auto path = (error ? std::filesystem::path(argv[0]) : self).parent_path() / name;
  ::execv(path.c_str(), argv);
  std::cerr << "error: " << command << " runs in " << path.string() << ", which cannot be started ("
            << std::strerror(errno) << ")\n";
  return kExitServiceError;
}

}  // namespace
}  // namespace seaplan::cli

int main(int argc, char** argv) {
  using namespace seaplan::cli;
  CliExecutable executable;
  executable.runs = RunsHere;
  executable.make_backend = [](const std::string&, double, const std::string&,
                               const seaplan::client::TlsFiles&) { return MakePlanningBackend(); };
  executable.hand_over = HandOver;
  return RunCli(argc, argv, executable);
}
