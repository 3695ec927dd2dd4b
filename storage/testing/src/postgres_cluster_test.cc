// The throwaway cluster is stopped and removed when its process dies
// without cleaning up (SIGKILL), by the guardian.
#include "seaplan/storage/testing/postgres_cluster.h"

#include <gtest/gtest.h>
#include <libpq-fe.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <thread>

namespace seaplan::storage::testing {
namespace {

bool Accepts(int port) {
  const std::string url =
      "postgresql://seaplan@127.0.0.1:" + std::to_string(port) + "/postgres?connect_timeout=5";
  PGconn* conn = PQconnectdb(url.c_str());
  const bool ok = PQstatus(conn) == CONNECTION_OK;
  PQfinish(conn);
  return ok;
}

TEST(PostgresClusterTest, GuardianStopsTheClusterOfAKilledProcess) {
  int fds[2];
  ASSERT_EQ(pipe(fds), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    close(fds[0]);
    auto cluster = TemporaryPostgresCluster::Start();
    std::string report = "error";
    if (cluster.ok()) {
      report = std::to_string((*cluster)->port()) + " " + (*cluster)->folder().string();
    } else if (absl::IsNotFound(cluster.status())) {
      report = "missing " + std::string(cluster.status().message());
    }
    (void)!write(fds[1], report.data(), report.size());
    close(fds[1]);
    raise(SIGKILL);  // no destructor, no atexit: only the guardian is left
    _exit(1);
  }
  close(fds[1]);
  std::string report;
  char buffer[4096];
  for (ssize_t n; (n = read(fds[0], buffer, sizeof(buffer))) > 0;) report.append(buffer, n);
  close(fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  if (report.starts_with("missing ")) {
    const char* ci = std::getenv("CI");
    if (ci != nullptr && *ci != '\0') FAIL() << "CI is set: " << report;
    GTEST_SKIP() << "PostgreSQL not available: " << report.substr(8);
  }
  ASSERT_NE(report, "error");
  const std::size_t space = report.find(' ');
  const int port = std::stoi(report.substr(0, space));
  const std::filesystem::path folder = report.substr(space + 1);
  // The guardian works asynchronously: wait for it, within a generous bound.
  bool gone = false;
  for (int i = 0; i < 600 && !gone; ++i) {
    gone = !std::filesystem::exists(folder) && !Accepts(port);
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_TRUE(gone) << "cluster on port " << port << " in " << folder << " still there";
}

}  // namespace
}  // namespace seaplan::storage::testing
