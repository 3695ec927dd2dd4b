// The real seaplan-server binary (SEAPLAN_BIN_DIR): starts on ephemeral
// loopback ports, learns them from --port-file, serves both transports,
// lists its services through reflection, and on SIGTERM drains, exits 0
// and leaves an intact database. Two servers starting at once on one
// database (SQLite data folder, PostgreSQL) create one admin token.
//
// This is a separate test binary that does not link the server libraries:
// libgrpc++_reflection carries its own copy of the reflection protos, which
// would clash with the client stubs of seaplan_grpc_std_protos.
#include <arpa/inet.h>
#include <fcntl.h>
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include "absl/strings/escaping.h"
#include "grpc/health/v1/health.grpc.pb.h"
#include "grpc/reflection/v1alpha/reflection.grpc.pb.h"
#include "seaplan/storage/open_store.h"
#include "seaplan/storage/sqlite_store.h"
#include "seaplan/storage/testing/postgres_cluster.h"
#include "seaplan/testing/shared_data.h"
#include "seaplan/testing/tiny_filesystem.h"
#include "seaplan/v1/access.grpc.pb.h"
#include "seaplan/v1/chart.grpc.pb.h"
#include "seaplan/v1/mission.grpc.pb.h"

extern char** environ;

namespace seaplan::server::testing {
namespace {

class TempDir {
 public:
  TempDir() {
    static std::atomic<int> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("seaplan-binary-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

void SetDeadline(grpc::ClientContext* ctx, int ms) {
  ctx->set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(ms));
}

// A child process that is killed (SIGKILL) in the destructor if still running.
class Child {
 public:
  // `output`: when not empty, the file that gets the child's stdout and stderr.
  explicit Child(const std::vector<std::string>& argv, const std::filesystem::path& output = {}) {
    std::vector<char*> args;
    args.reserve(argv.size() + 1);
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (!output.empty()) {
      posix_spawn_file_actions_addopen(&actions, 1, output.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                       0644);
      posix_spawn_file_actions_adddup2(&actions, 1, 2);
    }
    EXPECT_EQ(posix_spawn(&pid_, args[0], &actions, nullptr, args.data(), environ), 0) << argv[0];
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Child() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  pid_t pid() const { return pid_; }
  // Waits up to `timeout` for exit; returns the wait status or -1 on timeout.
  int Wait(std::chrono::seconds timeout) {
    const auto until = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < until) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return status;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return -1;
  }

 private:
  pid_t pid_ = -1;
};

bool ReadPorts(const std::filesystem::path& file, int* grpc_port, int* http_port) {
  std::ifstream in(file);
  std::string line;
  *grpc_port = *http_port = 0;
  while (std::getline(in, line)) {
    if (line.rfind("grpc=", 0) == 0) *grpc_port = std::stoi(line.substr(5));
    if (line.rfind("http=", 0) == 0) *http_port = std::stoi(line.substr(5));
  }
  return *grpc_port > 0 && *http_port > 0;
}

// Waits up to 20 s for the server's port file; fails if the server exits.
void WaitForPorts(Child& child, const std::filesystem::path& port_file, int* grpc_port,
                  int* http_port) {
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!ReadPorts(port_file, grpc_port, http_port) && std::chrono::steady_clock::now() < until) {
    ASSERT_EQ(waitpid(child.pid(), nullptr, WNOHANG), 0) << "server exited early";
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

TEST(ServerBinaryTest, ServesBothTransportsAndShutsDownCleanlyOnSigterm) {
  const std::filesystem::path binary = seaplan::testing::BinDir() / "seaplan-server";
  if (!std::filesystem::exists(binary)) GTEST_SKIP() << binary << " not built";
  TempDir dir;
  const auto port_file = dir.path() / "ports";
  const auto data_dir = dir.path() / "data";
  Child child({binary.string(), "--grpc-addr", "127.0.0.1:0", "--http-addr", "127.0.0.1:0",
               "--data-dir", data_dir.string(), "--port-file", port_file.string(), "--log-level",
               "warn", "--planning-threads", "1"});
  int grpc_port = 0, http_port = 0;
  ASSERT_NO_FATAL_FAILURE(WaitForPorts(child, port_file, &grpc_port, &http_port));
  ASSERT_GT(grpc_port, 0) << "no port file";

  auto channel = grpc::CreateChannel("127.0.0.1:" + std::to_string(grpc_port),
                                     grpc::InsecureChannelCredentials());
  auto health = grpc::health::v1::Health::NewStub(channel);
  grpc::ClientContext ctx;
  SetDeadline(&ctx, 5000);
  grpc::health::v1::HealthCheckRequest req;
  req.set_service("seaplan.v1.PlanningService");
  grpc::health::v1::HealthCheckResponse resp;
  ASSERT_TRUE(health->Check(&ctx, req, &resp).ok());
  EXPECT_EQ(resp.status(), grpc::health::v1::HealthCheckResponse::SERVING);

  // First start: an admin token in the data folder, readable by the owner only.
  const auto token_file = data_dir / "admin.token";
  struct stat token_stat {};
  ASSERT_EQ(stat(token_file.c_str(), &token_stat), 0) << "no " << token_file;
  EXPECT_EQ(token_stat.st_mode & 0777, 0600u);
  std::string token;
  std::getline(std::ifstream(token_file), token);
  ASSERT_EQ(token.rfind("seaplan_", 0), 0u) << token;

  httplib::Client http("127.0.0.1", http_port);
  auto res = http.Get("/healthz");  // health needs no token
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  res = http.Post("/v1/MissionService/GetMission", "{\"missionId\":\"m-x\"}", "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 401);
  res = http.Post("/v1/MissionService/GetMission", {{"Authorization", "Bearer " + token}},
                  "{\"missionId\":\"m-x\"}", "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  auto missions = v1::MissionService::NewStub(channel);
  v1::ListMissionsRequest list_req;
  v1::ListMissionsResponse list_resp;
  {
    grpc::ClientContext anonymous;
    SetDeadline(&anonymous, 5000);
    EXPECT_EQ(missions->ListMissions(&anonymous, list_req, &list_resp).error_code(),
              grpc::StatusCode::UNAUTHENTICATED);
  }
  grpc::ClientContext ctx2;
  SetDeadline(&ctx2, 5000);
  ctx2.AddMetadata("authorization", "Bearer " + token);
  ASSERT_TRUE(missions->ListMissions(&ctx2, list_req, &list_resp).ok());

  // Reflection (no token needed: the schema is public) lists the services.
  {
    auto reflection = grpc::reflection::v1alpha::ServerReflection::NewStub(channel);
    grpc::ClientContext rctx;
    SetDeadline(&rctx, 5000);
    auto stream = reflection->ServerReflectionInfo(&rctx);
    grpc::reflection::v1alpha::ServerReflectionRequest rreq;
    rreq.set_list_services("*");
    ASSERT_TRUE(stream->Write(rreq));
    grpc::reflection::v1alpha::ServerReflectionResponse rresp;
    ASSERT_TRUE(stream->Read(&rresp));
    std::set<std::string> names;
    for (const auto& service : rresp.list_services_response().service())
      names.insert(service.name());
    for (const char* expected :
         {"seaplan.v1.PlanningService", "seaplan.v1.ChartService", "seaplan.v1.RouteService",
          "seaplan.v1.MissionService", "seaplan.v1.AccessService", "grpc.health.v1.Health"}) {
      EXPECT_TRUE(names.count(expected)) << expected;
    }
    // The schema itself is served too (what grpcurl needs).
    grpc::reflection::v1alpha::ServerReflectionRequest file_req;
    file_req.set_file_containing_symbol("seaplan.v1.MissionService");
    ASSERT_TRUE(stream->Write(file_req));
    ASSERT_TRUE(stream->Read(&rresp));
    EXPECT_GT(rresp.file_descriptor_response().file_descriptor_proto_size(), 0);
    stream->WritesDone();
    EXPECT_TRUE(stream->Finish().ok());
  }

  ASSERT_EQ(kill(child.pid(), SIGTERM), 0);
  const int status = child.Wait(std::chrono::seconds(15));
  ASSERT_NE(status, -1) << "did not exit within 15 s of SIGTERM";
  ASSERT_TRUE(WIFEXITED(status)) << "killed by a signal";
  EXPECT_EQ(WEXITSTATUS(status), 0);

  // The database is complete and consistent (checkpointed: no -wal left over).
  EXPECT_FALSE(std::filesystem::exists(data_dir / "seaplan.db-wal") &&
               std::filesystem::file_size(data_dir / "seaplan.db-wal") > 0);
  auto store = storage::SqliteStore::Open((data_dir / "seaplan.db").string());
  ASSERT_TRUE(store.ok()) << store.status();
  EXPECT_TRUE((*store)->CheckIntegrity().ok());
  EXPECT_EQ(*(*store)->SchemaVersion(), storage::LatestSchemaVersion());
}

// A second server on a port of a running one refuses to start, with an
// error that names the address, instead of taking a share of the first
// one's connections (gRPC and httplib bind with SO_REUSEPORT unless told
// not to).
TEST(ServerBinaryTest, ASecondServerOnATakenPortExitsWithAnError) {
  const std::filesystem::path binary = seaplan::testing::BinDir() / "seaplan-server";
  if (!std::filesystem::exists(binary)) GTEST_SKIP() << binary << " not built";
  TempDir dir;
  const auto port_file = dir.path() / "ports";
  Child first({binary.string(), "--grpc-addr", "127.0.0.1:0", "--http-addr", "127.0.0.1:0",
               "--data-dir", (dir.path() / "data-1").string(), "--port-file", port_file.string(),
               "--log-level", "warn", "--planning-threads", "1"});
  int grpc_port = 0, http_port = 0;
  ASSERT_NO_FATAL_FAILURE(WaitForPorts(first, port_file, &grpc_port, &http_port));
  ASSERT_GT(grpc_port, 0) << "no port file";

  const std::string taken = "127.0.0.1:" + std::to_string(grpc_port);
  const std::string taken_http = "127.0.0.1:" + std::to_string(http_port);
  // Starts a second server on these addresses; returns what it printed.
  auto second_fails = [&](const std::string& grpc_addr, const std::string& http_addr) {
    const auto output = dir.path() / "second.log";
    Child second(
        {binary.string(), "--grpc-addr", grpc_addr, "--http-addr", http_addr, "--data-dir",
         (dir.path() / "data-2").string(), "--log-level", "warn", "--planning-threads", "1"},
        output);
    const int status = second.Wait(std::chrono::seconds(20));
    EXPECT_NE(status, -1) << "the second server on " << grpc_addr << " and " << http_addr
                          << " is still running";
    EXPECT_TRUE(status != -1 && WIFEXITED(status) && WEXITSTATUS(status) != 0) << status;
    std::stringstream log;
    log << std::ifstream(output).rdbuf();
    return log.str();
  };
  std::string log = second_fails(taken, "127.0.0.1:0");
  EXPECT_NE(log.find("gRPC: cannot listen on " + taken), std::string::npos) << log;
  log = second_fails("127.0.0.1:0", taken_http);
  EXPECT_NE(log.find("HTTP: cannot bind " + taken_http), std::string::npos) << log;

  // The first server still answers on its port.
  auto channel = grpc::CreateChannel(taken, grpc::InsecureChannelCredentials());
  grpc::ClientContext ctx;
  SetDeadline(&ctx, 5000);
  grpc::health::v1::HealthCheckRequest req;
  grpc::health::v1::HealthCheckResponse resp;
  ASSERT_TRUE(grpc::health::v1::Health::NewStub(channel)->Check(&ctx, req, &resp).ok());
  EXPECT_EQ(resp.status(), grpc::health::v1::HealthCheckResponse::SERVING);
  httplib::Client http("127.0.0.1", http_port);
  auto res = http.Get("/healthz");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
}

// Servers started at once on one database, `rounds` times on a fresh one:
// every server comes up, exactly one admin token is stored, exactly one
// data folder holds admin.token (mode 0600, no temporary file left beside
// it), and every server accepts the token it holds as admin.
// `database`: empty for SQLite (then the servers share data_dirs[0]).
void StartAtOnceCreatesOneAdminToken(const std::string& database, int servers, int rounds,
                                     const std::function<std::string()>& fresh_database) {
  const std::filesystem::path binary = seaplan::testing::BinDir() / "seaplan-server";
  for (int round = 0; round < rounds; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    TempDir dir;
    const std::string url = database.empty() ? "" : fresh_database();
    std::vector<std::filesystem::path> data_dirs;
    std::vector<std::unique_ptr<Child>> children;
    data_dirs.reserve(static_cast<std::size_t>(servers));
    for (int i = 0; i < servers; ++i) {
      data_dirs.push_back(dir.path() / (url.empty() ? "data" : "data-" + std::to_string(i)));
    }
    for (int i = 0; i < servers; ++i) {
      std::vector<std::string> args = {binary.string(),
                                       "--grpc-addr",
                                       "127.0.0.1:0",
                                       "--http-addr",
                                       "127.0.0.1:0",
                                       "--data-dir",
                                       data_dirs[i].string(),
                                       "--port-file",
                                       (dir.path() / ("ports-" + std::to_string(i))).string(),
                                       "--log-level",
                                       "warn",
                                       "--planning-threads",
                                       "1"};
      if (!url.empty()) {
        args.push_back("--database");
        args.push_back(url);
      }
      children.push_back(std::make_unique<Child>(args));
    }
    std::vector<int> grpc_ports(servers);
    for (int i = 0; i < servers; ++i) {
      int http_port = 0;
      ASSERT_NO_FATAL_FAILURE(WaitForPorts(
          *children[i], dir.path() / ("ports-" + std::to_string(i)), &grpc_ports[i], &http_port));
      ASSERT_GT(grpc_ports[i], 0) << "server " << i << " wrote no port file";
    }

    if (url.empty()) data_dirs.resize(1);  // the servers' one folder
    std::vector<std::string> token_files;
    for (const auto& data_dir : data_dirs) {
      if (!std::filesystem::exists(data_dir)) continue;
      for (const auto& entry : std::filesystem::directory_iterator(data_dir)) {
        const std::string name = entry.path().filename().string();
        EXPECT_EQ(name.find("admin.token."), std::string::npos) << "left behind: " << entry.path();
        if (name == "admin.token") token_files.push_back(entry.path().string());
      }
    }
    ASSERT_EQ(token_files.size(), 1u) << "admin.token files written";
    struct stat token_stat {};
    ASSERT_EQ(stat(token_files[0].c_str(), &token_stat), 0);
    EXPECT_EQ(token_stat.st_mode & 0777, 0600u);
    std::string token;
    std::getline(std::ifstream(token_files[0]), token);
    ASSERT_EQ(token.rfind("seaplan_", 0), 0u) << token;

    {
      auto opened = storage::OpenStore(url, data_dirs[0].string());
      ASSERT_TRUE(opened.ok()) << opened.status();
      auto tokens = opened->store->tokens().List();
      ASSERT_TRUE(tokens.ok()) << tokens.status();
      ASSERT_EQ(tokens->size(), 1u) << "tokens stored";
      EXPECT_EQ((*tokens)[0].role, "admin");
      EXPECT_EQ(token.rfind("seaplan_" + (*tokens)[0].id + "_", 0), 0u) << token;
      ASSERT_TRUE(opened->store->Close().ok());
    }
    for (int i = 0; i < servers; ++i) {
      auto channel = grpc::CreateChannel("127.0.0.1:" + std::to_string(grpc_ports[i]),
                                         grpc::InsecureChannelCredentials());
      grpc::ClientContext ctx;
      SetDeadline(&ctx, 10000);
      ctx.AddMetadata("authorization", "Bearer " + token);
      v1::WhoAmIResponse who;
      const grpc::Status st =
          v1::AccessService::NewStub(channel)->WhoAmI(&ctx, v1::WhoAmIRequest(), &who);
      ASSERT_TRUE(st.ok()) << "server " << i << ": " << st.error_message();
      EXPECT_EQ(who.role(), v1::ROLE_ADMIN);
    }
    for (auto& child : children) ASSERT_EQ(kill(child->pid(), SIGTERM), 0);
    for (auto& child : children) EXPECT_NE(child->Wait(std::chrono::seconds(15)), -1);
  }
}

TEST(ServerBinaryTest, ServersStartingAtOnceOnOneSqliteFolderCreateOneAdminToken) {
  if (!std::filesystem::exists(seaplan::testing::BinDir() / "seaplan-server"))
    GTEST_SKIP() << "seaplan-server not built";
  StartAtOnceCreatesOneAdminToken("", 2, 4, nullptr);
}

TEST(ServerBinaryTest, ServersStartingAtOnceOnOnePostgresDatabaseCreateOneAdminToken) {
  if (!std::filesystem::exists(seaplan::testing::BinDir() / "seaplan-server"))
    GTEST_SKIP() << "seaplan-server not built";
  auto cluster = storage::testing::ProcessCluster();
  if (absl::IsNotFound(cluster.status())) {
    if (std::getenv("CI") != nullptr) FAIL() << cluster.status();
    GTEST_SKIP() << "PostgreSQL not available: " << cluster.status().message();
  }
  ASSERT_TRUE(cluster.ok()) << cluster.status();
  StartAtOnceCreatesOneAdminToken("postgresql", 2, 4, [&]() -> std::string {
    auto url = (*cluster)->CreateDatabase();
    EXPECT_TRUE(url.ok()) << url.status();
    return url.ok() ? *url : "";
  });
}

// The data folder's disk fills up under a running server: an upload that
// does not fit is refused with UNAVAILABLE / 503 saying the disk is full,
// what was acknowledged stays readable, uploads succeed again once there is
// space, and the server still shuts down cleanly onto a sound database.
TEST(ServerBinaryTest, AFullDataDiskAnswersUnavailableOverBothTransportsAndTheServerRecovers) {
  const std::filesystem::path binary = seaplan::testing::BinDir() / "seaplan-server";
  if (!std::filesystem::exists(binary)) GTEST_SKIP() << binary << " not built";
  seaplan::testing::TinyFilesystem disk("1m");
  if (!disk.mounted()) GTEST_SKIP() << "full-disk test skipped: " << disk.reason();
  TempDir dir;
  const auto port_file = dir.path() / "ports";
  const auto data_dir = disk.path("data");
  Child child({binary.string(), "--grpc-addr", "127.0.0.1:0", "--http-addr", "127.0.0.1:0",
               "--data-dir", data_dir.string(), "--port-file", port_file.string(), "--log-level",
               "error", "--planning-threads", "1"});
  int grpc_port = 0, http_port = 0;
  ASSERT_NO_FATAL_FAILURE(WaitForPorts(child, port_file, &grpc_port, &http_port));
  ASSERT_GT(grpc_port, 0) << "no port file";
  std::string token;
  std::getline(std::ifstream(data_dir / "admin.token"), token);
  ASSERT_FALSE(token.empty());

  // A small chart padded with 32 KiB of JSON whitespace: its source files are
  // stored with it, so a few dozen uploads fill a 1 MiB disk.
  std::string geojson = seaplan::testing::ReadFile(seaplan::testing::SourceDir() /
                                                   "engine/chart/testdata/harbour.geojson");
  ASSERT_FALSE(geojson.empty());
  geojson.append(32 * 1024, ' ');  // at the end: GDAL recognises GeoJSON by its start
  v1::UploadChartRequest upload;
  upload.set_name("harbour");
  upload.set_format(v1::CHART_FORMAT_GEOJSON);
  upload.set_minimum_depth_m(5);
  upload.add_files()->set_name("harbour.geojson");
  upload.mutable_files(0)->set_content(geojson);
  auto charts = v1::ChartService::NewStub(grpc::CreateChannel(
      "127.0.0.1:" + std::to_string(grpc_port), grpc::InsecureChannelCredentials()));
  auto upload_over_grpc = [&] {
    grpc::ClientContext ctx;
    SetDeadline(&ctx, 30000);
    ctx.AddMetadata("authorization", "Bearer " + token);
    v1::UploadChartResponse uploaded;
    return charts->UploadChart(&ctx, upload, &uploaded);
  };
  grpc::Status full;
  int stored = 0;
  for (int i = 0; i < 200 && full.ok(); ++i) {
    full = upload_over_grpc();
    if (full.ok()) ++stored;
  }
  ASSERT_FALSE(full.ok()) << "a 1 MiB disk held 200 charts of 32 KiB";
  EXPECT_EQ(full.error_code(), grpc::StatusCode::UNAVAILABLE) << full.error_message();
  EXPECT_NE(full.error_message().find("disk is full"), std::string::npos) << full.error_message();
  EXPECT_GT(stored, 0);
  std::printf("the 1 MiB disk was full after %d charts\n", stored);

  httplib::Client http("127.0.0.1", http_port);
  const httplib::Headers auth{{"Authorization", "Bearer " + token}};
  const std::string body =
      "{\"name\":\"harbour\",\"format\":\"CHART_FORMAT_GEOJSON\",\"minimumDepthM\":5,"
      "\"files\":[{\"name\":\"harbour.geojson\",\"content\":\"" +
      absl::Base64Escape(geojson) + "\"}]}";
  auto refused = http.Post("/v1/ChartService/UploadChart", auth, body, "application/json");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 503) << refused->body;
  EXPECT_NE(refused->body.find("disk is full"), std::string::npos) << refused->body;

  // Reads still work and see exactly the acknowledged charts.
  auto listed =
      http.Post("/v1/ChartService/ListCharts", auth, "{\"pageSize\":1000}", "application/json");
  ASSERT_TRUE(listed);
  ASSERT_EQ(listed->status, 200) << listed->body;
  int listed_charts = 0;
  for (std::size_t at = listed->body.find("\"chartId\""); at != std::string::npos;
       at = listed->body.find("\"chartId\"", at + 1)) {
    ++listed_charts;
  }
  EXPECT_EQ(listed_charts, stored);

  // Space is back: the same upload succeeds on both transports.
  ASSERT_TRUE(disk.Remount("size=32m"));
  const grpc::Status again = upload_over_grpc();
  EXPECT_TRUE(again.ok()) << again.error_message();
  auto accepted = http.Post("/v1/ChartService/UploadChart", auth, body, "application/json");
  ASSERT_TRUE(accepted);
  EXPECT_EQ(accepted->status, 200) << accepted->body.substr(0, 300);

  ASSERT_EQ(kill(child.pid(), SIGTERM), 0);
  const int status = child.Wait(std::chrono::seconds(15));
  ASSERT_NE(status, -1) << "did not exit within 15 s of SIGTERM";
  ASSERT_TRUE(WIFEXITED(status)) << "killed by a signal";
  EXPECT_EQ(WEXITSTATUS(status), 0);
  auto store = storage::SqliteStore::Open((data_dir / "seaplan.db").string());
  ASSERT_TRUE(store.ok()) << store.status();
  EXPECT_TRUE((*store)->CheckIntegrity().ok());
  auto all = (*store)->charts().List(1000, 0);
  ASSERT_TRUE(all.ok()) << all.status();
  EXPECT_EQ(static_cast<int>(all->items.size()), stored + 2);
}

// Runs a shell command; its exit code and standard output + error.
std::pair<int, std::string> Shell(const std::string& command) {
  std::string output;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return {-1, ""};
  char buffer[4096];
  while (std::size_t n = std::fread(buffer, 1, sizeof(buffer), pipe)) output.append(buffer, n);
  const int status = ::pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

TEST(ServerBinaryTest, BadFlagsAndBusyPortsFailWithNonZeroExit) {
  const std::filesystem::path binary = seaplan::testing::BinDir() / "seaplan-server";
  if (!std::filesystem::exists(binary)) GTEST_SKIP() << binary << " not built";
  TempDir dir;
  {
    Child child(
        {binary.string(), "--planning-threads", "0", "--data-dir", (dir.path() / "d").string()});
    const int status = child.Wait(std::chrono::seconds(10));
    ASSERT_NE(status, -1);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 0);
  }
  {
    Child child(
        {binary.string(), "--log-level", "loud", "--data-dir", (dir.path() / "d").string()});
    const int status = child.Wait(std::chrono::seconds(10));
    ASSERT_NE(status, -1);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 0);
  }
  {
    // A sweep not shorter than the lease, from the environment too.
    const auto [code, output] = Shell("SEAPLAN_SWEEP_MS=2000 " + binary.string() +
                                      " --lease-ms 2000 --data-dir " + (dir.path() / "d").string());
    EXPECT_EQ(code, 2) << output;
    EXPECT_NE(output.find("must be shorter than the lease (2000 ms)"), std::string::npos) << output;
    const auto [short_code, short_output] =
        Shell(binary.string() + " --lease-ms 50 --data-dir " + (dir.path() / "d").string());
    EXPECT_NE(short_code, 0) << short_output;
    EXPECT_NE(short_output.find("--lease-ms"), std::string::npos) << short_output;
  }
  {
    // A port another socket holds: the server says so and exits 1.
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    ASSERT_GE(fd, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    addr.sin_port = 0;
    ASSERT_EQ(bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    ASSERT_EQ(listen(fd, 1), 0);
    socklen_t len = sizeof addr;
    ASSERT_EQ(getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len), 0);
    const std::string busy = "127.0.0.1:" + std::to_string(ntohs(addr.sin_port));
    Child child({binary.string(), "--grpc-addr", "127.0.0.1:0", "--http-addr", busy, "--data-dir",
                 (dir.path() / "d").string(), "--log-level", "off"});
    const int status = child.Wait(std::chrono::seconds(10));
    close(fd);
    ASSERT_NE(status, -1);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 1);
  }
}

TEST(ServerBinaryTest, RefusesANonLoopbackAddressWithoutTlsAndSaysHow) {
  const std::filesystem::path binary = seaplan::testing::BinDir() / "seaplan-server";
  if (!std::filesystem::exists(binary)) GTEST_SKIP() << binary << " not built";
  TempDir dir;
  auto [code, output] =
      Shell(binary.string() + " --grpc-addr 0.0.0.0:0 --http-addr '' --data-dir " +
            (dir.path() / "data").string());
  EXPECT_EQ(code, 1) << output;
  EXPECT_NE(output.find("without TLS"), std::string::npos) << output;
  EXPECT_NE(output.find("--tls-cert"), std::string::npos) << output;
  // A certificate without its key is a usage error.
  auto [usage, usage_output] = Shell(binary.string() + " --tls-cert x.pem");
  EXPECT_EQ(usage, 2) << usage_output;
}

TEST(ServerBinaryTest, TlsServerAnswersTheCliGivenTheCaCertificate) {
  const std::filesystem::path bin = seaplan::testing::BinDir();
  if (!std::filesystem::exists(bin / "seaplan-server") || !std::filesystem::exists(bin / "seaplan"))
    GTEST_SKIP() << "seaplan-server or seaplan not built in " << bin;
  TempDir dir;
  const std::string d = dir.path().string();
  // A throwaway CA and a server certificate for 127.0.0.1.
  const auto [made, made_output] = Shell(
      "cd '" + d +
      "' && openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 "
      "-nodes -keyout ca.key -out ca.pem -days 2 -subj '/CN=test CA' && "
      "openssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -keyout server.key "
      "-out server.csr -subj '/CN=localhost' && "
      "printf 'subjectAltName=IP:127.0.0.1,DNS:localhost\\n' > server.ext && "
      "openssl x509 -req -in server.csr -CA ca.pem -CAkey ca.key -CAcreateserial -days 2 "
      "-out server.pem -extfile server.ext");
  if (made != 0) {
    if (std::getenv("CI") != nullptr) FAIL() << made_output;
    GTEST_SKIP() << "the openssl command failed: " << made_output;
  }
  const auto port_file = dir.path() / "ports";
  Child child({(bin / "seaplan-server").string(), "--grpc-addr", "127.0.0.1:0", "--http-addr",
               "127.0.0.1:0", "--data-dir", d + "/data", "--port-file", port_file.string(),
               "--log-level", "warn", "--tls-cert", d + "/server.pem", "--tls-key",
               d + "/server.key"});
  int grpc_port = 0, http_port = 0;
  ASSERT_NO_FATAL_FAILURE(WaitForPorts(child, port_file, &grpc_port, &http_port));
  ASSERT_GT(grpc_port, 0);
  // The admin token the server wrote at its first start.
  const std::string server = " --server 127.0.0.1:" + std::to_string(grpc_port) +
                             " --timeout 20 --token-file " + d + "/data/admin.token";
  const std::string cli = (bin / "seaplan").string();
  auto [ok, ok_output] = Shell(cli + server + " --ca-cert " + d + "/ca.pem mission list");
  EXPECT_EQ(ok, 0) << ok_output;
  // Without the CA the CLI speaks plaintext, which the TLS port does not answer.
  auto [plain, plain_output] = Shell(cli + server + " mission list");
  EXPECT_EQ(plain, 3) << plain_output;
  // Unreadable or non-PEM files are usage errors naming the option.
  auto [bad, bad_output] =
      Shell(cli + server + " --ca-cert " + d + "/server.csr.missing mission list");
  EXPECT_EQ(bad, 2) << bad_output;
  EXPECT_NE(bad_output.find("--ca-cert"), std::string::npos) << bad_output;
  auto [sim, sim_output] = Shell(
      (bin / "seaplan-sim").string() + " --server 127.0.0.1:" + std::to_string(grpc_port) +
      " --ca-cert " + d + "/server.ext --scenario " +
      (seaplan::testing::SourceDir() / "examples" / "scenarios" / "case-a.scenario").string() +
      " --report-dir " + d + "/sim");
  EXPECT_NE(sim, 0) << sim_output;
  EXPECT_NE(sim_output.find("not a PEM file"), std::string::npos) << sim_output;
  kill(child.pid(), SIGTERM);
  EXPECT_NE(child.Wait(std::chrono::seconds(30)), -1);
}

}  // namespace
}  // namespace seaplan::server::testing
