// Mission loop latency benchmark.
//
//   seaplan_mission_bench [--source DIR] [--bin DIR] [--iterations N]
//
// 1. Engine, in-process: case B replan (regenerate the problem from the
//    executed prefix + ship position, plan with seaplan::search, refine,
//    parse), N times: p50 / p95 / max in ms.
// 2. Server over gRPC (needs the mission engine wired into seaplan-server):
//    starts seaplan-server on a loopback ephemeral port, creates the case A
//    mission, then N times posts a TASK_FAILED feedback and measures the time
//    until the new version arrives on the WatchMission stream. Target:
//    p95 < 100 ms.
// 3. Wall time of the whole case C simulation (seaplan-sim, executor fuel).
// Exits 1 when a part fails (no plan, the server does not start or answer,
// no new version, case C does not complete), so that the smoke run catches it.
#include <grpcpp/grpcpp.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "client_token.h"
#include "token_channel.h"
#include "seaplan/mission/mission_planner.h"
#include "seaplan/search/planner.h"
#include "seaplan/v1/mission.grpc.pb.h"

namespace fs = std::filesystem;
using namespace seaplan;
using Clock = std::chrono::steady_clock;

namespace {

std::string Read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The nearest-rank `p` quantile of sorted, non-empty `ms`.
double Quantile(const std::vector<double>& ms, double p) {
  const auto rank = static_cast<size_t>(std::lround(p * static_cast<double>(ms.size() - 1)));
  return ms[std::min(ms.size() - 1, rank)];
}

void PrintStats(const char* what, std::vector<double> ms) {
  if (ms.empty()) return;
  std::sort(ms.begin(), ms.end());
  auto pct = [&](double p) { return Quantile(ms, p); };
  std::printf("%-48s n=%zu p50=%.2f ms p95=%.2f ms max=%.2f ms\n", what, ms.size(), pct(0.5),
              pct(0.95), ms.back());
}

mission::TemporalPlanner Planner() {
  return [](std::string_view d, std::string_view p,
            const StopToken& stop) -> StatusOr<mission::PlannerOutcome> {
    search::PlannerOptions o;
    o.time_limit_s = 10;
    o.anytime = false;
    search::PlanResult r = search::Solve(d, p, o, stop);
    mission::PlannerOutcome out;
    out.solved = r.status == search::PlanStatus::kSolvedSatisficing ||
                 r.status == search::PlanStatus::kSolvedOptimally;
    out.plan = r.plan;
    out.status = search::ToString(r.status);
    return out;
  };
}

bool EngineBench(const fs::path& src, int n) {
  mission::MissionDefinition def;
  def.domain = Read(src / "examples/fjord/domain.pddl");
  def.problem = Read(src / "examples/fjord/case-a.pddl");
  // Chart-free positions: 20 m per PDDL unit along a line.
  def.locations = {{"port-a", {0, 0}},
                   {"port-b", {1040, 0}},
                   {"port-c", {3080, 0}},
                   {"port-d", {5220, 0}},
                   {"port-e", {6960, 0}}};
  auto router = mission::StraightLineRouter(3.6);
  auto v1 = mission::PlanInitialVersion(def, Planner(), router, StopToken(), nullptr);
  if (!v1.ok()) {
    std::printf("engine: initial plan failed: %s\n", v1.status().ToString().c_str());
    return false;
  }
  std::vector<double> ms;
  for (int i = 0; i < n; ++i) {
    mission::ReplanInput in{
        "bench", 100.0, {v1->tasks[0].id}, {v1->tasks[1].id}, {{300, 420}, 0.9}};
    auto t0 = Clock::now();
    auto r = mission::Replan(def, *v1, def.locations, in, Planner(), router, StopToken(), nullptr);
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    if (!r.ok() || !r->version) {
      std::printf("engine: replan failed: %s\n",
                  r.ok() ? "no version" : r.status().ToString().c_str());
      return false;
    }
  }
  PrintStats("engine replan, case B (in-process)", ms);
  return true;
}

struct Server {
  pid_t pid = -1;
  std::string address;
  ~Server() {
    if (pid > 0) {
      kill(pid, SIGTERM);
      int st;
      waitpid(pid, &st, 0);
    }
  }
};

bool StartServer(const fs::path& bin, const fs::path& dir, Server* s) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  fs::path ports = dir / "ports";
  s->pid = fork();
  if (s->pid == 0) {
    std::string b = (bin / "seaplan-server").string(), d = (dir / "data").string(),
                p = ports.string();
    execl(b.c_str(), b.c_str(), "--grpc-addr", "127.0.0.1:0", "--http-addr", "", "--data-dir",
          d.c_str(), "--port-file", p.c_str(), "--log-level", "error", static_cast<char*>(nullptr));
    _exit(127);
  }
  for (int i = 0; i < 200; ++i) {
    std::ifstream in(ports);
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("grpc=", 0) == 0) {
        s->address = "127.0.0.1:" + line.substr(5);
        return true;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

bool ServerBench(const fs::path& src, const fs::path& bin, int n) {
  Server server;
  fs::path dir = fs::temp_directory_path() / ("seaplan-mission-bench-" + std::to_string(getpid()));
  if (!StartServer(bin, dir, &server)) {
    std::printf("server: failed (seaplan-server did not start from %s)\n", bin.c_str());
    return false;
  }
  // The admin token the server wrote at its first start, for this process
  // and for seaplan-sim.
  const fs::path token_file = dir / "data" / "admin.token";
  auto token = client::ResolveToken("", token_file.string());
  if (!token.ok()) {
    std::printf("server: failed (%s)\n", std::string(token.status().message()).c_str());
    return false;
  }
  auto channel = client::CreateChannelWithToken(server.address, grpc::InsecureChannelCredentials(),
                                                grpc::ChannelArguments(), *token);
  auto stub = v1::MissionService::NewStub(channel);
  v1::CreateMissionRequest req;
  auto* spec = req.mutable_spec();
  spec->set_name("bench-case-a");
  spec->set_domain(Read(src / "examples/fjord/domain.pddl"));
  spec->set_problem(Read(src / "examples/fjord/case-a.pddl"));
  const double lat[] = {63.4418, 63.4458, 63.4422, 63.4458, 63.4427};
  const double lon[] = {10.3271, 10.3462, 10.3864, 10.4286, 10.4627};
  const char* names[] = {"port-a", "port-b", "port-c", "port-d", "port-e"};
  for (int i = 0; i < 5; ++i) {
    auto* l = spec->add_locations();
    l->set_name(names[i]);
    l->mutable_position()->set_latitude_deg(lat[i]);
    l->mutable_position()->set_longitude_deg(lon[i]);
  }
  spec->mutable_ship()->set_service_speed_mps(3.6);
  spec->set_vessel_id("bench");
  v1::Mission mission;
  {
    grpc::ClientContext ctx;
    grpc::Status s = stub->CreateMission(&ctx, req, &mission);
    if (!s.ok()) {
      std::printf("server: CreateMission failed: %s\n", s.error_message().c_str());
      return false;
    }
  }
  grpc::ClientContext wctx;
  v1::WatchMissionRequest wreq;
  wreq.set_mission_id(mission.mission_id());
  auto reader = stub->WatchMission(&wctx, wreq);
  v1::MissionEvent ev;
  v1::PlanVersion current;
  while (reader->Read(&ev)) {
    if (ev.has_plan_version()) {
      current = ev.plan_version();
      break;
    }
  }
  std::vector<double> ms;
  for (int i = 0; i < n; ++i) {
    std::string move;
    for (const auto& t : current.tasks()) {
      if (t.kind() == v1::Task::KIND_MOVE) {
        move = t.task_id();
        break;
      }
    }
    if (move.empty()) break;
    v1::ReportFeedbackRequest fb;
    fb.set_mission_id(mission.mission_id());
    fb.set_vessel_id("bench");
    fb.set_sequence_number(i + 1);
    auto* f = fb.mutable_feedback();
    f->set_kind(v1::Feedback::KIND_TASK_FAILED);
    f->set_task_id(move);
    f->set_plan_version(current.version());
    f->set_mission_time_s(100.0 + i);
    f->mutable_state()->mutable_position()->set_latitude_deg(63.4460);
    f->mutable_state()->mutable_position()->set_longitude_deg(10.3330);
    f->mutable_state()->set_fuel_fraction(0.9);
    auto t0 = Clock::now();
    v1::ReportFeedbackResponse resp;
    grpc::ClientContext ctx;
    if (!stub->ReportFeedback(&ctx, fb, &resp).ok() || !resp.replan_triggered()) break;
    bool got = false;
    while (reader->Read(&ev)) {
      if (ev.has_plan_version() && ev.plan_version().version() > current.version()) {
        current = ev.plan_version();
        got = true;
        break;
      }
    }
    if (!got) break;
    ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  wctx.TryCancel();
  PrintStats("server: ReportFeedback -> new version on watch", ms);
  const bool all_versions = static_cast<int>(ms.size()) == n;
  if (!all_versions) std::printf("server: failed (%zu of %d new versions)\n", ms.size(), n);
  if (!ms.empty()) {
    std::sort(ms.begin(), ms.end());
    const double p95 = Quantile(ms, 0.95);
    std::printf("target p95 < 100 ms: %s\n", p95 < 100 ? "met" : "NOT met");
  }
  // Whole case C simulation.
  std::string cmd = (bin / "seaplan-sim").string() + " --server " + server.address +
                    " --token-file " + token_file.string() +
                    " --scenario " + (src / "examples/scenarios/case-c.scenario").string() +
                    " --report-dir " + (dir / "case-c").string() + " > " +
                    (dir / "case-c.out").string() + " 2>&1";
  auto t0 = Clock::now();
  int st = std::system(cmd.c_str());
  double wall = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf("case C simulation: exit %d, wall time %.2f s (as fast as possible)\n",
              WIFEXITED(st) ? WEXITSTATUS(st) : -1, wall);
  return all_versions && WIFEXITED(st) && WEXITSTATUS(st) == 0;
}

}  // namespace

int main(int argc, char** argv) {
  fs::path src = SEAPLAN_BENCH_SOURCE_DIR, bin = fs::path(argv[0]).parent_path();
  int n = 30;
  for (int i = 1; i + 1 < argc; i += 2) {
    std::string a = argv[i];
    if (a == "--source")
      src = argv[i + 1];
    else if (a == "--bin")
      bin = argv[i + 1];
    else if (a == "--iterations")
      n = std::max(1, std::atoi(argv[i + 1]));
  }
  const bool engine_ok = EngineBench(src, n);
  const bool server_ok = ServerBench(src, bin, n);
  return engine_ok && server_ok ? 0 : 1;
}
