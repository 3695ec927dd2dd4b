// The operator's command line (cli.h). Subcommands mirror the API; plan,
// validate, chart, route and risk run in-process when no --server is given.
#include "cli.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/strings/str_cat.h"
#include "client_token.h"
#include "google/protobuf/util/json_util.h"
#include "output.h"
#include "seaplan/common/file_replace.h"
#include "seaplan/common/log.h"
#include "seaplan/common/status.h"

namespace seaplan::cli {
namespace {

// A finite number >= 0 ("expected <what> >= 0, got -2"); CLI11's
// NonNegativeNumber names the whole range of a double instead.
CLI::Validator NonNegative(const std::string& what, const std::string& type_name) {
  return CLI::Validator(
      [what](std::string& v) {
        char* end = nullptr;
        const double x = std::strtod(v.c_str(), &end);
        return !v.empty() && end == v.c_str() + v.size() && std::isfinite(x) && x >= 0
                   ? std::string()
                   : "expected " + what + " >= 0, got " + v;
      },
      type_name);
}

struct GlobalOptions {
  std::string server;  // empty: in-process
  // The API token (--token, else --token-file, SEAPLAN_TOKEN or
  // SEAPLAN_TOKEN_FILE); read by the server backend only.
  std::string token;
  std::string token_file;
  bool json = false;
  double timeout_s = 0;
  client::TlsFiles tls;
  const CliExecutable* executable = nullptr;
};

absl::Status ReadFile(const std::string& path, std::string* content) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return absl::InvalidArgumentError("cannot read file '" + path + "'");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  *content = buffer.str();
  return absl::OkStatus();
}

absl::Status WriteFile(const std::string& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  if (!out || !(out << content))
    return absl::InvalidArgumentError("cannot write file '" + path + "'");
  return absl::OkStatus();
}

// Writes `content` whole (seaplan::ReplaceFile): a reader, or a process
// killed meanwhile, sees the old file or the new. Anything but a regular file
// (a symlink, /dev/stdout, a pipe), and a folder this process may not create
// in, are written in place.
absl::Status ReplacePlanFile(const std::string& path, const std::string& content) {
  std::error_code error;
  const auto status = std::filesystem::symlink_status(path, error);
  if (!error && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    return WriteFile(path, content);
  }
  if (ReplaceFile(path, content).ok()) return absl::OkStatus();
  return WriteFile(path, content);
}

// "63.44,10.39" -> LatLon.
absl::Status ParseLatLon(const std::string& text, v1::LatLon* position) {
  const auto comma = text.find(',');
  char* end = nullptr;
  if (comma == std::string::npos) {
    return absl::InvalidArgumentError("position '" + text + "': expected LAT,LON in degrees");
  }
  const std::string lat_text = text.substr(0, comma), lon_text = text.substr(comma + 1);
  const double lat = std::strtod(lat_text.c_str(), &end);
  if (end == lat_text.c_str() || *end != '\0' || lat < -90 || lat > 90) {
    return absl::InvalidArgumentError("position '" + text + "': latitude must be in [-90, 90]");
  }
  const double lon = std::strtod(lon_text.c_str(), &end);
  if (end == lon_text.c_str() || *end != '\0' || lon < -180 || lon > 180) {
    return absl::InvalidArgumentError("position '" + text + "': longitude must be in [-180, 180]");
  }
  position->set_latitude_deg(lat);
  position->set_longitude_deg(lon);
  return absl::OkStatus();
}

// The token as given (flag, file or environment); a file that cannot be
// read is reported and exits with kExitBadInput.
std::string ResolvedToken(const GlobalOptions& options) {
  if (options.server.empty()) return "";
  absl::StatusOr<std::string> token = client::ResolveToken(options.token, options.token_file);
  if (!token.ok()) {
    std::cerr << "error: " << token.status().message() << "\n";
    std::exit(kExitBadInput);
  }
  return *token;
}

std::unique_ptr<Backend> MakeBackend(const GlobalOptions& options) {
  return options.executable->make_backend(options.server, options.timeout_s, ResolvedToken(options),
                                          options.tls);
}

void PrintJsonOr(const GlobalOptions& options, const google::protobuf::Message& message,
                 const std::function<void()>& human) {
  if (options.json) {
    std::cout << ToJson(message) << "\n";
  } else {
    human();
  }
}

// ---- plan -----------------------------------------------------------------

struct PlanArgs {
  std::string domain, problem, output;
  double time_limit_s = 60;
  std::uint64_t memory_limit_mb = 0;
  int max_concurrent = 0;
  bool no_anytime = false;
  bool no_type_based = false;
  bool landmarks = true;
  bool no_symmetry = false;
  bool no_eager_ends = false;
  bool stream = false;
  std::uint64_t seed = 1;
  double epsilon_s = 0;
  std::uint64_t max_expansions = 0;
  double cpu_limit_s = 0;
  double switch_after = -1;     // < 0: the planner's default
  double seed_rounds = -1;      // < 0: the planner's default
  double suffix_searches = -1;  // < 0: the planner's default
};

int RunPlan(const GlobalOptions& options, const PlanArgs& args) {
  v1::PlanRequest request;
  if (auto s = ReadFile(args.domain, request.mutable_domain()); !s.ok())
    return ReportError(std::cerr, s);
  if (auto s = ReadFile(args.problem, request.mutable_problem()); !s.ok())
    return ReportError(std::cerr, s);
  auto* planner = request.mutable_options();
  const auto limit_ms = static_cast<std::int64_t>(args.time_limit_s * 1000);
  planner->mutable_time_limit()->set_seconds(limit_ms / 1000);
  planner->mutable_time_limit()->set_nanos(static_cast<int>((limit_ms % 1000) * 1000000));
  planner->set_memory_limit_mb(args.memory_limit_mb);
  planner->set_max_concurrent_actions(args.max_concurrent);
  planner->set_anytime(!args.no_anytime);
  if (args.no_type_based) planner->set_type_based_exploration(false);
  planner->set_landmarks(args.landmarks);
  if (args.no_symmetry) planner->set_symmetry_reduction(false);
  if (args.no_eager_ends) planner->set_eager_ends(false);
  if (args.switch_after >= 0) planner->set_second_greedy_after_share(args.switch_after);
  if (args.seed_rounds >= 0) planner->set_seed_rounds_share(args.seed_rounds);
  if (args.suffix_searches >= 0) planner->set_suffix_search_share(args.suffix_searches);
  planner->set_random_seed(args.seed);
  planner->set_epsilon_s(args.epsilon_s);
  planner->set_max_expansions(args.max_expansions);
  if (args.cpu_limit_s > 0) {
    const auto cpu_ms = static_cast<std::int64_t>(args.cpu_limit_s * 1000);
    planner->mutable_cpu_time_limit()->set_seconds(cpu_ms / 1000);
    planner->mutable_cpu_time_limit()->set_nanos(static_cast<int>((cpu_ms % 1000) * 1000000));
  }

  auto backend = MakeBackend(options);
  v1::PlanResponse response;
  absl::Status status;
  // With -o, each improved plan replaces the file as soon as it is found
  // (written beside it, then renamed): a process killed from outside (an
  // outer time limit, the OOM killer) leaves its best plan so far there.
  absl::Status write_status;
  if (args.stream || !args.output.empty()) {
    status = backend->PlanStream(request, [&](const v1::PlanStreamEvent& event) {
      if (event.has_improved_plan() && !args.output.empty() && write_status.ok()) {
        write_status = ReplacePlanFile(args.output, FormatPlanText(event.improved_plan()));
      }
      if (!args.stream) {
        if (event.has_final_result()) response = event.final_result();
        return;
      }
      if (options.json) {
        std::cout << ToJson(event) << "\n" << std::flush;
      } else if (event.has_improved_plan()) {
        std::cerr << "improved plan: makespan " << event.improved_plan().makespan_s() << " s after "
                  << event.improved_plan().statistics().search_time_s() << " s\n";
      } else if (event.has_progress()) {
        std::cerr << "searching: " << event.progress().statistics().expanded() << " expanded, "
                  << event.progress().elapsed_s() << " s\n";
      }
      if (event.has_final_result()) response = event.final_result();
    });
  } else {
    status = backend->Plan(request, &response);
  }
  if (!status.ok()) return ReportError(std::cerr, status);
  if (!args.stream || !options.json) {
    PrintJsonOr(options, response, [&] { PrintPlanResponse(std::cout, response); });
  }
  if (!write_status.ok()) return ReportError(std::cerr, write_status);
  // A solved task's plan is written even when empty (its goal holds at the
  // start): an old file left in its place would be taken for it.
  const bool solved =
      response.status() == v1::SOLVED_SATISFICING || response.status() == v1::SOLVED_OPTIMALLY;
  if (!args.output.empty() && solved) {
    if (auto s = ReplacePlanFile(args.output, FormatPlanText(response)); !s.ok())
      return ReportError(std::cerr, s);
  }
  switch (response.status()) {
    case v1::SOLVED_SATISFICING:
    case v1::SOLVED_OPTIMALLY:
      return kExitSuccess;
    case v1::UNSUPPORTED:
      return kExitBadInput;
    default:
      return kExitNoPlan;
  }
}

// ---- validate -------------------------------------------------------------

int RunValidate(const GlobalOptions& options, const std::string& domain, const std::string& problem,
                const std::string& plan, double epsilon_s) {
  v1::ValidateRequest request;
  if (auto s = ReadFile(domain, request.mutable_domain()); !s.ok())
    return ReportError(std::cerr, s);
  if (auto s = ReadFile(problem, request.mutable_problem()); !s.ok())
    return ReportError(std::cerr, s);
  if (auto s = ReadFile(plan, request.mutable_plan()); !s.ok()) return ReportError(std::cerr, s);
  request.set_epsilon_s(epsilon_s);
  v1::ValidateResponse response;
  if (auto s = MakeBackend(options)->Validate(request, &response); !s.ok()) {
    return ReportError(std::cerr, s);
  }
  PrintJsonOr(options, response, [&] { PrintValidateResponse(std::cout, response); });
  return response.valid() ? kExitSuccess : kExitNoPlan;
}

// ---- charts ---------------------------------------------------------------

struct ChartArgs {
  std::vector<std::string> files;
  std::string name, format;
  double minimum_depth_m = 0, safety_buffer_m = 0;
};

absl::Status BuildUpload(const ChartArgs& args, v1::UploadChartRequest* request) {
  if (args.files.empty()) return absl::InvalidArgumentError("no chart file given");
  for (std::string path : args.files) {
    while (path.size() > 1 && path.back() == '/') path.pop_back();
    const std::string base = path.substr(path.find_last_of('/') + 1);
    std::error_code error;
    if (!std::filesystem::is_directory(path, error)) {
      auto* file = request->add_files();
      file->set_name(base);
      SEAPLAN_RETURN_IF_ERROR(ReadFile(path, file->mutable_content()));
      continue;
    }
    // A folder (a FileGDB .gdb, a set of shapefiles): every file in it, named
    // by its path inside the folder so the loader sees the same tree.
    std::vector<std::string> inner;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(path, error)) {
      if (entry.is_regular_file()) {
        inner.push_back(std::filesystem::relative(entry.path(), path).generic_string());
      }
    }
    if (error) {
      return absl::InvalidArgumentError("cannot read folder '" + path + "': " + error.message());
    }
    if (inner.empty()) return absl::InvalidArgumentError("folder '" + path + "' has no files");
    std::sort(inner.begin(), inner.end());
    for (const std::string& relative : inner) {
      auto* file = request->add_files();
      file->set_name(absl::StrCat(base, "/", relative));
      SEAPLAN_RETURN_IF_ERROR(ReadFile(absl::StrCat(path, "/", relative), file->mutable_content()));
    }
  }
  const std::string& first = request->files(0).name();
  request->set_name(args.name.empty() ? first.substr(0, first.find('/')) : args.name);
  if (args.format == "s57")
    request->set_format(v1::CHART_FORMAT_S57);
  else if (args.format == "geojson")
    request->set_format(v1::CHART_FORMAT_GEOJSON);
  else if (args.format == "zip")
    request->set_format(v1::CHART_FORMAT_ZIP);
  else if (!args.format.empty() && args.format != "auto") {
    return absl::InvalidArgumentError("unknown chart format '" + args.format +
                                      "' (expected auto, s57, geojson or zip)");
  }
  request->set_minimum_depth_m(args.minimum_depth_m);
  request->set_safety_buffer_m(args.safety_buffer_m);
  return absl::OkStatus();
}

int RunChartUpload(const GlobalOptions& options, const ChartArgs& args) {
  v1::UploadChartRequest request;
  if (auto s = BuildUpload(args, &request); !s.ok()) return ReportError(std::cerr, s);
  v1::UploadChartResponse response;
  if (auto s = MakeBackend(options)->UploadChart(request, &response); !s.ok()) {
    return ReportError(std::cerr, s);
  }
  PrintJsonOr(options, response, [&] {
    PrintChart(std::cout, response.chart());
    for (const auto& w : response.warnings()) std::cerr << "warning: " << w << "\n";
  });
  return kExitSuccess;
}

int RunChartList(const GlobalOptions& options) {
  v1::ListChartsRequest request;
  auto backend = MakeBackend(options);
  v1::ListChartsResponse all;
  do {
    v1::ListChartsResponse page;
    if (auto s = backend->ListCharts(request, &page); !s.ok()) return ReportError(std::cerr, s);
    for (const auto& chart : page.charts()) *all.add_charts() = chart;
    request.set_page_token(page.next_page_token());
  } while (!request.page_token().empty());
  PrintJsonOr(options, all, [&] {
    if (all.charts_size() == 0) std::cout << "no charts\n";
    for (const auto& chart : all.charts()) PrintChart(std::cout, chart);
  });
  return kExitSuccess;
}

int RunChartGet(const GlobalOptions& options, const std::string& id, const std::string& geojson) {
  v1::GetChartRequest request;
  request.set_chart_id(id);
  request.set_include_obstacles_geojson(!geojson.empty());
  v1::GetChartResponse response;
  if (auto s = MakeBackend(options)->GetChart(request, &response); !s.ok())
    return ReportError(std::cerr, s);
  if (!geojson.empty()) {
    if (auto s = WriteFile(geojson, response.obstacles_geojson()); !s.ok())
      return ReportError(std::cerr, s);
  }
  PrintJsonOr(options, response.chart(), [&] { PrintChart(std::cout, response.chart()); });
  return kExitSuccess;
}

int RunChartDelete(const GlobalOptions& options, const std::string& id) {
  v1::DeleteChartRequest request;
  request.set_chart_id(id);
  v1::DeleteChartResponse response;
  if (auto s = MakeBackend(options)->DeleteChart(request, &response); !s.ok())
    return ReportError(std::cerr, s);
  PrintJsonOr(options, response,
              [&] { std::cout << "deleted chart " << response.chart_id() << "\n"; });
  return kExitSuccess;
}

// ---- route and risk ---------------------------------------------------------

struct RouteArgs {
  std::string chart_id;
  ChartArgs chart_file;  // in-process or upload-then-route
  std::string from, to, geojson, track;
  double wind_speed_mps = 0, wind_from_deg = 0, current_speed_mps = 0, current_from_deg = 0;
  int particles = 0, iterations = 0, segments = 0;
  std::uint64_t seed = 0;
  double horizon_s = 0, safety_distance_m = 0, speed_mps = 0;
};

// Resolves the chart: an id on the server, or files uploaded into the backend first.
absl::Status ResolveChart(Backend& backend, const RouteArgs& args, std::string* chart_id) {
  if (!args.chart_id.empty()) {
    *chart_id = args.chart_id;
    return absl::OkStatus();
  }
  if (args.chart_file.files.empty()) {
    return absl::InvalidArgumentError(
        "give --chart ID (a chart on the server) or --chart-file FILE");
  }
  v1::UploadChartRequest upload;
  SEAPLAN_RETURN_IF_ERROR(BuildUpload(args.chart_file, &upload));
  v1::UploadChartResponse uploaded;
  SEAPLAN_RETURN_IF_ERROR(backend.UploadChart(upload, &uploaded));
  *chart_id = uploaded.chart().chart_id();
  return absl::OkStatus();
}

void FillEnvironment(const RouteArgs& args, v1::Environment* env) {
  env->set_wind_speed_mps(args.wind_speed_mps);
  env->set_wind_from_deg(args.wind_from_deg);
  env->set_current_speed_mps(args.current_speed_mps);
  env->set_current_from_deg(args.current_from_deg);
}

int RunRoute(const GlobalOptions& options, const RouteArgs& args) {
  auto backend = MakeBackend(options);
  v1::PlanRouteRequest request;
  if (auto s = ParseLatLon(args.from, request.mutable_start()); !s.ok())
    return ReportError(std::cerr, s);
  if (auto s = ParseLatLon(args.to, request.mutable_goal()); !s.ok())
    return ReportError(std::cerr, s);
  if (auto s = ResolveChart(*backend, args, request.mutable_chart_id()); !s.ok()) {
    return ReportError(std::cerr, s);
  }
  FillEnvironment(args, request.mutable_environment());
  request.mutable_ship()->set_service_speed_mps(args.speed_mps);
  auto* opt = request.mutable_options();
  opt->set_particles(args.particles);
  opt->set_iterations(args.iterations);
  opt->set_segments(args.segments);
  opt->set_random_seed(args.seed);
  opt->set_ttg_horizon_s(args.horizon_s);
  opt->set_safety_distance_m(args.safety_distance_m);
  opt->set_include_obstacles_geojson(!args.geojson.empty());
  v1::PlanRouteResponse response;
  if (auto s = backend->PlanRoute(request, &response); !s.ok()) return ReportError(std::cerr, s);
  if (!args.geojson.empty()) {
    if (auto s = WriteFile(args.geojson, response.obstacles_geojson()); !s.ok())
      return ReportError(std::cerr, s);
  }
  PrintJsonOr(options, response, [&] { PrintRoute(std::cout, response); });
  return kExitSuccess;
}

// Track file: one "lat,lon[,heading_deg[,speed_mps[,mode]]]" per line; '#' comments.
absl::Status ReadTrack(const std::string& path, v1::EstimateRiskRequest* request) {
  std::string content;
  SEAPLAN_RETURN_IF_ERROR(ReadFile(path, &content));
  std::istringstream lines(content);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream fs(line);
    for (std::string field; std::getline(fs, field, ',');) fields.push_back(field);
    auto* point = request->add_track();
    if (fields.size() < 2) {
      return absl::InvalidArgumentError(path + ":" + std::to_string(number) +
                                        ": expected lat,lon[,heading_deg[,speed_mps[,mode]]]");
    }
    auto s = ParseLatLon(fields[0] + "," + fields[1], point->mutable_position());
    if (!s.ok())
      return absl::InvalidArgumentError(path + ":" + std::to_string(number) + ": " +
                                        std::string(s.message()));
    if (fields.size() > 2 && !fields[2].empty())
      point->set_heading_deg(std::atof(fields[2].c_str()));
    if (fields.size() > 3 && !fields[3].empty()) point->set_speed_mps(std::atof(fields[3].c_str()));
    if (fields.size() > 4) {
      v1::MsoMode mode = v1::MSO_MODE_UNSPECIFIED;
      if (!v1::MsoMode_Parse("MSO_MODE_" + fields[4], &mode)) {
        return absl::InvalidArgumentError(path + ":" + std::to_string(number) + ": unknown mode '" +
                                          fields[4] + "' (expected PTO, MEC or PTI)");
      }
      point->set_mode(mode);
    }
  }
  if (request->track_size() == 0)
    return absl::InvalidArgumentError(path + ": the track has no points");
  return absl::OkStatus();
}

int RunRisk(const GlobalOptions& options, const RouteArgs& args) {
  auto backend = MakeBackend(options);
  v1::EstimateRiskRequest request;
  if (auto s = ReadTrack(args.track, &request); !s.ok()) return ReportError(std::cerr, s);
  if (auto s = ResolveChart(*backend, args, request.mutable_chart_id()); !s.ok()) {
    return ReportError(std::cerr, s);
  }
  FillEnvironment(args, request.mutable_environment());
  request.set_ttg_horizon_s(args.horizon_s);
  v1::EstimateRiskResponse response;
  if (auto s = backend->EstimateRisk(request, &response); !s.ok()) return ReportError(std::cerr, s);
  PrintJsonOr(options, response, [&] { PrintRisk(std::cout, response); });
  return kExitSuccess;
}

// ---- missions -------------------------------------------------------------

struct MissionArgs {
  std::string spec, domain, problem, id, reason;
  int after_version = 0;
  std::int64_t after_event = 0;
  bool follow = true;
  // mission feedback: the store's cursor, reports per call, most to print (0: all)
  std::int64_t after_sequence = 0;
  int page_size = 0;
  std::int64_t limit = 0;
};

int RunMissionCreate(const GlobalOptions& options, const MissionArgs& args) {
  v1::CreateMissionRequest request;
  if (!args.spec.empty()) {
    std::string json;
    if (auto s = ReadFile(args.spec, &json); !s.ok()) return ReportError(std::cerr, s);
    auto parsed = google::protobuf::util::JsonStringToMessage(json, request.mutable_spec());
    if (!parsed.ok()) {
      return ReportError(std::cerr,
                         absl::InvalidArgumentError(args.spec + ": not a MissionSpec in JSON: " +
                                                    std::string(parsed.message())));
    }
  }
  if (!args.domain.empty()) {
    if (auto s = ReadFile(args.domain, request.mutable_spec()->mutable_domain()); !s.ok())
      return ReportError(std::cerr, s);
  }
  if (!args.problem.empty()) {
    if (auto s = ReadFile(args.problem, request.mutable_spec()->mutable_problem()); !s.ok())
      return ReportError(std::cerr, s);
  }
  v1::Mission mission;
  if (auto s = MakeBackend(options)->CreateMission(request, &mission); !s.ok())
    return ReportError(std::cerr, s);
  PrintJsonOr(options, mission, [&] { PrintMission(std::cout, mission); });
  return kExitSuccess;
}

int RunMissionGet(const GlobalOptions& options, const std::string& id) {
  v1::GetMissionRequest request;
  request.set_mission_id(id);
  v1::Mission mission;
  if (auto s = MakeBackend(options)->GetMission(request, &mission); !s.ok())
    return ReportError(std::cerr, s);
  PrintJsonOr(options, mission, [&] { PrintMission(std::cout, mission); });
  return kExitSuccess;
}

int RunMissionList(const GlobalOptions& options) {
  v1::ListMissionsRequest request;
  auto backend = MakeBackend(options);
  v1::ListMissionsResponse all;
  do {
    v1::ListMissionsResponse page;
    if (auto s = backend->ListMissions(request, &page); !s.ok()) return ReportError(std::cerr, s);
    for (const auto& m : page.missions()) *all.add_missions() = m;
    request.set_page_token(page.next_page_token());
  } while (!request.page_token().empty());
  PrintJsonOr(options, all, [&] {
    if (all.missions_size() == 0) std::cout << "no missions\n";
    for (const auto& m : all.missions()) PrintMission(std::cout, m);
  });
  return kExitSuccess;
}

// The stored feedback reports, oldest first, page after page until the last
// or `--limit`; the answer's next_after_sequence is where to go on from
// (0: nothing more stored yet).
int RunMissionFeedback(const GlobalOptions& options, const MissionArgs& args) {
  v1::ListFeedbackRequest request;
  request.set_mission_id(args.id);
  request.set_after_sequence(args.after_sequence);
  request.set_page_size(args.page_size);
  auto backend = MakeBackend(options);
  v1::ListFeedbackResponse all;
  const auto full = [&] { return args.limit > 0 && all.feedback_size() >= args.limit; };
  bool cut = false;  // stopped at --limit with reports left
  for (bool more = true; more && !cut;) {
    v1::ListFeedbackResponse page;
    if (auto s = backend->ListFeedback(request, &page); !s.ok()) return ReportError(std::cerr, s);
    for (const auto& f : page.feedback()) {
      if (full()) {
        cut = true;
        break;
      }
      *all.add_feedback() = f;
    }
    more = page.next_after_sequence() != 0;
    request.set_after_sequence(page.next_after_sequence());
    cut = cut || (more && full());
  }
  if (cut) all.set_next_after_sequence(all.feedback(all.feedback_size() - 1).sequence());
  PrintJsonOr(options, all, [&] {
    if (all.feedback_size() == 0) {
      std::cout << "no feedback\n";
      return;
    }
    PrintFeedbackTable(std::cout, all);
    if (cut) {
      std::cerr << "more reports follow: --after-sequence " << all.next_after_sequence() << "\n";
    }
  });
  return kExitSuccess;
}

// ---- token, audit ----------------------------------------------------------
struct TokenArgs {
  std::string role;
  std::string vessel;
  std::string description;
  std::int64_t expires_in_s = 0;
  std::string id;
};

const char* RoleLabel(v1::Role role) {
  switch (role) {
    case v1::ROLE_ADMIN:
      return "admin";
    case v1::ROLE_OPERATOR:
      return "operator";
    case v1::ROLE_VIEWER:
      return "viewer";
    case v1::ROLE_VESSEL:
      return "vessel";
    default:
      return "?";
  }
}

void PrintToken(std::ostream& out, const v1::TokenInfo& t) {
  out << t.token_id() << "  " << RoleLabel(t.role());
  if (!t.vessel_id().empty()) out << " (" << t.vessel_id() << ")";
  out << "  created " << FormatTimeMs(t.created_at_ms());
  if (t.expires_at_ms() != 0) out << "  expires " << FormatTimeMs(t.expires_at_ms());
  if (t.revoked_at_ms() != 0) out << "  REVOKED " << FormatTimeMs(t.revoked_at_ms());
  if (!t.description().empty()) out << "  " << t.description();
  out << "\n";
}

int RunTokenCreate(const GlobalOptions& options, const TokenArgs& args) {
  v1::CreateTokenRequest request;
  v1::Role role = v1::ROLE_UNSPECIFIED;
  for (v1::Role r : {v1::ROLE_ADMIN, v1::ROLE_OPERATOR, v1::ROLE_VIEWER, v1::ROLE_VESSEL}) {
    if (args.role == RoleLabel(r)) role = r;
  }
  if (role == v1::ROLE_UNSPECIFIED) {
    std::cerr << "error: --role must be admin, operator, viewer or vessel\n";
    return kExitBadInput;
  }
  request.set_role(role);
  request.set_vessel_id(args.vessel);
  request.set_description(args.description);
  request.set_expires_in_s(args.expires_in_s);
  v1::CreateTokenResponse response;
  if (auto s = MakeBackend(options)->CreateToken(request, &response); !s.ok())
    return ReportError(std::cerr, s);
  PrintJsonOr(options, response, [&] {
    PrintToken(std::cerr, response.token());
    std::cerr << "the token (shown only now; keep it secret):\n";
    std::cout << response.bearer() << "\n";
  });
  return kExitSuccess;
}

int RunTokenList(const GlobalOptions& options) {
  v1::ListTokensResponse response;
  if (auto s = MakeBackend(options)->ListTokens({}, &response); !s.ok())
    return ReportError(std::cerr, s);
  PrintJsonOr(options, response, [&] {
    for (const auto& t : response.tokens()) PrintToken(std::cout, t);
  });
  return kExitSuccess;
}

int RunTokenRevoke(const GlobalOptions& options, const TokenArgs& args) {
  v1::RevokeTokenRequest request;
  request.set_token_id(args.id);
  v1::RevokeTokenResponse response;
  if (auto s = MakeBackend(options)->RevokeToken(request, &response); !s.ok())
    return ReportError(std::cerr, s);
  PrintJsonOr(options, response, [&] { PrintToken(std::cout, response.token()); });
  return kExitSuccess;
}

int RunAudit(const GlobalOptions& options) {
  v1::ListAuditEventsRequest request;
  request.set_page_size(1000);
  auto backend = MakeBackend(options);
  v1::ListAuditEventsResponse all;
  do {
    v1::ListAuditEventsResponse page;
    if (auto s = backend->ListAuditEvents(request, &page); !s.ok())
      return ReportError(std::cerr, s);
    for (const auto& e : page.events()) *all.add_events() = e;
    request.set_page_token(page.next_page_token());
  } while (!request.page_token().empty());
  PrintJsonOr(options, all, [&] {
    for (const auto& e : all.events()) {
      std::cout << FormatTimeMs(e.time_ms()) << "  " << e.token_id() << " (" << RoleLabel(e.role());
      if (!e.vessel_id().empty()) std::cout << " " << e.vessel_id();
      std::cout << ")  " << e.action() << "  " << e.target();
      if (!e.detail().empty()) std::cout << "  " << e.detail();
      std::cout << "\n";
    }
  });
  return kExitSuccess;
}

bool IsFinal(v1::MissionState state) {
  return state == v1::MISSION_STATE_COMPLETED || state == v1::MISSION_STATE_FAILED ||
         state == v1::MISSION_STATE_CANCELLED;
}

int RunMissionWatch(const GlobalOptions& options, const MissionArgs& args) {
  v1::WatchMissionRequest request;
  request.set_mission_id(args.id);
  request.set_after_version(args.after_version);
  request.set_after_event_id(args.after_event);
  auto status = MakeBackend(options)->WatchMission(request, [&](const v1::MissionEvent& event) {
    if (options.json) {
      std::cout << ToJson(event) << "\n" << std::flush;
    } else if (event.has_plan_version()) {
      PrintPlanVersion(std::cout, event.plan_version());
    } else if (event.has_log()) {
      PrintLogEvent(std::cout, event.log());
    } else if (event.has_mission()) {
      PrintMission(std::cout, event.mission());
    }
    std::cout << std::flush;
    return args.follow && !(event.has_mission() && IsFinal(event.mission().state()));
  });
  if (!status.ok()) return ReportError(std::cerr, status);
  return kExitSuccess;
}

int RunMissionReplan(const GlobalOptions& options, const MissionArgs& args) {
  v1::RequestReplanRequest request;
  request.set_mission_id(args.id);
  request.set_reason(args.reason.empty() ? "operator request" : args.reason);
  v1::RequestReplanResponse response;
  if (auto s = MakeBackend(options)->RequestReplan(request, &response); !s.ok())
    return ReportError(std::cerr, s);
  PrintJsonOr(options, response, [&] { PrintPlanVersion(std::cout, response.version()); });
  return kExitSuccess;
}

int RunMissionCancel(const GlobalOptions& options, const MissionArgs& args) {
  v1::CancelMissionRequest request;
  request.set_mission_id(args.id);
  request.set_reason(args.reason.empty() ? "cancelled by operator" : args.reason);
  v1::Mission mission;
  if (auto s = MakeBackend(options)->CancelMission(request, &mission); !s.ok())
    return ReportError(std::cerr, s);
  PrintJsonOr(options, mission, [&] { PrintMission(std::cout, mission); });
  return kExitSuccess;
}

void AddRouteOptions(CLI::App* command, RouteArgs& args) {
  command->add_option("--chart", args.chart_id, "Chart id on the server");
  command->add_option("--chart-file", args.chart_file.files,
                      "Chart file(s) to load (S-57 .000 + updates, GeoJSON, zip)");
  command->add_option("--min-depth", args.chart_file.minimum_depth_m,
                      "Minimum depth for --chart-file (m)");
  command->add_option("--buffer", args.chart_file.safety_buffer_m,
                      "Safety buffer for --chart-file (m)");
  command->add_option("--wind-speed", args.wind_speed_mps, "Wind speed (m/s)");
  command->add_option("--wind-from", args.wind_from_deg, "Direction the wind comes from (deg)");
  command->add_option("--current-speed", args.current_speed_mps, "Current speed (m/s)");
  command->add_option("--current-from", args.current_from_deg,
                      "Direction the current comes from (deg)");
  command->add_option("--horizon", args.horizon_s, "Time-to-grounding horizon (s), default 600");
}

}  // namespace

int RunCli(int argc, char** argv, const CliExecutable& executable) {
  CLI::App app{"seaplan: mission planning for autonomous ships (operator CLI)"};
  app.require_subcommand(1);
  GlobalOptions options;
  options.executable = &executable;
  if (const char* env = std::getenv("SEAPLAN_SERVER")) options.server = env;
  app.add_option("--server", options.server,
                 "Server address host:port (env SEAPLAN_SERVER); in-process when empty");
  app.add_option("--token", options.token,
                 "API token for --server (else --token-file, env SEAPLAN_TOKEN or "
                 "SEAPLAN_TOKEN_FILE)");
  app.add_option("--token-file", options.token_file, "file whose first line is the API token");
  app.add_flag("--json", options.json, "Machine-readable JSON output");
  app.add_option("--timeout", options.timeout_s, "RPC deadline in seconds (0: none)");
  client::AddTlsOptions(app, &options.tls);
  std::string log_level = "warn";
  app.add_option("--log-level", log_level, "debug, info, warn, error or off (in-process work)")
      ->capture_default_str();
  app.parse_complete_callback([&] {
    log::Level level;
    if (!log::ParseLevel(log_level, &level)) {
      throw CLI::ValidationError("--log-level", "expected debug, info, warn, error or off");
    }
    log::SetLevel(level);
    if (absl::Status tls = client::CheckTlsFiles(options.tls); !tls.ok())
      throw CLI::ValidationError(std::string(tls.message()));
  });

  int exit_code = kExitSuccess;
  std::string handed_over;  // a command this executable does not run
  // The callback of `command`: runs it here, or notes it for hand-over.
  auto runner = [&](const char* command, std::function<int()> run) {
    return [&, command, run = std::move(run)] {
      if (executable.runs(command, options.server)) {
        exit_code = run();
      } else {
        handed_over = command;
      }
    };
  };

  PlanArgs plan;
  auto* plan_cmd = app.add_subcommand("plan", "Plan a PDDL 2.1 temporal problem");
  plan_cmd->add_option("domain", plan.domain, "Domain file")->required();
  plan_cmd->add_option("problem", plan.problem, "Problem file")->required();
  plan_cmd->add_option("--time-limit", plan.time_limit_s, "Time limit (s)")->capture_default_str();
  plan_cmd->add_option("--memory-limit", plan.memory_limit_mb, "Memory limit (MB), default 2048");
  plan_cmd->add_option("--max-concurrent", plan.max_concurrent,
                       "Most actions running at once (0: any)");
  plan_cmd
      ->add_option("--max-expansions", plan.max_expansions,
                   "Stop after this many expanded states, the same plan on any machine (0: no "
                   "limit)")
      ->check(CLI::Validator(
          [](std::string& v) {
            return v.find_first_not_of("0123456789") == std::string::npos && !v.empty()
                       ? std::string()
                       : "expected a whole number >= 0, got " + v;
          },
          "UINT"))
      ->capture_default_str();
  plan_cmd
      ->add_option("--cpu-limit", plan.cpu_limit_s,
                   "CPU time limit of the search (s), the same work under any load (0: none)")
      ->check(NonNegative("a number of seconds", "SECONDS"));
  plan_cmd->add_flag(
      "--no-anytime", plan.no_anytime,
      "No anytime phases: stop after the first plan and the bounded searches that shorten it");
  plan_cmd->add_flag("--no-type-based", plan.no_type_based,
                     "First-plan searches without the type-based exploration list");
  plan_cmd->add_flag("--landmarks,!--no-landmarks", plan.landmarks,
                     "First-plan searches also ordered by LAMA's landmark count (default; "
                     "--no-landmarks: without it)");
  plan_cmd->add_flag("--no-symmetry", plan.no_symmetry,
                     "First-plan searches keep states that only permute interchangeable objects "
                     "(they always do when timed literals close deadlines)");
  plan_cmd->add_flag("--no-eager-ends", plan.no_eager_ends,
                     "Searches also try the orders in which an end that only adds facts "
                     "happens later");
  plan_cmd
      ->add_option("--switch-after", plan.switch_after,
                   "Share of the budget (expansions, CPU or time limit) after which, with no "
                   "plan yet, the first-plan search by makespan gives way to one that delays "
                   "actions undoing held goals (default 0.25; 0: the newest-first search alone)")
      ->check(CLI::Range(0.0, 1.0));
  plan_cmd
      ->add_option("--seed-rounds", plan.seed_rounds,
                   "After the first plan and the searches that shorten it, rounds of the same "
                   "with other seeds, begun while they have expanded fewer than this multiple of "
                   "the states expanded before them (default 1; 0: none)")
      ->check(NonNegative("a number", "MULTIPLE"));
  plan_cmd
      ->add_option("--suffix-searches", plan.suffix_searches,
                   "After the rounds, the best plan's last sixths searched again with the rest "
                   "kept, on at most this multiple of the states expanded before them (default "
                   "1; 0: none)")
      ->check(NonNegative("a number", "MULTIPLE"));
  plan_cmd->add_option("--seed", plan.seed, "Random seed")->capture_default_str();
  plan_cmd->add_option("--epsilon", plan.epsilon_s,
                       "Separation of interfering events (s), default 0.001");
  plan_cmd->add_flag("--stream", plan.stream, "Show progress and each improved plan");
  plan_cmd->add_option("-o,--output", plan.output,
                       "Write the plan to this file (each improved plan as soon as it is found)");
  plan_cmd->callback(runner("plan", [&] { return RunPlan(options, plan); }));

  std::string v_domain, v_problem, v_plan;
  double v_epsilon = 0;
  auto* validate_cmd = app.add_subcommand("validate", "Validate a temporal plan");
  validate_cmd->add_option("domain", v_domain, "Domain file")->required();
  validate_cmd->add_option("problem", v_problem, "Problem file")->required();
  validate_cmd->add_option("plan", v_plan, "Plan file (IPC format)")->required();
  validate_cmd->add_option("--epsilon", v_epsilon,
                           "Separation of interfering events (s), default 0.001");
  validate_cmd->callback(runner(
      "validate", [&] { return RunValidate(options, v_domain, v_problem, v_plan, v_epsilon); }));

  auto* chart_cmd = app.add_subcommand("chart", "Upload, list, show and delete charts");
  chart_cmd->require_subcommand(1);
  ChartArgs chart;
  auto* upload_cmd = chart_cmd->add_subcommand("upload", "Upload a chart");
  upload_cmd
      ->add_option(
          "files", chart.files,
          "S-57 .000 (+ .001 ...), GeoJSON, shapefiles, a FileGDB or shapefile folder, or zip")
      ->required();
  upload_cmd->add_option("--name", chart.name, "Chart name");
  upload_cmd->add_option("--format", chart.format, "auto, s57, geojson or zip");
  upload_cmd->add_option("--min-depth", chart.minimum_depth_m, "Minimum depth (m), default 10");
  upload_cmd->add_option("--buffer", chart.safety_buffer_m, "Safety buffer (m), default 10");
  upload_cmd->callback(runner("chart upload", [&] { return RunChartUpload(options, chart); }));
  chart_cmd->add_subcommand("list", "List charts")->callback(runner("chart list", [&] {
    return RunChartList(options);
  }));
  std::string chart_id, chart_geojson;
  auto* get_cmd = chart_cmd->add_subcommand("get", "Show a chart");
  get_cmd->add_option("id", chart_id, "Chart id")->required();
  get_cmd->add_option("--geojson", chart_geojson, "Write the obstacles as GeoJSON to this file");
  get_cmd->callback(
      runner("chart get", [&] { return RunChartGet(options, chart_id, chart_geojson); }));
  std::string delete_chart_id;
  auto* delete_cmd = chart_cmd->add_subcommand(
      "delete", "Delete a chart (admin token; refused while unfinished missions use it)");
  delete_cmd->add_option("id", delete_chart_id, "Chart id")->required();
  delete_cmd->callback(
      runner("chart delete", [&] { return RunChartDelete(options, delete_chart_id); }));

  RouteArgs route;
  auto* route_cmd =
      app.add_subcommand("route", "Plan a risk-aware route with its MSO mode schedule");
  AddRouteOptions(route_cmd, route);
  route_cmd->add_option("--from", route.from, "Start LAT,LON")->required();
  route_cmd->add_option("--to", route.to, "Goal LAT,LON")->required();
  route_cmd->add_option("--particles", route.particles, "PSO particles, default 30");
  route_cmd->add_option("--iterations", route.iterations, "PSO iterations, default 100");
  route_cmd->add_option("--segments", route.segments, "Segments per alternative, default 20");
  route_cmd->add_option("--seed", route.seed, "Random seed");
  route_cmd->add_option("--safety-distance", route.safety_distance_m,
                        "Level-1 margin (m), default 50");
  route_cmd->add_option("--speed", route.speed_mps, "Planning speed (m/s)");
  route_cmd->add_option("--geojson", route.geojson, "Write routes and obstacles as GeoJSON");
  route_cmd->callback(runner("route", [&] { return RunRoute(options, route); }));

  RouteArgs risk;
  auto* risk_cmd = app.add_subcommand("risk", "Grounding risk along a route or track");
  AddRouteOptions(risk_cmd, risk);
  risk_cmd
      ->add_option("--track", risk.track, "CSV: lat,lon[,heading_deg[,speed_mps[,mode]]] per line")
      ->required();
  risk_cmd->callback(runner("risk", [&] { return RunRisk(options, risk); }));

  auto* mission_cmd = app.add_subcommand("mission", "Create, watch and steer missions");
  mission_cmd->require_subcommand(1);
  MissionArgs mission;
  auto* create_cmd = mission_cmd->add_subcommand("create", "Create a mission");
  create_cmd->add_option("--spec", mission.spec, "MissionSpec as JSON");
  create_cmd->add_option("--domain", mission.domain, "PDDL domain (overrides the spec's)");
  create_cmd->add_option("--problem", mission.problem, "PDDL problem (overrides the spec's)");
  create_cmd->callback(
      runner("mission create", [&] { return RunMissionCreate(options, mission); }));
  auto* mget_cmd = mission_cmd->add_subcommand("get", "Show a mission");
  mget_cmd->add_option("id", mission.id, "Mission id")->required();
  mget_cmd->callback(runner("mission get", [&] { return RunMissionGet(options, mission.id); }));
  mission_cmd->add_subcommand("list", "List missions")->callback(runner("mission list", [&] {
    return RunMissionList(options);
  }));
  auto* watch_cmd =
      mission_cmd->add_subcommand("watch", "Follow a mission's plan versions and log");
  watch_cmd->add_option("id", mission.id, "Mission id")->required();
  watch_cmd->add_option("--after-version", mission.after_version, "Resume after this plan version");
  watch_cmd->add_option("--after-event", mission.after_event, "Resume after this log event id");
  watch_cmd->callback(runner("mission watch", [&] { return RunMissionWatch(options, mission); }));
  auto* replan_cmd = mission_cmd->add_subcommand("replan", "Ask for a new plan");
  replan_cmd->add_option("id", mission.id, "Mission id")->required();
  replan_cmd->add_option("--reason", mission.reason, "Why");
  replan_cmd->callback(
      runner("mission replan", [&] { return RunMissionReplan(options, mission); }));
  auto* cancel_cmd = mission_cmd->add_subcommand("cancel", "Cancel a mission");
  cancel_cmd->add_option("id", mission.id, "Mission id")->required();
  cancel_cmd->add_option("--reason", mission.reason, "Why");
  cancel_cmd->callback(
      runner("mission cancel", [&] { return RunMissionCancel(options, mission); }));

  auto* feedback_cmd = mission_cmd->add_subcommand(
      "feedback", "List a mission's stored feedback reports (oldest first)");
  feedback_cmd->add_option("id", mission.id, "Mission id")->required();
  feedback_cmd->add_option("--after-sequence", mission.after_sequence,
                           "Start after this stored report (its seq; 0: from the first)");
  feedback_cmd->add_option("--page-size", mission.page_size,
                           "Reports per call, default 50, at most 1000");
  feedback_cmd->add_option("--limit", mission.limit, "Print at most this many (0: all)");
  feedback_cmd->callback(
      runner("mission feedback", [&] { return RunMissionFeedback(options, mission); }));

  TokenArgs token_args;
  auto* token_cmd = app.add_subcommand("token", "API tokens (admin; needs --server)");
  token_cmd->require_subcommand(1);
  auto* tcreate_cmd = token_cmd->add_subcommand("create", "Create a token (printed once)");
  tcreate_cmd->add_option("--role", token_args.role, "admin, operator, viewer or vessel")
      ->required();
  tcreate_cmd->add_option("--vessel", token_args.vessel, "Vessel id a vessel token is bound to");
  tcreate_cmd->add_option("--description", token_args.description, "What the token is for");
  tcreate_cmd->add_option("--expires-in-s", token_args.expires_in_s, "Lifetime (s); 0: none");
  tcreate_cmd->callback(
      runner("token create", [&] { return RunTokenCreate(options, token_args); }));
  token_cmd->add_subcommand("list", "List tokens (never their secrets)")
      ->callback(runner("token list", [&] { return RunTokenList(options); }));
  auto* trevoke_cmd = token_cmd->add_subcommand("revoke", "Revoke a token");
  trevoke_cmd->add_option("id", token_args.id, "Token id")->required();
  trevoke_cmd->callback(
      runner("token revoke", [&] { return RunTokenRevoke(options, token_args); }));
  app.add_subcommand("audit", "Show the audit log (admin; needs --server)")
      ->callback(runner("audit", [&] { return RunAudit(options); }));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitSuccess : kExitBadInput;
  }
  if (!handed_over.empty()) return executable.hand_over(handed_over, options.server, argv);
  return exit_code;
}

}  // namespace seaplan::cli
