// seaplan-server replicas on PostgreSQL behind nginx, measured end to end
// over gRPC on loopback (real binaries, real nginx with deploy/nginx.conf):
//
//   1. latency per acknowledged ReportFeedback, one server on SQLite vs one
//      on PostgreSQL, taking turns in rounds (ratio from the same run);
//   2. Plan and ReportFeedback throughput and p99 with 1, 2 and 3 replicas
//      behind nginx, `--clients` concurrent callers for `--seconds` each;
//   3. failover: the replica holding a mission's replan lease is killed
//      (SIGKILL), and the time until the mission's next plan version (made
//      by another replica) is measured, `--kills` times.
//
//   build/bin/seaplan_replicas_bench [--seconds 10] [--clients 8] [--kills 3]
//
// PostgreSQL is a throwaway cluster with fsync on (initdb + pg_ctl in the
// temporary folder); nginx is Debian's, run as a child. Every call presents
// the fixtures' admin token, one caller for the servers' rate limiter, so
// the servers run with --rate-limit 0: the bench measures capacity, not the
// per-caller limit. See README.md.
#include <grpcpp/grpcpp.h>
#include <libpq-fe.h>
#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "e2e_support.h"
#include "nginx_balancer.h"
#include "seaplan/bench/percentile.h"
#include "seaplan/storage/testing/postgres_cluster.h"
#include "seaplan/v1/mission.grpc.pb.h"
#include "seaplan/v1/planning.grpc.pb.h"

namespace {

namespace fs = std::filesystem;
using namespace seaplan;
using Clock = std::chrono::steady_clock;

fs::path SourceDir() {
  return SEAPLAN_BENCH_SOURCE_DIR;
}
fs::path BinDir() {
  return SEAPLAN_BENCH_BIN_DIR;
}

using seaplan::bench::Percentile;

double MsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Case A of examples/fjord as a mission (five ports, 3.6 m/s).
v1::MissionSpec FjordSpec(const std::string& vessel) {
  struct Port {
    const char* name;
    double lat, lon;
  };
  // In the fjord's water (the chart of examples/scenarios).
  static const Port kPorts[] = {{"port-a", 63.4418, 10.3271},
                                {"port-b", 63.4458, 10.3462},
                                {"port-c", 63.4422, 10.3864},
                                {"port-d", 63.4458, 10.4286},
                                {"port-e", 63.4427, 10.4627}};
  v1::MissionSpec spec;
  spec.set_name("bench " + vessel);
  spec.set_domain(e2e::ReadWholeFile(SourceDir() / "examples/fjord/domain.pddl"));
  spec.set_problem(e2e::ReadWholeFile(SourceDir() / "examples/fjord/case-a.pddl"));
  for (const Port& p : kPorts) {
    auto* l = spec.add_locations();
    l->set_name(p.name);
    l->mutable_position()->set_latitude_deg(p.lat);
    l->mutable_position()->set_longitude_deg(p.lon);
  }
  spec.mutable_ship()->set_service_speed_mps(3.6);
  spec.set_vessel_id(vessel);
  return spec;
}

absl::StatusOr<v1::Mission> CreateMission(v1::MissionService::Stub& stub,
                                          const std::string& vessel) {
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(120));
  v1::CreateMissionRequest req;
  *req.mutable_spec() = FjordSpec(vessel);
  v1::Mission m;
  grpc::Status st = stub.CreateMission(&ctx, req, &m);
  if (!st.ok()) return absl::UnavailableError(absl::StrCat("CreateMission: ", st.error_message()));
  return m;
}

// A report that changes nothing but the log (the first task started).
grpc::Status Report(v1::MissionService::Stub& stub, const v1::Mission& m, std::int64_t seq,
                    v1::Feedback::Kind kind = v1::Feedback::KIND_TASK_STARTED) {
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
  v1::ReportFeedbackRequest req;
  req.set_mission_id(m.mission_id());
  req.set_vessel_id(m.spec().vessel_id());
  req.set_sequence_number(seq);
  req.mutable_feedback()->set_kind(kind);
  req.mutable_feedback()->set_task_id("t0");
  req.mutable_feedback()->set_plan_version(m.current_version());
  v1::ReportFeedbackResponse resp;
  return stub.ReportFeedback(&ctx, req, &resp);
}

struct Samples {
  std::vector<double> ms;
  int errors = 0;
  double seconds = 0;
};

// `clients` threads call `call(client, i)` for `seconds`; latency per OK call.
template <typename Call>
Samples Load(int clients, double seconds, Call call) {
  std::mutex mu;
  Samples out;
  const auto start = Clock::now();
  const auto until = start + std::chrono::duration<double>(seconds);
  std::vector<std::thread> threads;
  threads.reserve(static_cast<std::size_t>(clients));
  for (int c = 0; c < clients; ++c) {
    threads.emplace_back([&, c] {
      std::vector<double> mine;
      int errors = 0;
      for (int i = 0; Clock::now() < until; ++i) {
        const auto t = Clock::now();
        if (call(c, i).ok()) {
          mine.push_back(MsSince(t));
        } else {
          ++errors;
        }
      }
      std::lock_guard lock(mu);
      out.ms.insert(out.ms.end(), mine.begin(), mine.end());
      out.errors += errors;
    });
  }
  for (auto& t : threads) t.join();
  out.seconds = MsSince(start) / 1000.0;
  return out;
}

void PrintRow(const std::string& what, const Samples& s) {
  std::printf("%-40s %8.1f/s %9.1f %9.1f %7d\n", what.c_str(), s.ms.size() / s.seconds,
              Percentile(s.ms, 0.5), Percentile(s.ms, 0.99), s.errors);
}

class Bench {
 public:
  Bench(fs::path dir, std::string database_url, fs::path nginx)
      : dir_(std::move(dir)), database_url_(std::move(database_url)), nginx_(std::move(nginx)) {}

  bool StartReplica(int i) {
    return replicas_[i].Start(BinDir() / "seaplan-server", dir_ / ("replica" + std::to_string(i)),
                              0,
                              {"--database", database_url_, "--http-addr", "127.0.0.1:0",
                               "--log-level", "error", "--rate-limit", "0"});
  }

  // Section 1: one server on SQLite, one on PostgreSQL, sequential reports
  // in alternating rounds of 50.
  bool SqliteVsPostgres(int reports) {
    e2e::ServerProcess sqlite, postgres;
    if (!sqlite.Start(BinDir() / "seaplan-server", dir_ / "sqlite", 0,
                      {"--log-level", "error", "--rate-limit", "0"}) ||
        !postgres.Start(
            BinDir() / "seaplan-server", dir_ / "postgres", 0,
            {"--database", database_url_, "--log-level", "error", "--rate-limit", "0"})) {
      std::printf("servers did not start\n");
      return false;
    }
    struct Side {
      std::string name;
      std::unique_ptr<v1::MissionService::Stub> stub;
      v1::Mission mission;
      std::vector<double> ms;
    } sides[2] = {{"SQLite (WAL, synchronous=FULL)", nullptr, {}, {}},
                  {"PostgreSQL (fsync on, loopback)", nullptr, {}, {}}};
    e2e::ServerProcess* servers[2] = {&sqlite, &postgres};
    for (int s = 0; s < 2; ++s) {
      sides[s].stub = v1::MissionService::NewStub(
          grpc::CreateChannel(servers[s]->address(), grpc::InsecureChannelCredentials()));
      auto m = CreateMission(*sides[s].stub, "ratio-" + std::to_string(s));
      if (!m.ok()) {
        std::printf("%s\n", m.status().ToString().c_str());
        return false;
      }
      sides[s].mission = *m;
    }
    std::int64_t seq = 1;
    for (int done = 0; done < reports; done += 50) {
      for (auto& side : sides) {
        for (int i = 0; i < 50; ++i) {
          const auto t = Clock::now();
          if (Report(*side.stub, side.mission, seq++).ok()) side.ms.push_back(MsSince(t));
        }
      }
    }
    std::printf("\n1. ReportFeedback latency per acknowledged report, one server, one caller\n");
    std::printf("%-40s %9s %9s %9s\n", "backend", "p50 ms", "p99 ms", "mean ms");
    double p50[2], p99[2];
    for (int s = 0; s < 2; ++s) {
      double mean = 0;
      for (double v : sides[s].ms) mean += v;
      mean /= std::max<std::size_t>(1, sides[s].ms.size());
      p50[s] = Percentile(sides[s].ms, 0.5);
      p99[s] = Percentile(sides[s].ms, 0.99);
      std::printf("%-40s %9.2f %9.2f %9.2f\n", sides[s].name.c_str(), p50[s], p99[s], mean);
    }
    std::printf("PostgreSQL / SQLite: p50 x%.2f, p99 x%.2f\n", p50[1] / p50[0], p99[1] / p99[0]);
    return true;
  }

  // Section 2: n replicas behind nginx.
  bool Throughput(int clients, double seconds) {
    std::printf("\n2. Through nginx, %d callers, %.0f s per row\n", clients, seconds);
    std::printf("%-40s %10s %9s %9s %7s\n", "call, replicas", "calls", "p50 ms", "p99 ms",
                "errors");
    for (int n = 1; n <= 3; ++n) {
      for (int i = 0; i < n; ++i) {
        if (replicas_[i].pid() <= 0 && !StartReplica(i)) {
          std::printf("replica %d did not start\n", i);
          return false;
        }
      }
      ha::NginxBalancer nginx;
      std::vector<ha::ReplicaPorts> ports;
      ports.reserve(static_cast<std::size_t>(n));
      for (int i = 0; i < n; ++i) ports.push_back({replicas_[i].port(), replicas_[i].http_port()});
      if (!nginx.Start(nginx_, SourceDir() / "deploy/nginx.conf", ports,
                       dir_ / ("nginx" + std::to_string(n)))) {
        std::printf("nginx did not start: %s\n", nginx.log().c_str());
        return false;
      }
      auto channel = grpc::CreateChannel(nginx.grpc_address(), grpc::InsecureChannelCredentials());
      auto planning = v1::PlanningService::NewStub(channel);
      v1::PlanRequest plan;
      plan.set_domain(e2e::ReadWholeFile(SourceDir() / "examples/fjord/domain.pddl"));
      plan.set_problem(e2e::ReadWholeFile(SourceDir() / "examples/fjord/case-a.pddl"));
      plan.mutable_options()->set_anytime(false);
      plan.mutable_options()->mutable_time_limit()->set_seconds(10);
      Samples plans = Load(clients, seconds, [&](int, int) {
        grpc::ClientContext ctx;
        ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
        v1::PlanResponse resp;
        return planning->Plan(&ctx, plan, &resp);
      });
      PrintRow(absl::StrCat("Plan (fjord case A), ", n), plans);

      auto missions = v1::MissionService::NewStub(channel);
      std::vector<v1::Mission> mine(clients);
      for (int c = 0; c < clients; ++c) {
        auto m = CreateMission(*missions, absl::StrCat("load-", n, "-", c));
        if (!m.ok()) {
          // Refused (the caller's rate limit after the Plan row's burst):
          // the row is missing, but the replicas ran; printed, not a failure.
          std::printf("%s\n", m.status().ToString().c_str());
          return true;
        }
        mine[c] = *m;
      }
      Samples reports =
          Load(clients, seconds, [&](int c, int i) { return Report(*missions, mine[c], i + 1); });
      PrintRow(absl::StrCat("ReportFeedback, ", n), reports);
    }
    return true;
  }

  // Section 3: kill the lease holder of a replan, time the next version.
  bool Failover(int kills) {
    std::printf("\n3. Kill (SIGKILL) the replica running a mission's replan -> next version\n");
    for (int i = 0; i < 3; ++i) {
      if (replicas_[i].pid() <= 0 && !StartReplica(i)) return false;
    }
    ha::NginxBalancer nginx;
    std::vector<ha::ReplicaPorts> ports;
    for (auto& r : replicas_) ports.push_back({r.port(), r.http_port()});
    if (!nginx.Start(nginx_, SourceDir() / "deploy/nginx.conf", ports, dir_ / "nginx-failover")) {
      std::printf("nginx did not start: %s\n", nginx.log().c_str());
      return false;
    }
    auto stub = v1::MissionService::NewStub(
        grpc::CreateChannel(nginx.grpc_address(), grpc::InsecureChannelCredentials()));
    PGconn* db = PQconnectdb(database_url_.c_str());
    std::vector<double> takeover_ms;
    int attempts = 0;
    while (static_cast<int>(takeover_ms.size()) < kills && attempts++ < 10 * kills) {
      auto m = CreateMission(*stub, absl::StrCat("failover-", attempts));
      if (!m.ok()) break;
      // A failed task: the receiving replica claims the replan and plans.
      if (!Report(*stub, *m, 1, v1::Feedback::KIND_TASK_FAILED).ok()) continue;
      const std::string id = m->mission_id();
      const char* params[] = {id.c_str()};
      int killed = -1;
      Clock::time_point killed_at;
      for (auto until = Clock::now() + std::chrono::seconds(30);
           killed < 0 && Clock::now() < until;) {
        PGresult* r = PQexecParams(
            db,
            "SELECT w.holder, m.current_version FROM mission_work w JOIN missions m ON m.id = "
            "w.mission_id WHERE w.mission_id = $1 AND w.holder IS NOT NULL",
            1, nullptr, params, nullptr, nullptr, 0);
        if (PQresultStatus(r) == PGRES_TUPLES_OK && PQntuples(r) == 1 &&
            std::atoi(PQgetvalue(r, 0, 1)) == 1) {
          std::smatch match;
          const std::string holder = PQgetvalue(r, 0, 0);
          if (std::regex_match(holder, match, std::regex("[^:]*:([0-9]+):.*"))) {
            for (int i = 0; i < 3; ++i) {
              if (replicas_[i].pid() == std::stoi(match[1])) {
                replicas_[i].Kill();
                killed_at = Clock::now();
                killed = i;
              }
            }
          }
        }
        const bool replanned = PQresultStatus(r) == PGRES_TUPLES_OK && PQntuples(r) == 0;
        PQclear(r);
        if (replanned && killed < 0) {
          // Done before it was seen held (a fast replan): try another mission.
          PGresult* v = PQexecParams(db, "SELECT current_version FROM missions WHERE id = $1", 1,
                                     nullptr, params, nullptr, nullptr, 0);
          const bool done = PQntuples(v) == 1 && std::atoi(PQgetvalue(v, 0, 0)) >= 2;
          PQclear(v);
          if (done) break;
        }
      }
      if (killed < 0) continue;
      for (auto until = Clock::now() + std::chrono::seconds(120); Clock::now() < until;) {
        PGresult* v = PQexecParams(db, "SELECT current_version FROM missions WHERE id = $1", 1,
                                   nullptr, params, nullptr, nullptr, 0);
        const bool done = PQntuples(v) == 1 && std::atoi(PQgetvalue(v, 0, 0)) >= 2;
        PQclear(v);
        if (done) {
          takeover_ms.push_back(MsSince(killed_at));
          std::printf("kill %zu: replica %d killed mid-replan, version 2 after %.0f ms\n",
                      takeover_ms.size(), killed + 1, takeover_ms.back());
          break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
      }
      (void)StartReplica(killed);  // same ports: nginx sends to it again
    }
    PQfinish(db);
    if (!takeover_ms.empty()) {
      std::printf("kill -> next version: median %.0f ms, max %.0f ms (%zu kills, lease 5 s)\n",
                  Percentile(takeover_ms, 0.5), Percentile(takeover_ms, 1.0), takeover_ms.size());
    } else {
      std::printf("no replan was caught running (each finished before it was seen)\n");
    }
    return true;
  }

 private:
  fs::path dir_;
  std::string database_url_;
  fs::path nginx_;
  e2e::ServerProcess replicas_[3];
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("seaplan-server replicas on PostgreSQL behind nginx: throughput, latency, failover");
  double seconds = 10;
  int clients = 8, kills = 3, reports = 1000;
  app.add_option("--seconds", seconds, "duration of each throughput row");
  app.add_option("--clients", clients, "concurrent callers in the throughput rows");
  app.add_option("--reports", reports, "reports per backend in the SQLite/PostgreSQL ratio");
  app.add_option("--kills", kills, "replicas killed mid-replan in the failover figure");
  CLI11_PARSE(app, argc, argv);

  const fs::path nginx = ha::FindNginx();
  if (nginx.empty()) {
    std::fprintf(stderr, "nginx not installed (apt-get install nginx)\n");
    return 77;
  }
  storage::testing::PostgresClusterOptions options;
  options.fsync = true;
  auto cluster = storage::testing::TemporaryPostgresCluster::Start(options);
  if (!cluster.ok()) {
    std::fprintf(stderr, "%s\n", cluster.status().ToString().c_str());
    return absl::IsNotFound(cluster.status()) ? 77 : 1;
  }
  auto url = (*cluster)->CreateDatabase();
  if (!url.ok()) {
    std::fprintf(stderr, "%s\n", url.status().ToString().c_str());
    return 1;
  }
  char tmpl[] = "/tmp/seaplan-replicas-bench-XXXXXX";
  if (mkdtemp(tmpl) == nullptr) return 1;
  const fs::path dir = tmpl;
  fs::permissions(dir, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                           fs::perms::others_read | fs::perms::others_exec);
  // A section whose servers or nginx do not start fails the run (after the
  // others ran): the figures it prints would be missing, not slow.
  bool ok = true;
  {
    Bench bench(dir, *url, nginx);
    ok = bench.SqliteVsPostgres(reports) && ok;
    ok = bench.Throughput(clients, seconds) && ok;
    ok = bench.Failover(kills) && ok;
  }
  std::error_code ec;
  fs::remove_all(dir, ec);
  return ok ? 0 : 1;
}
