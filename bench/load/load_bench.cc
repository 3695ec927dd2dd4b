// Load test of the real seaplan-server binary over loopback gRPC: N
// concurrent clients mixing Plan, PlanRoute, WatchMission and
// ReportFeedback for a bounded time. Prints, per RPC, the calls, successes,
// RESOURCE_EXHAUSTED refusals, other errors and the p50 / p99 latency, the
// same RPC's p50 alone (one client, before the load: the baseline) and the
// ratio, the throughput, and the server's peak RSS (VmHWM). Exit 1 when any
// call failed with anything but RESOURCE_EXHAUSTED.
//
//   seaplan_load_bench [--clients 50] [--duration-s 60] [--missions 4]
//                      [--rate-limit 0] [--bin DIR] [--source DIR]
//
// Loopback only: the server is started here on 127.0.0.1 ephemeral ports
// and stopped at the end; every loop ends at the duration (calls in flight
// then finish within their deadlines).
#include <grpcpp/grpcpp.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "e2e_support.h"
#include "seaplan/bench/percentile.h"
#include "seaplan/v1/chart.grpc.pb.h"
#include "seaplan/v1/mission.grpc.pb.h"
#include "seaplan/v1/planning.grpc.pb.h"
#include "seaplan/v1/route.grpc.pb.h"
#include "token_channel.h"

namespace fs = std::filesystem;
using namespace seaplan;
using Clock = std::chrono::steady_clock;

namespace {

std::string Read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Options {
  int clients = 50;
  double duration_s = 60;
  int missions = 4;
  std::string rate_limit = "0";
  fs::path bin, source = SEAPLAN_BENCH_SOURCE_DIR;
};

// Peak resident set (VmHWM) of process `pid` in MiB; -1 when unreadable.
double PeakRssMiB(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  }
  return -1;
}

// Latencies and outcomes of one RPC.
struct Tally {
  std::vector<double> ok_ms;
  long ok = 0, exhausted = 0, errors = 0;
  std::map<std::string, long> error_kinds;
};

class Recorder {
 public:
  void Add(const std::string& rpc, const grpc::Status& st, double ms) {
    std::lock_guard lock(mu_);
    Tally& t = tallies_[rpc];
    if (st.ok()) {
      ++t.ok;
      t.ok_ms.push_back(ms);
    } else if (st.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED) {
      ++t.exhausted;
    } else {
      ++t.errors;
      // 200 characters: a connection failure names its cause at the end
      // ("failed to connect to all addresses; last error: ...").
      ++t.error_kinds[std::to_string(st.error_code()) + " " + st.error_message().substr(0, 200)];
    }
  }
  std::map<std::string, Tally> Take() {
    std::lock_guard lock(mu_);
    return std::move(tallies_);
  }

 private:
  std::mutex mu_;
  std::map<std::string, Tally> tallies_;
};

using seaplan::bench::Percentile;

const char* kPorts[] = {"port-a", "port-b", "port-c", "port-d", "port-e"};
const double kLat[] = {63.441795, 63.445835, 63.442244, 63.445835, 63.442693};
const double kLon[] = {10.327122, 10.346208, 10.386389, 10.428579, 10.462732};

// The calls of the mix, each timed; `id` makes sequence numbers unique.
class Workload {
 public:
  Workload(const std::shared_ptr<grpc::Channel>& channel, const Options& o, std::string chart_id,
           std::vector<std::pair<std::string, std::string>> missions)
      : planning_(v1::PlanningService::NewStub(channel)),
        routes_(v1::RouteService::NewStub(channel)),
        mission_stub_(v1::MissionService::NewStub(channel)),
        chart_id_(std::move(chart_id)),
        missions_(std::move(missions)) {
    plan_.set_domain(Read(o.source / "examples/fjord/domain.pddl"));
    plan_.set_problem(Read(o.source / "examples/fjord/case-a.pddl"));
    plan_.mutable_options()->mutable_time_limit()->set_seconds(20);
  }

  grpc::Status Plan() {
    grpc::ClientContext ctx;
    Deadline(&ctx, 180);
    v1::PlanResponse resp;
    return planning_->Plan(&ctx, plan_, &resp);
  }
  grpc::Status PlanRoute(int id) {
    grpc::ClientContext ctx;
    Deadline(&ctx, 180);
    v1::PlanRouteRequest req;
    req.set_chart_id(chart_id_);
    const int a = id % 2, b = a + 1;  // port-a -> port-b or port-b -> port-c
    req.mutable_start()->set_latitude_deg(kLat[a]);
    req.mutable_start()->set_longitude_deg(kLon[a]);
    req.mutable_goal()->set_latitude_deg(kLat[b]);
    req.mutable_goal()->set_longitude_deg(kLon[b]);
    req.mutable_options()->set_iterations(30);
    v1::PlanRouteResponse resp;
    return routes_->PlanRoute(&ctx, req, &resp);
  }
  // Opens a watch, waits for its first event (the latency), then reads for
  // a moment as a console would, and leaves.
  grpc::Status Watch(int id) {
    grpc::ClientContext ctx;
    Deadline(&ctx, 30);
    v1::WatchMissionRequest req;
    req.set_mission_id(missions_[static_cast<std::size_t>(id) % missions_.size()].first);
    auto reader = mission_stub_->WatchMission(&ctx, req);
    v1::MissionEvent event;
    if (!reader->Read(&event)) return reader->Finish();
    const auto until = Clock::now() + std::chrono::milliseconds(500);
    std::thread canceller([&] {
      std::this_thread::sleep_until(until);
      ctx.TryCancel();
    });
    while (reader->Read(&event)) {
    }
    canceller.join();
    const grpc::Status st = reader->Finish();
    return st.error_code() == grpc::StatusCode::CANCELLED ? grpc::Status::OK : st;
  }
  grpc::Status Feedback(int id, long n) {
    grpc::ClientContext ctx;
    Deadline(&ctx, 60);
    const auto& [mission_id, vessel] = missions_[static_cast<std::size_t>(id) % missions_.size()];
    v1::ReportFeedbackRequest req;
    req.set_mission_id(mission_id);
    req.set_vessel_id(vessel);
    req.set_sequence_number(static_cast<long long>(id) * 1000000000LL + n);
    auto* f = req.mutable_feedback();
    f->set_kind(v1::Feedback::KIND_POSITION);
    f->set_plan_version(1);
    f->set_mission_time_s(1.0 + static_cast<double>(n) * 0.01);
    f->mutable_state()->mutable_position()->set_latitude_deg(kLat[0]);
    f->mutable_state()->mutable_position()->set_longitude_deg(kLon[0]);
    f->mutable_state()->set_fuel_fraction(1.0);
    v1::ReportFeedbackResponse resp;
    return mission_stub_->ReportFeedback(&ctx, req, &resp);
  }

 private:
  static void Deadline(grpc::ClientContext* ctx, int seconds) {
    ctx->set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(seconds));
  }
  std::unique_ptr<v1::PlanningService::Stub> planning_;
  std::unique_ptr<v1::RouteService::Stub> routes_;
  std::unique_ptr<v1::MissionService::Stub> mission_stub_;
  std::string chart_id_;
  std::vector<std::pair<std::string, std::string>> missions_;
  v1::PlanRequest plan_;
};

const char* kRpcs[] = {"Plan", "PlanRoute", "WatchMission", "ReportFeedback"};

grpc::Status Call(Workload& w, int kind, int id, long n) {
  switch (kind) {
    case 0:
      return w.Plan();
    case 1:
      return w.PlanRoute(id);
    case 2:
      return w.Watch(id);
    default:
      return w.Feedback(id, n);
  }
}

double Ms(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

int Run(const Options& o) {
  const fs::path dir =
      fs::temp_directory_path() / ("seaplan-load-bench-" + std::to_string(getpid()));
  fs::remove_all(dir);
  e2e::ServerProcess server;
  if (!server.Start(o.bin / "seaplan-server", dir, 0,
                    {"--log-level", "error", "--rate-limit", o.rate_limit})) {
    std::fprintf(stderr, "load: seaplan-server did not start from %s (log: %s)\n", o.bin.c_str(),
                 (dir / "server.log").c_str());
    return 1;
  }
  // Every client presents the admin token the server was started with (one
  // caller: the bench runs with --rate-limit 0 by default).
  const std::string& token = seaplan::testing::TestAdminToken();
  auto channel = seaplan::client::CreateChannelWithToken(
      server.address(), grpc::InsecureChannelCredentials(), grpc::ChannelArguments(), token);
  // Setup: the chart for PlanRoute and the missions to watch and feed.
  std::string chart_id;
  {
    auto charts = v1::ChartService::NewStub(channel);
    grpc::ClientContext ctx;
    v1::UploadChartRequest req;
    req.set_name("fjord-entrance");
    auto* file = req.add_files();
    file->set_name("fjord-entrance.geojson");
    file->set_content(Read(o.source / "examples/scenarios/fjord-entrance.geojson"));
    v1::UploadChartResponse resp;
    grpc::Status st = charts->UploadChart(&ctx, req, &resp);
    if (!st.ok()) {
      std::fprintf(stderr, "load: UploadChart: %s\n", st.error_message().c_str());
      return 1;
    }
    chart_id = resp.chart().chart_id();
  }
  std::vector<std::pair<std::string, std::string>> missions;
  {
    auto stub = v1::MissionService::NewStub(channel);
    for (int m = 0; m < o.missions; ++m) {
      v1::CreateMissionRequest req;
      auto* spec = req.mutable_spec();
      spec->set_name("load-" + std::to_string(m));
      spec->set_domain(Read(o.source / "examples/fjord/domain.pddl"));
      spec->set_problem(Read(o.source / "examples/fjord/case-a.pddl"));
      for (int i = 0; i < 5; ++i) {
        auto* l = spec->add_locations();
        l->set_name(kPorts[i]);
        l->mutable_position()->set_latitude_deg(kLat[i]);
        l->mutable_position()->set_longitude_deg(kLon[i]);
      }
      spec->mutable_ship()->set_service_speed_mps(3.6);
      spec->set_vessel_id("load-vessel-" + std::to_string(m));
      grpc::ClientContext ctx;
      v1::Mission mission;
      grpc::Status st = stub->CreateMission(&ctx, req, &mission);
      if (!st.ok()) {
        std::fprintf(stderr, "load: CreateMission: %s\n", st.error_message().c_str());
        return 1;
      }
      missions.emplace_back(mission.mission_id(), spec->vessel_id());
    }
  }
  Workload work(channel, o, chart_id, missions);
  // Baseline: each RPC alone, a few times, before the load.
  std::map<std::string, double> alone_p50;
  for (int kind = 0; kind < 4; ++kind) {
    std::vector<double> ms;
    for (int i = 0; i < 3; ++i) {
      const auto t0 = Clock::now();
      const grpc::Status st = Call(work, kind, 999999, i);
      if (!st.ok()) {
        std::fprintf(stderr, "load: %s alone failed: %s\n", kRpcs[kind],
                     st.error_message().c_str());
        return 1;
      }
      ms.push_back(Ms(t0));
    }
    alone_p50[kRpcs[kind]] = Percentile(ms, 0.5);
  }
  // The load: client i calls RPC i % 4 in a loop until the end. Each
  // client has its own channel (its own connection), as separate ships and
  // consoles would.
  Recorder recorder;
  const auto started = Clock::now();
  const auto end = started + std::chrono::milliseconds(static_cast<long>(o.duration_s * 1000));
  std::vector<std::thread> clients;
  clients.reserve(static_cast<std::size_t>(o.clients));
  for (int id = 0; id < o.clients; ++id) {
    clients.emplace_back([&, id] {
      grpc::ChannelArguments args;
      args.SetInt("seaplan.load.client", id);  // a distinct channel per client
      Workload own(seaplan::client::CreateChannelWithToken(
                       server.address(), grpc::InsecureChannelCredentials(), args, token),
                   o, chart_id, missions);
      const int kind = id % 4;
      for (long n = 0; Clock::now() < end; ++n) {
        const auto t0 = Clock::now();
        const grpc::Status st = Call(own, kind, id, n);
        recorder.Add(kRpcs[kind], st, Ms(t0));
        // A refusal says "later": back off a little, as clients should.
        if (st.error_code() == grpc::StatusCode::RESOURCE_EXHAUSTED)
          std::this_thread::sleep_for(std::chrono::milliseconds(200));
      }
    });
  }
  for (auto& c : clients) c.join();
  const double wall_s = std::chrono::duration<double>(Clock::now() - started).count();
  const double peak_rss = PeakRssMiB(server.pid());
  auto tallies = recorder.Take();
  long total_ok = 0, total_errors = 0, total_exhausted = 0;
  std::printf("load: %d clients, %.1f s (wall %.1f s), server %s, rate limit %s\n", o.clients,
              o.duration_s, wall_s, server.address().c_str(), o.rate_limit.c_str());
  std::printf("%-15s %7s %7s %9s %6s %10s %10s %12s %7s\n", "rpc", "calls", "ok", "exhausted",
              "errors", "p50_ms", "p99_ms", "alone_p50_ms", "p50/alone");
  for (const char* rpc : kRpcs) {
    const Tally& t = tallies[rpc];
    const double p50 = Percentile(t.ok_ms, 0.5);
    std::printf("%-15s %7ld %7ld %9ld %6ld %10.1f %10.1f %12.1f %7.2f\n", rpc,
                t.ok + t.exhausted + t.errors, t.ok, t.exhausted, t.errors, p50,
                Percentile(t.ok_ms, 0.99), alone_p50[rpc],
                alone_p50[rpc] > 0 ? p50 / alone_p50[rpc] : 0.0);
    for (const auto& [kind, count] : t.error_kinds)
      std::printf("    error x%ld: %s\n", count, kind.c_str());
    total_ok += t.ok;
    total_errors += t.errors;
    total_exhausted += t.exhausted;
  }
  std::printf("throughput: %.1f successful calls/s (%ld ok, %ld RESOURCE_EXHAUSTED, %ld errors)\n",
              static_cast<double>(total_ok) / wall_s, total_ok, total_exhausted, total_errors);
  std::printf("server peak RSS: %.1f MiB\n", peak_rss);
  std::printf("errors other than RESOURCE_EXHAUSTED: %ld (%s)\n", total_errors,
              total_errors == 0 ? "pass" : "FAIL");
  std::error_code ec;
  fs::remove_all(dir, ec);
  return total_errors == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  o.bin = fs::path(argv[0]).parent_path();
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i], v = argv[i + 1];
    if (a == "--clients") {
      o.clients = std::clamp(std::atoi(v.c_str()), 1, 200);
    } else if (a == "--duration-s") {
      o.duration_s = std::clamp(std::atof(v.c_str()), 0.1, 600.0);
    } else if (a == "--missions") {
      o.missions = std::clamp(std::atoi(v.c_str()), 1, 50);
    } else if (a == "--rate-limit") {
      o.rate_limit = v;
    } else if (a == "--bin") {
      o.bin = v;
    } else if (a == "--source") {
      o.source = v;
    } else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  return Run(o);
}
