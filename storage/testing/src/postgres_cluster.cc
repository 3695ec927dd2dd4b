#include "seaplan/storage/testing/postgres_cluster.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <libpq-fe.h>
#include <netinet/in.h>
#include <pwd.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <mutex>
#include <sstream>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"

extern char** environ;

namespace seaplan::storage::testing {
namespace {

namespace fs = std::filesystem;

// The newest PostgreSQL bin folder holding initdb and pg_ctl.
absl::StatusOr<fs::path> FindBinDir() {
  if (const char* env = std::getenv("SEAPLAN_PG_BINDIR"); env && *env) {
    if (fs::exists(fs::path(env) / "initdb")) return fs::path(env);
    return absl::NotFoundError(absl::StrCat("SEAPLAN_PG_BINDIR=", env, " has no initdb"));
  }
  std::vector<std::pair<int, fs::path>> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator("/usr/lib/postgresql", ec)) {
    const fs::path bin = entry.path() / "bin";
    if (fs::exists(bin / "initdb") && fs::exists(bin / "pg_ctl")) {
      found.emplace_back(std::atoi(entry.path().filename().c_str()), bin);
    }
  }
  if (found.empty()) {
    return absl::NotFoundError(
        "PostgreSQL server binaries not found (no /usr/lib/postgresql/*/bin/initdb; "
        "scripts/install-deps.sh installs Debian's postgresql package, or set SEAPLAN_PG_BINDIR)");
  }
  std::sort(found.begin(), found.end());
  return found.back().second;
}

// The account the server runs as when this process is root.
absl::StatusOr<std::string> UnprivilegedUser() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("SEAPLAN_PG_USER"); env && *env) candidates.push_back(env);
  candidates.push_back("postgres");
  candidates.push_back("nobody");
  for (const std::string& name : candidates) {
    if (getpwnam(name.c_str()) != nullptr) return name;
  }
  return absl::NotFoundError(
      "running as root and no unprivileged account (postgres, nobody) "
      "to run PostgreSQL as; set SEAPLAN_PG_USER");
}

// Runs argv (through runuser when `run_as` is set), output to `log`; waits.
absl::Status Run(const std::string& run_as, std::vector<std::string> argv, const fs::path& log) {
  if (!run_as.empty()) {
    argv.insert(argv.begin(), {"runuser", "-u", run_as, "--"});
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<char*> args;
  args.reserve(argv.size() + 1);  // and the terminating null
  for (std::string& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    return absl::UnavailableError(absl::StrCat("cannot run ", argv[0], ": ", std::strerror(rc)));
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return absl::OkStatus();
  std::ifstream in(log);
  std::stringstream text;
  text << in.rdbuf();
  std::string tail = text.str();
  if (tail.size() > 2000) tail = tail.substr(tail.size() - 2000);
  return absl::UnavailableError(
      absl::StrCat(absl::StrJoin(argv, " "), " failed (status ", status, "): ", tail));
}

std::string ShellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out += "'\\''";
    } else {
      out += c;
    }
  }
  return out + "'";
}

// Connects as the superuser; the caller finishes the connection.
absl::StatusOr<PGconn*> Connect(const std::string& url) {
  PGconn* conn = PQconnectdb(url.c_str());
  if (PQstatus(conn) != CONNECTION_OK) {
    absl::Status st = absl::UnavailableError(PQerrorMessage(conn));
    PQfinish(conn);
    return st;
  }
  return conn;
}

}  // namespace

int FreeLoopbackPort() {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  addr.sin_port = 0;
  socklen_t len = sizeof(addr);
  int port = 0;
  if (bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) == 0 &&
      getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0) {
    port = ntohs(addr.sin_port);
  }
  close(fd);
  return port;
}

absl::StatusOr<std::unique_ptr<TemporaryPostgresCluster>> TemporaryPostgresCluster::Start(
    const PostgresClusterOptions& options) {
  std::unique_ptr<TemporaryPostgresCluster> cluster(new TemporaryPostgresCluster());
  SEAPLAN_ASSIGN_OR_RETURN(cluster->bindir_, FindBinDir());
  if (geteuid() == 0) {
    SEAPLAN_ASSIGN_OR_RETURN(cluster->run_as_, UnprivilegedUser());
  }
  // The server's account must reach the folder: as root, TMPDIR may be
  // under a private home, so use /tmp.
  const fs::path parent = cluster->run_as_.empty() ? fs::temp_directory_path() : fs::path("/tmp");
  std::string folder_template = (parent / "seaplan-pg-XXXXXX").string();
  if (mkdtemp(folder_template.data()) == nullptr) {
    return absl::UnavailableError(absl::StrCat("mkdtemp: ", std::strerror(errno)));
  }
  cluster->folder_ = folder_template;
  if (!cluster->run_as_.empty()) {
    const passwd* pw = getpwnam(cluster->run_as_.c_str());
    if (chown(cluster->folder_.c_str(), pw->pw_uid, pw->pw_gid) != 0) {
      return absl::UnavailableError(
          absl::StrCat("chown ", cluster->folder_.string(), ": ", std::strerror(errno)));
    }
  }

  // The guardian: stops the server and removes the folder when the pipe
  // closes, i.e. when this process ends however it ends.
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    return absl::UnavailableError(absl::StrCat("pipe: ", std::strerror(errno)));
  }
  const fs::path data = cluster->folder_ / "data";
  std::string stop_cmd = absl::StrCat(ShellQuote((cluster->bindir_ / "pg_ctl").string()), " -D ",
                                      ShellQuote(data.string()), " -m immediate -w stop");
  if (!cluster->run_as_.empty()) {
    stop_cmd = absl::StrCat("runuser -u ", ShellQuote(cluster->run_as_), " -- ", stop_cmd);
  }
  std::string script = absl::StrCat(
      "cat >/dev/null; if [ -f ", ShellQuote((data / "postmaster.pid").string()), " ]; then ",
      stop_cmd, " >/dev/null 2>&1; fi; rm -rf ", ShellQuote(cluster->folder_.string()));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], 0);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSID);
  std::string sh = "/bin/sh", dash_c = "-c";
  char* args[] = {sh.data(), dash_c.data(), script.data(), nullptr};
  const int rc = posix_spawn(&cluster->guardian_, "/bin/sh", &actions, &attr, args, environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  close(fds[0]);
  cluster->guardian_pipe_ = fds[1];
  if (rc != 0) {
    cluster->guardian_ = -1;
    return absl::UnavailableError(absl::StrCat("cannot spawn the guardian: ", std::strerror(rc)));
  }

  const fs::path log = cluster->folder_ / "setup.log";
  SEAPLAN_RETURN_IF_ERROR(
      Run(cluster->run_as_,
          {(cluster->bindir_ / "initdb").string(), "-D", data.string(), "-U", "seaplan",
           "--auth=trust", "-E", "UTF8", "--no-locale", "--no-sync", "--no-instructions"},
          log));
  {
    std::ofstream conf(data / "postgresql.conf", std::ios::app);
    conf << "\n# seaplan test cluster\nlisten_addresses = '127.0.0.1'\n"
         << "unix_socket_directories = '" << cluster->folder_.string() << "'\n"
         << "max_connections = " << options.max_connections << "\n"
         << "fsync = " << (options.fsync ? "on" : "off") << "\n"
         << "full_page_writes = " << (options.fsync ? "on" : "off") << "\n";
    if (!conf) return absl::UnavailableError("cannot write postgresql.conf");
  }
  // A free port can be taken between the probe and the bind: try a few.
  absl::Status started;
  for (int attempt = 0; attempt < 5; ++attempt) {
    cluster->port_ = FreeLoopbackPort();
    started = Run(cluster->run_as_,
                  {(cluster->bindir_ / "pg_ctl").string(), "-D", data.string(), "-l",
                   (cluster->folder_ / "server.log").string(), "-w", "-t",
                   std::to_string(options.start_timeout.count()), "-o",
                   absl::StrCat("-p ", cluster->port_), "start"},
                  log);
    if (started.ok()) break;
  }
  SEAPLAN_RETURN_IF_ERROR(started);
  return cluster;
}

TemporaryPostgresCluster::~TemporaryPostgresCluster() {
  (void)Stop();
}

absl::Status TemporaryPostgresCluster::Stop() {
  if (guardian_pipe_ < 0) return absl::OkStatus();
  close(guardian_pipe_);
  guardian_pipe_ = -1;
  if (guardian_ > 0) {
    int status = 0;
    while (waitpid(guardian_, &status, 0) < 0 && errno == EINTR) {
    }
    guardian_ = -1;
  }
  if (fs::exists(folder_)) {
    return absl::InternalError(absl::StrCat("could not remove ", folder_.string()));
  }
  return absl::OkStatus();
}

std::string TemporaryPostgresCluster::Url(const std::string& database) const {
  return absl::StrCat("postgresql://seaplan@127.0.0.1:", port_, "/", database);
}

absl::StatusOr<std::string> TemporaryPostgresCluster::CreateDatabase() {
  const std::string name = absl::StrCat("test_", ++databases_created_);
  SEAPLAN_RETURN_IF_ERROR(Execute(Url(), absl::StrCat("CREATE DATABASE ", name)));
  return Url(name);
}

absl::Status TemporaryPostgresCluster::Execute(const std::string& url,
                                               const std::string& sql) const {
  SEAPLAN_ASSIGN_OR_RETURN(PGconn * conn, Connect(url));
  PGresult* r = PQexec(conn, sql.c_str());
  const ExecStatusType st = PQresultStatus(r);
  absl::Status status = (st == PGRES_COMMAND_OK || st == PGRES_TUPLES_OK)
                            ? absl::OkStatus()
                            : absl::InternalError(PQresultErrorMessage(r));
  PQclear(r);
  PQfinish(conn);
  return status;
}

absl::StatusOr<std::string> TemporaryPostgresCluster::QueryValue(const std::string& url,
                                                                 const std::string& sql) const {
  SEAPLAN_ASSIGN_OR_RETURN(PGconn * conn, Connect(url));
  PGresult* r = PQexec(conn, sql.c_str());
  absl::StatusOr<std::string> value;
  if (PQresultStatus(r) != PGRES_TUPLES_OK) {
    value = absl::InternalError(PQresultErrorMessage(r));
  } else if (PQntuples(r) == 0) {
    value = absl::NotFoundError(absl::StrCat("no row: ", sql));
  } else {
    value = std::string(PQgetvalue(r, 0, 0));
  }
  PQclear(r);
  PQfinish(conn);
  return value;
}

absl::StatusOr<TemporaryPostgresCluster*> ProcessCluster() {
  static std::mutex mu;
  static absl::StatusOr<std::unique_ptr<TemporaryPostgresCluster>>* cluster = nullptr;
  std::lock_guard lock(mu);
  if (cluster == nullptr) {
    // Deliberately leaked: the guardian stops the server when the process
    // exits, and no static destructor order can then bite.
    cluster = new absl::StatusOr<std::unique_ptr<TemporaryPostgresCluster>>(
        TemporaryPostgresCluster::Start());
  }
  if (!cluster->ok()) return cluster->status();
  return cluster->value().get();
}

}  // namespace seaplan::storage::testing
