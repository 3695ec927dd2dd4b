// nginx in front of seaplan-server replicas for tests and benchmarks: the
// repository's deploy/nginx.conf with the replicas' loopback addresses, two
// free loopback ports and a folder of its own (pid file, logs, temporary
// files) substituted, run in the foreground as a child of this process
// (stopped with it). Header-only; not thread-safe.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "e2e_support.h"
#include "seaplan/storage/testing/postgres_cluster.h"
#include "seaplan/testing/child_process.h"

namespace seaplan::ha {

namespace fs = std::filesystem;

inline bool Accepts(int port) {
  int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = htons(static_cast<uint16_t>(port));
  const bool ok = connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0;
  close(fd);
  return ok;
}

// $SEAPLAN_NGINX, else Debian's /usr/sbin/nginx; empty when there is none.
inline fs::path FindNginx() {
  if (const char* env = std::getenv("SEAPLAN_NGINX")) return env;
  for (const char* p : {"/usr/sbin/nginx", "/usr/bin/nginx", "/usr/local/sbin/nginx"}) {
    if (access(p, X_OK) == 0) return p;
  }
  return {};
}

// A replica's loopback ports.
struct ReplicaPorts {
  int grpc = 0;
  int http = 0;
};

// deploy/nginx.conf (`conf`) for replicas on loopback: the first
// `replicas.size()` of its replicaN lines point at them, later ones are
// dropped; it listens on 127.0.0.1 and keeps its files in `dir`.
inline std::string NginxConfigFor(std::string conf, const std::vector<ReplicaPorts>& replicas,
                                  int grpc_port, int http_port, const fs::path& dir) {
  for (int n = 1; n <= 9; ++n) {
    const std::string name = "replica" + std::to_string(n);
    if (n <= static_cast<int>(replicas.size())) {
      conf = std::regex_replace(conf, std::regex(absl::StrCat(name, ":50051")),
                                absl::StrCat("127.0.0.1:", replicas[n - 1].grpc));
      conf = std::regex_replace(conf, std::regex(absl::StrCat(name, ":8080")),
                                absl::StrCat("127.0.0.1:", replicas[n - 1].http));
    } else {
      conf = std::regex_replace(
          conf, std::regex(absl::StrCat("[^\\n]*server ", name, ":[^\\n]*\\n")), "");
    }
  }
  conf = std::regex_replace(conf, std::regex("listen 50051"),
                            "listen 127.0.0.1:" + std::to_string(grpc_port));
  conf = std::regex_replace(conf, std::regex("listen 8080"),
                            "listen 127.0.0.1:" + std::to_string(http_port));
  const std::string d = dir.string();  // may itself be under /tmp: replaced first
  conf = std::regex_replace(conf, std::regex("/tmp/"), d + "/");
  conf = std::regex_replace(conf, std::regex("/dev/stderr"), d + "/nginx-error.log");
  conf = std::regex_replace(conf, std::regex("/dev/stdout"), d + "/nginx-access.log");
  return conf;
}

class NginxBalancer {
 public:
  NginxBalancer() = default;
  NginxBalancer(const NginxBalancer&) = delete;
  NginxBalancer& operator=(const NginxBalancer&) = delete;
  ~NginxBalancer() { Stop(); }

  // Writes `dir`/nginx.conf from `repo_conf` and starts nginx; false (see
  // log()) when it does not listen within 30 s.
  bool Start(const fs::path& nginx, const fs::path& repo_conf,
             const std::vector<ReplicaPorts>& replicas, const fs::path& dir) {
    dir_ = dir;
    fs::create_directories(dir);
    grpc_port_ = storage::testing::FreeLoopbackPort();
    http_port_ = storage::testing::FreeLoopbackPort();
    const fs::path conf = dir / "nginx.conf";
    std::ofstream(conf) << NginxConfigFor(e2e::ReadWholeFile(repo_conf), replicas, grpc_port_,
                                          http_port_, dir);
    const std::string bin = nginx.string(), prefix = dir.string() + "/", c = conf.string(),
                      err = (dir / "nginx-error.log").string(), out = (dir / "nginx.out").string();
    std::fflush(nullptr);  // or the child's freopen flushes the parent's buffer again
    pid_ = fork();
    if (pid_ == 0) {
      prctl(PR_SET_PDEATHSIG, SIGTERM);  // the parent dies: nginx stops too
      FILE* f = std::freopen(out.c_str(), "w", stdout);
      if (f != nullptr) dup2(fileno(f), STDERR_FILENO);
      execl(bin.c_str(), bin.c_str(), "-p", prefix.c_str(), "-c", c.c_str(), "-e", err.c_str(),
            "-g", "daemon off;", static_cast<char*>(nullptr));
      _exit(127);
    }
    const auto readiness = seaplan::testing::WaitUntilChildReady(
        pid_, std::chrono::seconds(30), [&] { return Accepts(grpc_port_) && Accepts(http_port_); });
    if (readiness == seaplan::testing::ChildReadiness::kExited) pid_ = -1;
    return readiness == seaplan::testing::ChildReadiness::kReady;
  }

  // SIGTERM (fast shutdown), SIGKILL after 10 s; reaped.
  void Stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    int status = 0;
    for (int i = 0; i < 200 && waitpid(pid_, &status, WNOHANG) == 0; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    if (waitpid(pid_, &status, WNOHANG) == 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, &status, 0);
    }
    pid_ = -1;
  }

  std::string grpc_address() const { return "127.0.0.1:" + std::to_string(grpc_port_); }
  int http_port() const { return http_port_; }
  // What nginx printed and logged (for failure messages).
  std::string log() const {
    return e2e::ReadWholeFile(dir_ / "nginx.out") + e2e::ReadWholeFile(dir_ / "nginx-error.log");
  }

 private:
  fs::path dir_;
  pid_t pid_ = -1;
  int grpc_port_ = 0;
  int http_port_ = 0;
};

}  // namespace seaplan::ha
