// seaplan-sim: plays the onboard side of a mission against a seaplan server,
// over gRPC only.
//
//   seaplan-sim --server 127.0.0.1:50051 --scenario examples/scenarios/case-b.scenario
//               [--mission-id ID (attach)] [--time-factor N] [--report-dir DIR]
//               [--replan-timeout-s S] [--max-mission-time-s S] [--log-level LEVEL]
//               [--journal FILE] [--shore-wait-s S]
//   (flags parsed with CLI11; --help lists them)
//
// Creates the mission of the scenario (uploading its chart first when it has
// one) or attaches to an existing one, watches it, executes its tasks on the
// simulated ship, posts feedback, follows replans and writes the mission
// report (report.json, trajectory.svg, gantt.svg). At the end it prints the
// navigation log (mission time, source, message per line) and the report's path.
//
// A shore outage does not stop the ship: reports go to an fsync'd journal
// first and are sent in order when the server answers (sim_client.h); the
// current plan version is executed meanwhile, and once it has run out the
// sim waits up to --shore-wait-s for the shore to hear everything (and for
// a replan the backlog triggers) before giving up with exit code 3.
//
// Exit codes: 0 mission completed; 1 error (bad flags, scenario, I/O, RPC);
// 2 mission failed or cancelled; 3 timed out waiting for the server;
// 4 the server does not plan missions (CreateMission UNIMPLEMENTED).
#include <CLI/CLI.hpp>
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

#include "absl/strings/str_cat.h"
#include "client_token.h"
#include "executor.h"
#include "report.h"
#include "scenario.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/log.h"
#include "seaplan/common/wall_clock.h"
#include "seaplan/convert/mission_convert.h"
#include "sim_client.h"
#include "tls_channel.h"

namespace {

using namespace seaplan;

constexpr double kDeg = M_PI / 180.0;

struct Flags {
  std::string server = "127.0.0.1:50051";
  std::string token;
  std::string token_file;
  client::TlsFiles tls;
  std::string scenario;
  std::string mission_id;
  std::string report_dir = "sim-report";
  double time_factor = -1;  // < 0: from the scenario (0 = as fast as possible)
  double replan_timeout_s = 120;
  double max_mission_time_s = 20000;
  std::string log_level = "warn";
  std::string colav = "sbmpc";
  uint64_t seed = 0;
  bool former_autopilot = false;
  std::string journal;  // empty: <report_dir>/feedback.journal
  double shore_wait_s = 600;
};

// Waits until every journaled report is acknowledged; false when the shore
// stayed unreachable until `deadline`.
bool FlushBacklog(sim::SimClient& client, std::chrono::steady_clock::time_point deadline) {
  while (client.backlog() > 0) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    client.WaitSent(std::chrono::milliseconds(200));
    // WaitSent returns at once while the shore is unreachable.
    if (client.shore_unreachable()) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  return true;
}

std::string ReadAll(const std::string& path, bool* ok) {
  std::ifstream in(path, std::ios::binary);
  *ok = static_cast<bool>(in);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

v1::MissionSpec MakeSpec(const sim::Scenario& s, const std::string& domain,
                         const std::string& problem, const std::string& chart_id,
                         const sim::ExecutorConfig& cfg, const chart::LocalFrame& frame) {
  v1::MissionSpec spec;
  spec.set_name(s.name);
  spec.set_domain(domain);
  spec.set_problem(problem);
  spec.set_chart_id(chart_id);
  for (const auto& [name, ll] : s.locations) {
    auto* l = spec.add_locations();
    l->set_name(name);
    l->mutable_position()->set_latitude_deg(ll.lat_deg);
    l->mutable_position()->set_longitude_deg(ll.lon_deg);
  }
  spec.mutable_ship()->set_name(s.vessel_id);
  spec.mutable_ship()->set_service_speed_mps(s.service_speed_mps);
  chart::LatLon start = frame.ToLatLon({cfg.start.east_m, cfg.start.north_m});
  auto* st = spec.mutable_initial_state();
  st->mutable_position()->set_latitude_deg(start.lat_deg);
  st->mutable_position()->set_longitude_deg(start.lon_deg);
  st->set_heading_deg(s.start_heading_deg);
  st->set_fuel_fraction(s.initial_fuel);
  st->set_mode(v1::MSO_MODE_PTO);
  spec.mutable_environment()->set_wind_speed_mps(s.wind_speed_mps);
  spec.mutable_environment()->set_wind_from_deg(s.wind_from_deg);
  spec.mutable_environment()->set_current_speed_mps(s.current_speed_mps);
  spec.mutable_environment()->set_current_from_deg(s.current_from_deg);
  for (const auto& [action, d] : s.port_operations) {
    auto* p = spec.add_port_operations();
    p->set_action(action);
    p->set_duration_s(d);
  }
  spec.mutable_replan_policy()->set_fuel_threshold_fraction(s.fuel_threshold);
  spec.mutable_replan_policy()->set_position_deviation_m(s.position_deviation_m);
  spec.mutable_replan_policy()->set_delay_tolerance_s(s.delay_tolerance_s);
  spec.mutable_planner_options()->mutable_time_limit()->set_seconds(
      static_cast<int64_t>(s.planner_time_limit_s));
  spec.mutable_planner_options()->set_max_expansions(s.planner_max_expansions);
  spec.set_vessel_id(s.vessel_id);
  spec.set_ship_object(s.ship_object);
  return spec;
}

// The ship's location in the PDDL problem: "(at <ship> <loc>)" in :init.
std::string ShipLocation(const std::string& problem, const std::string& ship) {
  if (ship.empty()) return "";
  std::string needle = "(at " + ship + " ";
  size_t p = problem.find(needle);
  if (p == std::string::npos) return "";
  size_t e = problem.find(')', p);
  return problem.substr(p + needle.size(), e - p - needle.size());
}

// Degrees in [0, 360) clockwise from north.
double CompassDeg(double rad) {
  const double deg = std::fmod(rad / kDeg, 360.0);
  return deg < 0 ? deg + 360 : deg;
}

void FillShipState(const sim::FeedbackOut& fb, const chart::LocalFrame& frame, v1::ShipState* st) {
  chart::LatLon ll = frame.ToLatLon({fb.position.east_m, fb.position.north_m});
  st->mutable_position()->set_latitude_deg(ll.lat_deg);
  st->mutable_position()->set_longitude_deg(ll.lon_deg);
  st->set_heading_deg(CompassDeg(fb.heading_rad));
  st->set_speed_mps(fb.speed_mps);
  st->set_fuel_fraction(fb.fuel_fraction);
  st->set_mode(convert::MsoModeToProto(fb.mode));
  st->set_collision_avoidance_active(fb.collision_avoidance_active);
}

// The live picture: the ship and the traffic it tracks (AIS-like: the
// scripted vessels' positions, course and speed over ground).
v1::ReportVesselStateRequest VesselState(const sim::Executor& executor,
                                         const std::string& mission_id,
                                         const std::string& vessel_id,
                                         const chart::LocalFrame& frame) {
  v1::ReportVesselStateRequest req;
  req.set_mission_id(mission_id);
  req.set_vessel_id(vessel_id);
  req.set_mission_time_s(executor.time_s());
  FillShipState(executor.CurrentState(), frame, req.mutable_state());
  for (const sim::TrafficVessel& vessel : executor.traffic()) {
    const sim::Kinematics k = vessel.At(executor.time_s());
    v1::TrackedTarget* t = req.add_targets();
    t->set_target_id(vessel.name);
    t->set_kind(vessel.kind);
    const chart::LatLon ll = frame.ToLatLon({k.position.east_m, k.position.north_m});
    t->mutable_position()->set_latitude_deg(ll.lat_deg);
    t->mutable_position()->set_longitude_deg(ll.lon_deg);
    // Course over ground: atan2(east, north).
    t->set_course_deg(CompassDeg(std::atan2(k.velocity.east_m, k.velocity.north_m)));
    t->set_speed_mps(std::hypot(k.velocity.east_m, k.velocity.north_m));
  }
  return req;
}

}  // namespace

int main(int argc, char** argv) {
  Flags f;
  CLI::App app{
      "seaplan-sim: simulate the onboard side of a mission against a seaplan server (gRPC)"};
  app.add_option("--server", f.server, "seaplan-server gRPC address HOST:PORT")
      ->capture_default_str();
  app.add_option("--token", f.token,
                 "API token to present (else --token-file, env SEAPLAN_TOKEN or "
                 "SEAPLAN_TOKEN_FILE); a vessel token may only sail its own vessel's missions");
  app.add_option("--token-file", f.token_file, "file whose first line is the API token");
  client::AddTlsOptions(app, &f.tls);
  app.add_option("--scenario", f.scenario, "scenario file (examples/scenarios/*.scenario)")
      ->required();
  app.add_option("--mission-id", f.mission_id,
                 "attach to this existing mission instead of creating one");
  app.add_option("--report-dir", f.report_dir, "folder for report.json, trajectory.svg, gantt.svg")
      ->capture_default_str();
  app.add_option(
         "--time-factor", f.time_factor,
         "run N times faster than real time (0 = as fast as possible; default: the scenario's)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--replan-timeout-s", f.replan_timeout_s,
                 "wait this long for a (new) plan version")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--max-mission-time-s", f.max_mission_time_s,
                 "give up after this much mission time (exit 3)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--log-level", f.log_level, "debug, info, warn, error or off")
      ->capture_default_str();
  app.add_option("--colav", f.colav,
                 "collision avoidance: sbmpc (scenario-based MPC) or vo (velocity obstacles)")
      ->check(CLI::IsMember({"sbmpc", "vo"}))
      ->capture_default_str();
  app.add_flag("--former-autopilot", f.former_autopilot,
               "steer with the heading control from before engine/colav (PID on the error, kp 2, "
               "kd 200), for comparisons");
  app.add_option("--seed", f.seed,
                 "perturb the traffic's timing and the wind with this seed (0: as scripted)")
      ->capture_default_str();
  app.add_option("--journal", f.journal,
                 "feedback journal (reports not yet acknowledged by the server survive a restart "
                 "here; default: <report-dir>/feedback.journal)");
  app.add_option("--shore-wait-s", f.shore_wait_s,
                 "once the plan has run out, wait this long for an unreachable server (exit 3)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.footer(
      "Exit codes: 0 mission completed; 1 error (bad flags, scenario, I/O, RPC); 2 mission failed "
      "or\n"
      "cancelled; 3 timed out waiting for the server; 4 the server does not plan missions.");
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);  // 0
  } catch (const CLI::ParseError& e) {
    app.exit(e);  // prints the error and the usage hint
    return 1;     // bad flags: exit code 1, as documented
  }
  log::Level level;
  if (!log::ParseLevel(f.log_level, &level)) {
    std::fprintf(stderr,
                 "seaplan-sim: --log-level: unknown level '%s' (debug, info, warn, error, off)\n",
                 f.log_level.c_str());
    return 1;
  }
  log::SetLevel(level);
  // Bad TLS files are bad flags: said before any work.
  auto credentials = client::ChannelCredentials(f.tls);
  if (!credentials.ok()) {
    std::fprintf(stderr, "seaplan-sim: %s\n", std::string(credentials.status().message()).c_str());
    return 1;
  }

  auto scenario = sim::LoadScenario(f.scenario);
  if (!scenario.ok()) {
    std::fprintf(stderr, "seaplan-sim: %s\n", std::string(scenario.status().message()).c_str());
    return 1;
  }
  const char* shared_env = std::getenv("SEAPLAN_SHARED");
  const std::string shared = shared_env ? shared_env : "";
  auto fail = [](const absl::Status& s) {
    std::fprintf(stderr, "seaplan-sim: %s\n", s.ToString().c_str());
    return 1;
  };
  auto domain_path = sim::ResolvePath(*scenario, scenario->domain_path, shared);
  auto problem_path = sim::ResolvePath(*scenario, scenario->problem_path, shared);
  if (!domain_path.ok()) return fail(domain_path.status());
  if (!problem_path.ok()) return fail(problem_path.status());
  bool ok1 = false, ok2 = false;
  std::string domain = ReadAll(*domain_path, &ok1), problem = ReadAll(*problem_path, &ok2);
  if (!ok1 || !ok2)
    return fail(
        absl::NotFoundError(absl::StrCat("cannot read ", ok1 ? *problem_path : *domain_path)));

  // Frame and obstacles (for the plot) from the chart when there is one.
  chart::LocalFrame frame = chart::LocalFrame::ForCentre(scenario->locations.front().second);
  sim::Rings rings;
  std::string chart_bytes, chart_file;
  if (!scenario->chart_path.empty()) {
    auto p = sim::ResolvePath(*scenario, scenario->chart_path, shared);
    if (!p.ok()) return fail(p.status());
    chart_file = *p;
    bool ok = false;
    chart_bytes = ReadAll(chart_file, &ok);
    if (!ok) return fail(absl::NotFoundError(absl::StrCat("cannot read chart ", chart_file)));
    chart::ChartOptions copt;
    copt.safety_buffer_m = 0.0;
    copt.simplify_tolerance_m = 0.0;
    auto map = chart::LoadChartFile(chart_file, copt);
    if (map.ok()) {
      frame = map->frame();
      for (const chart::Polygon& poly : map->polygons()) {
        std::vector<EastNorth> ring;
        for (const EastNorth& q : poly.outer) ring.push_back({q.east_m, q.north_m});
        rings.push_back(std::move(ring));
      }
    } else {
      log::Warn("chart {} not loaded for the plot: {}", chart_file, map.status().ToString());
    }
  }

  auto cfg =
      sim::MakeExecutorConfig(*scenario, frame, ShipLocation(problem, scenario->ship_object));
  if (!cfg.ok()) return fail(cfg.status());
  cfg->land = rings;  // the unbuffered land, for the collision avoidance
  cfg->avoidance.policy =
      f.colav == "vo" ? colav::Policy::kVelocityObstacle : colav::Policy::kScenarioMpc;
  if (f.seed != 0) sim::PerturbConfig(f.seed, &*cfg);
  if (f.former_autopilot) {
    cfg->autopilot.heading_kp = 2.0;
    cfg->autopilot.heading_kd_s = 200.0;
    cfg->autopilot.derivative_on_error = true;
  }
  auto executor = sim::Executor::Create(*cfg);
  if (!executor.ok()) return fail(executor.status());
  mission::LocationTable locations = sim::LocalLocations(*scenario, frame);

  absl::StatusOr<std::string> token = client::ResolveToken(f.token, f.token_file);
  if (!token.ok()) return fail(token.status());
  sim::SimClient client(f.server, *credentials, *token);
  {
    std::error_code ec;
    std::filesystem::create_directories(f.report_dir, ec);
    if (ec) return fail(absl::UnavailableError(absl::StrCat("cannot create ", f.report_dir)));
    const std::string journal =
        f.journal.empty() ? (std::filesystem::path(f.report_dir) / "feedback.journal").string()
                          : f.journal;
    if (absl::Status st = client.StartUplink(journal); !st.ok()) return fail(st);
  }
  std::string mission_id = f.mission_id;
  if (mission_id.empty()) {
    std::string chart_id;
    if (!chart_bytes.empty()) {
      auto chart =
          client.UploadChart(scenario->name + "-chart",
                             std::filesystem::path(chart_file).filename().string(), chart_bytes);
      if (!chart.ok()) return fail(chart.status());
      chart_id = chart->chart_id();
    }
    v1::MissionSpec spec = MakeSpec(*scenario, domain, problem, chart_id, *cfg, frame);
    const std::string request_id = absl::StrCat(
        scenario->name, "-", std::chrono::system_clock::now().time_since_epoch().count());
    auto m = client.CreateMission(spec, request_id);
    if (!m.ok() && absl::IsUnimplemented(m.status()) && !spec.chart_id().empty()) {
      // A server that plans missions but cannot route over a chart yet:
      // fall back to straight-line legs (the chart still draws the plot).
      std::fprintf(stderr,
                   "seaplan-sim: warning: %s; retrying without the chart (straight-line legs)\n",
                   std::string(m.status().message()).c_str());
      executor->Log("server cannot route over the chart: straight-line legs");
      spec.clear_chart_id();
      m = client.CreateMission(spec, request_id + "-nochart");
    }
    if (!m.ok()) {
      std::fprintf(stderr, "seaplan-sim: CreateMission: %s\n", m.status().ToString().c_str());
      return absl::IsUnimplemented(m.status()) ? 4 : 1;
    }
    mission_id = m->mission_id();
  }
  std::printf("mission %s\n", mission_id.c_str());
  std::fflush(stdout);
  executor->mutable_report().mission_id = mission_id;
  executor->mutable_report().scenario = scenario->name;

  // A token that may not sail this mission (another vessel's, revoked) is
  // an error at once, not an outage to ride out.
  if (auto m = client.GetMission(mission_id);
      !m.ok() && (absl::IsPermissionDenied(m.status()) || absl::IsUnauthenticated(m.status()))) {
    return fail(m.status());
  }
  client.StartWatch(mission_id);
  const auto replan_timeout =
      std::chrono::milliseconds(static_cast<int64_t>(f.replan_timeout_s * 1000));
  auto first = client.WaitForVersion(0, replan_timeout);
  if (!first) {
    std::fprintf(stderr, "seaplan-sim: no plan version for mission %s\n", mission_id.c_str());
    return client.terminal_state() == v1::MISSION_STATE_UNSPECIFIED ? 3 : 2;
  }
  executor->SetPlan(convert::PlanVersionFromProto(*first, frame));
  double current_origin = first->mission_time_origin_s();

  const double time_factor = f.time_factor >= 0 ? f.time_factor : scenario->time_factor;
  const auto wall_start = std::chrono::steady_clock::now();
  int exit_code = 0;
  std::vector<sim::FeedbackOut> out;
  auto next_vessel_state = std::chrono::steady_clock::time_point{};
  bool vessel_state_warned = false;
  auto drain_log = [&] {
    for (const v1::LogEvent& e : client.TakeLogEvents()) {
      executor->mutable_report().log.Add(e.mission_time_s(), e.message(), e.source());
    }
  };
  const auto shore_wait = std::chrono::milliseconds(static_cast<int64_t>(f.shore_wait_s * 1000));
  bool offline = false;  // as last noted in the navigation log
  while (true) {
    if (auto v = client.PollVersion(executor->plan_version())) {
      // A version planned from the same state as the one under way (two
      // triggers of one situation) is a duplicate: keep executing.
      if (v->mission_time_origin_s() > current_origin + 1e-6) {
        current_origin = v->mission_time_origin_s();
        executor->SetPlan(convert::PlanVersionFromProto(*v, frame));
      } else {
        executor->Log(absl::StrCat("ignored plan version ", v->version(),
                                   " (planned from the same state as version ",
                                   executor->plan_version(), ")"));
      }
    }
    // Nothing left to execute (done, or a task failed): the shore must hear
    // every report before it can judge the mission or replan.
    const bool plan_ran_out = executor->Finished() || executor->WaitingForPlan();
    if (plan_ran_out) {
      if (!FlushBacklog(client, std::chrono::steady_clock::now() + shore_wait)) {
        std::fprintf(stderr,
                     "seaplan-sim: server unreachable for %.0f s after the plan ran out; %zu "
                     "reports unsent (kept in the journal)\n",
                     f.shore_wait_s, client.backlog());
        exit_code = 3;
        break;
      }
    } else {
      if (executor->time_s() > f.max_mission_time_s) {
        std::fprintf(stderr, "seaplan-sim: mission time limit %.0f s reached\n",
                     f.max_mission_time_s);
        exit_code = 3;
        break;
      }
      out.clear();
      executor->Step(&out);
      // The live picture for watchers, a few times a second of wall time
      // (the server publishes at most once a second); failures only warn.
      // Not while the shore is unreachable: on a partitioned link each try
      // would hold the ship for its deadline, and the next one replaces it.
      if (const auto now = std::chrono::steady_clock::now();
          now >= next_vessel_state && !client.shore_unreachable()) {
        next_vessel_state = now + std::chrono::milliseconds(250);
        absl::Status sent = client.ReportVesselState(
            VesselState(*executor, mission_id, scenario->vessel_id, frame));
        if (!sent.ok() && !vessel_state_warned) {
          vessel_state_warned = true;
          std::fprintf(stderr, "seaplan-sim: warning: ReportVesselState: %s (live updates off)\n",
                       sent.ToString().c_str());
        }
      }
      std::vector<v1::ReportFeedbackRequest> reports;
      for (const sim::FeedbackOut& fb : out) {
        v1::ReportFeedbackRequest& req = reports.emplace_back();
        req.set_mission_id(mission_id);
        req.set_vessel_id(scenario->vessel_id);
        v1::Feedback* p = req.mutable_feedback();
        p->set_kind(convert::FeedbackKindToProto(fb.kind));
        p->set_task_id(fb.task_id);
        p->set_plan_version(fb.plan_version);
        p->set_mission_time_s(fb.mission_time_s);
        p->set_detail(fb.detail);
        FillShipState(fb, frame, p->mutable_state());
      }
      if (absl::Status st = client.Send(std::move(reports)); !st.ok()) {
        exit_code = fail(st);
        break;
      }
      // With the shore up, reports are answered before the ship moves on
      // (a replan it triggers is followed at once); with it down, the ship
      // executes on and the uplink keeps the backlog.
      client.WaitSent(ScaledWallClock(std::chrono::milliseconds(30'000)));
    }
    if (client.shore_unreachable() != offline) {
      offline = !offline;
      executor->Log(offline ? absl::StrCat("shore unreachable: executing plan version ",
                                           executor->plan_version(), " on board, ",
                                           client.backlog(), " reports kept for sending")
                            : std::string("shore reachable again: reports kept meanwhile sent"));
    }
    bool need_plan = executor->WaitingForPlan();
    for (const sim::FeedbackAck& ack : client.TakeAcks()) {
      if (ack.response.replan_triggered()) {
        need_plan = true;
        executor->Log(
            absl::StrCat("replan requested by the server: ", ack.response.replan_reason()));
      }
    }
    if (absl::Status st = client.uplink_error(); !st.ok()) {
      std::fprintf(stderr, "seaplan-sim: %s\n", st.ToString().c_str());
      exit_code = 1;
      break;
    }
    if (plan_ran_out && !need_plan) {
      // Everything acknowledged. A replan may still be under way, or done,
      // that no answer announced (its report's answer was lost with a server
      // that died, and the restarted server resumed the replan, while the
      // ship ran its plan out on board): follow it.
      auto m = client.GetMission(mission_id);
      if (!m.ok()) break;
      const bool newer_version =
          m->state() == v1::MISSION_STATE_ACTIVE && m->current_version() > executor->plan_version();
      if (m->state() != v1::MISSION_STATE_REPLANNING && !newer_version) break;
      need_plan = true;
    }
    if (need_plan) {
      auto v = client.WaitForVersion(executor->plan_version(), replan_timeout);
      if (v) {
        current_origin = v->mission_time_origin_s();
        executor->SetPlan(convert::PlanVersionFromProto(*v, frame));
      } else if (client.terminal_state() == v1::MISSION_STATE_COMPLETED &&
                 !executor->WaitingForPlan()) {
        // The goal already holds: nothing to replan.
      } else {
        std::fprintf(stderr, "seaplan-sim: no new plan version after a replan request\n");
        exit_code = client.terminal_state() == v1::MISSION_STATE_UNSPECIFIED ? 3 : 2;
        break;
      }
    }
    if (time_factor > 0 && !plan_ran_out) {
      auto due = wall_start + std::chrono::duration<double>(executor->time_s() / time_factor);
      std::this_thread::sleep_until(due);
    }
  }
  // Wait a little for the server's verdict (COMPLETED after the last task).
  auto verdict_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  v1::MissionState state = v1::MISSION_STATE_UNSPECIFIED;
  while (std::chrono::steady_clock::now() < verdict_deadline) {
    auto m = client.GetMission(mission_id);
    if (m.ok()) state = m->state();
    if (state == v1::MISSION_STATE_COMPLETED || state == v1::MISSION_STATE_FAILED ||
        state == v1::MISSION_STATE_CANCELLED) {
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  client.StopWatch();
  client.StopUplink();
  drain_log();
  auto& report = executor->mutable_report();
  report.completed = exit_code == 0 && executor->Finished() && state == v1::MISSION_STATE_COMPLETED;
  for (const auto& v : report.versions) {
    if (v.reason.rfind("fuel", 0) == 0) ++report.fuel_triggered_replans;
  }
  absl::Status written = sim::WriteReport(f.report_dir, report, rings, locations);
  if (!written.ok()) return fail(written);
  // The navigation log (time, source, message), then where the report is.
  std::printf("navigation log (mission time s, source, message):\n");
  std::vector<mission::LogEntry> entries = report.log.entries();
  std::stable_sort(entries.begin(), entries.end(),
                   [](const mission::LogEntry& a, const mission::LogEntry& b) {
                     return a.mission_time_s < b.mission_time_s;
                   });
  for (const mission::LogEntry& e : entries) {
    std::printf("%9.1f  %-12s  %s\n", e.mission_time_s, e.source.c_str(), e.message.c_str());
  }
  std::error_code ec;
  const std::string report_path = std::filesystem::absolute(f.report_dir, ec).string();
  std::printf("mission %s: %s, %zu plan versions, mission time %.1f s\n", mission_id.c_str(),
              v1::MissionState_Name(state).c_str(), report.versions.size(), executor->time_s());
  std::printf("report: %s/report.json (trajectory.svg, gantt.svg)\n", report_path.c_str());
  if (exit_code != 0) return exit_code;
  if (state != v1::MISSION_STATE_COMPLETED) return state == v1::MISSION_STATE_UNSPECIFIED ? 3 : 2;
  return 0;
}
