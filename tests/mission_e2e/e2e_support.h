// Helpers of the mission end-to-end tests: the real seaplan-server on a
// loopback ephemeral port with a fresh database, the real seaplan-sim as a
// child process with a wall-clock limit, and the few report.json fields the
// tests read, for mission_e2e_test.cc and trondheim_e2e_test.cc.
// Header-only: each test binary includes it once. Not thread-safe
// (processes and files are per test).
#pragma once

#include <fcntl.h>
#include <grpcpp/grpcpp.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "seaplan/testing/child_process.h"
#include "seaplan/testing/grpc_test_token.h"
#include "seaplan/v1/mission.grpc.pb.h"

namespace seaplan::e2e {

namespace fs = std::filesystem;

inline std::string ReadWholeFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// seaplan-server on 127.0.0.1 (HTTP off unless `extra_args` sets
// --http-addr), database and port file in the folder given to Start, on an
// ephemeral port or the given one (a restart on the port of a killed
// server); `extra_args` are appended (e.g. --database URL). SIGTERM and
// reaped on destruction.
// It accepts the fixtures' admin token (seaplan/testing/test_token.h),
// which this process's gRPC calls and the clients it starts present by
// default (UseTestAdminTokenByDefault).
class ServerProcess {
 public:
  ServerProcess() = default;
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;
  ~ServerProcess() { Stop(); }

  // False when the binary does not start or never reports its port (15 s).
  bool Start(const fs::path& server_bin, const fs::path& dir, int port = 0,
             const std::vector<std::string>& extra_args = {}) {
    fs::create_directories(dir);
    const fs::path port_file = dir / "ports";
    fs::remove(port_file);
    seaplan::testing::UseTestAdminTokenByDefault();
    const std::string token_file =
        seaplan::testing::WriteTestAdminTokenFile(dir / "admin-token").string();
    const std::string bin = server_bin.string(), data = (dir / "data").string(),
                      ports = port_file.string(), log = (dir / "server.log").string(),
                      grpc_addr = "127.0.0.1:" + std::to_string(port);
    port_ = http_port_ = 0;
    // Defaults, each left out when `extra_args` gives the flag itself.
    const std::pair<std::string, std::string> defaults[] = {{"--http-addr", ""},
                                                            {"--log-level", "warn"}};
    std::vector<std::string> argv = {bin,       "--grpc-addr", grpc_addr, "--data-dir",
                                     data,      "--port-file", ports,     "--admin-token-file",
                                     token_file};
    const auto given = [&](const std::string& flag) {
      return std::find(extra_args.begin(), extra_args.end(), flag) != extra_args.end();
    };
    for (const auto& [flag, value] : defaults) {
      if (!given(flag)) argv.insert(argv.end(), {flag, value});
    }
    const bool http = given("--http-addr");
    argv.insert(argv.end(), extra_args.begin(), extra_args.end());
    std::vector<char*> args;
    args.reserve(argv.size() + 1);
    for (std::string& a : argv) args.push_back(a.data());
    args.push_back(nullptr);
    pid_ = fork();
    if (pid_ == 0) {
      int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);  // restarts append
      if (fd >= 0) {
        dup2(fd, STDOUT_FILENO);
        dup2(fd, STDERR_FILENO);
      }
      execv(args[0], args.data());
      _exit(127);
    }
    if (pid_ < 0) return false;
    const auto listening = [&] {
      std::ifstream in(port_file);
      std::string line;
      while (std::getline(in, line)) {
        if (line.rfind("http=", 0) == 0) http_port_ = std::stoi(line.substr(5));
        if (line.rfind("grpc=", 0) == 0) {
          port_ = std::stoi(line.substr(5));
          address_ = "127.0.0.1:" + line.substr(5);
        }
      }
      return port_ != 0 && (!http || http_port_ != 0);
    };
    const auto readiness =
        seaplan::testing::WaitUntilChildReady(pid_, std::chrono::seconds(15), listening);
    if (readiness == seaplan::testing::ChildReadiness::kExited) pid_ = -1;
    return readiness == seaplan::testing::ChildReadiness::kReady;
  }
  void Stop() { SignalAndReap(SIGTERM); }
  // SIGKILL: no shutdown, no flush, as in a crash or an OOM kill.
  void Kill() { SignalAndReap(SIGKILL); }
  const std::string& address() const { return address_; }
  int port() const { return port_; }
  int http_port() const { return http_port_; }  // 0 when HTTP is off
  pid_t pid() const { return pid_; }

 private:
  void SignalAndReap(int signal) {
    if (pid_ > 0) {
      kill(pid_, signal);
      int status = 0;
      waitpid(pid_, &status, 0);
      pid_ = -1;
    }
  }

  pid_t pid_ = -1;
  int port_ = 0;
  int http_port_ = 0;
  std::string address_;
};

// The sim's feedback journal: every report written ("R <seq> ...") and
// every acknowledgement ("A <seq>").
struct JournalView {
  std::vector<int64_t> reported;
  std::set<int64_t> acknowledged;
};
inline JournalView ReadJournal(const fs::path& path) {
  JournalView j;
  std::istringstream in(ReadWholeFile(path));
  std::string tag;
  int64_t seq = 0;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream l(line);
    if (!(l >> tag >> seq)) continue;
    if (tag == "R") j.reported.push_back(seq);
    if (tag == "A") j.acknowledged.insert(seq);
  }
  return j;
}

struct ProcessResult {
  int exit_code = -1;      // -1: killed by a signal or did not start
  bool timed_out = false;  // killed after the wall-clock limit
  std::string output;      // stdout + stderr
};

// Starts `argv` (argv[0] is the binary path) with extra environment
// variables, stdout + stderr into `output_file`; the child's pid (-1 when
// fork fails).
inline pid_t StartProcess(const std::vector<std::string>& argv,
                          const std::vector<std::pair<std::string, std::string>>& env,
                          const fs::path& output_file) {
  std::vector<char*> args;
  args.reserve(argv.size() + 1);
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const std::string out = output_file.string();
  pid_t pid = fork();
  if (pid == 0) {
    for (const auto& [k, v] : env) setenv(k.c_str(), v.c_str(), 1);
    int fd = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, STDOUT_FILENO);
      dup2(fd, STDERR_FILENO);
    }
    execv(args[0], args.data());
    _exit(127);
  }
  return pid;
}

// Waits for a child of StartProcess; SIGKILL after `limit`.
inline ProcessResult WaitProcess(pid_t pid, const fs::path& output_file,
                                 std::chrono::seconds limit) {
  ProcessResult r;
  if (pid < 0) return r;
  const auto deadline = std::chrono::steady_clock::now() + limit;
  int status = 0;
  while (true) {
    pid_t w = waitpid(pid, &status, WNOHANG);
    if (w == pid) break;
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      r.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  if (!r.timed_out && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.output = ReadWholeFile(output_file);
  return r;
}

// StartProcess + WaitProcess.
inline ProcessResult RunProcess(const std::vector<std::string>& argv,
                                const std::vector<std::pair<std::string, std::string>>& env,
                                const fs::path& output_file, std::chrono::seconds limit) {
  return WaitProcess(StartProcess(argv, env, output_file), output_file, limit);
}

// report.json readers. The sim writes the report itself with a fixed layout
// ("key": value, one space), so a regex per key is enough for these tests.
inline std::vector<double> Numbers(const std::string& text, const std::string& key) {
  std::vector<double> out;
  std::regex re("\"" + key + "\": (-?[0-9.eE+-]+)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator();
       ++it) {
    out.push_back(std::stod((*it)[1]));
  }
  return out;
}
inline std::vector<std::string> Strings(const std::string& text, const std::string& key) {
  std::vector<std::string> out;
  std::regex re("\"" + key + "\": \"([^\"]*)\"");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator();
       ++it) {
    out.push_back((*it)[1]);
  }
  return out;
}
inline bool Flag(const std::string& text, const std::string& key) {
  return text.find("\"" + key + "\": true") != std::string::npos;
}

// One executed-track sample: mission time, local frame east/north (metres).
struct TrackPoint {
  double time_s = 0.0, east_m = 0.0, north_m = 0.0;
};
// The "trajectory" array ([t, x, y] triples, the report's last array).
inline std::vector<TrackPoint> Trajectory(const std::string& report) {
  std::vector<TrackPoint> out;
  const size_t at = report.find("\"trajectory\"");
  if (at == std::string::npos) return out;
  const std::string traj = report.substr(at);
  std::regex pt("\\[(-?[0-9.eE+-]+), (-?[0-9.eE+-]+), (-?[0-9.eE+-]+)\\]");
  for (auto it = std::sregex_iterator(traj.begin(), traj.end(), pt); it != std::sregex_iterator();
       ++it) {
    out.push_back({std::stod((*it)[1]), std::stod((*it)[2]), std::stod((*it)[3])});
  }
  return out;
}

// A refined move of a plan version: task id, action and route waypoints
// (local frame, metres).
struct RoutedMove {
  std::string id, action;
  std::vector<std::pair<double, double>> waypoints;
};
// Every task with a "route" in the report (all plan versions).
inline std::vector<RoutedMove> RoutedMoves(const std::string& report) {
  std::vector<RoutedMove> out;
  std::regex task(
      "\\{\"id\": \"([^\"]*)\", \"kind\": \"[^\"]*\", \"action\": \"([^\"]*)\"[^\\[\\}]*\"route\": "
      "\\[");
  std::regex wp("^\\[(-?[0-9.eE+-]+), (-?[0-9.eE+-]+), \"[^\"]*\"\\](, )?");
  for (auto it = std::sregex_iterator(report.begin(), report.end(), task);
       it != std::sregex_iterator(); ++it) {
    RoutedMove m{(*it)[1], (*it)[2], {}};
    std::string rest = report.substr(static_cast<size_t>(it->position() + it->length()));
    std::smatch w;
    while (std::regex_search(rest, w, wp)) {
      m.waypoints.emplace_back(std::stod(w[1]), std::stod(w[2]));
      rest = w.suffix();
    }
    out.push_back(std::move(m));
  }
  return out;
}

// "location = name lat lon" lines of a scenario file, in order.
struct ScenarioLocation {
  std::string name;
  double lat_deg = 0.0, lon_deg = 0.0;
};
inline std::vector<ScenarioLocation> ScenarioLocations(const std::string& scenario_text) {
  std::vector<ScenarioLocation> out;
  std::regex re("(^|\\n)\\s*location\\s*=\\s*(\\S+)\\s+(-?[0-9.]+)\\s+(-?[0-9.]+)");
  for (auto it = std::sregex_iterator(scenario_text.begin(), scenario_text.end(), re);
       it != std::sregex_iterator(); ++it) {
    out.push_back({(*it)[2], std::stod((*it)[3]), std::stod((*it)[4])});
  }
  return out;
}
// Names of the "traffic = name kind ..." lines of a scenario file.
inline std::vector<std::string> ScenarioTraffic(const std::string& scenario_text) {
  std::vector<std::string> out;
  std::regex re("(^|\\n)\\s*traffic\\s*=\\s*(\\S+)");
  for (auto it = std::sregex_iterator(scenario_text.begin(), scenario_text.end(), re);
       it != std::sregex_iterator(); ++it) {
    out.push_back((*it)[2]);
  }
  return out;
}

}  // namespace seaplan::e2e
