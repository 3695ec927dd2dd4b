#include "output.h"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <iomanip>
#include <string>
#include <vector>

#include "google/protobuf/util/json_util.h"
#include "seaplan/v1/common.pb.h"
#include "seaplan/validate/plan.h"

namespace seaplan::cli {
namespace v1 = ::seaplan::v1;
namespace {

std::string Seconds(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.3f", value);
  return buffer;
}

}  // namespace

std::string ToJson(const google::protobuf::Message& message) {
  std::string json;
  google::protobuf::util::JsonPrintOptions options;
  options.preserve_proto_field_names = false;
  (void)google::protobuf::util::MessageToJsonString(message, &json, options);
  return json;
}

const char* MsoModeName(v1::MsoMode mode) {
  switch (mode) {
    case v1::MSO_MODE_PTO:
      return "PTO";
    case v1::MSO_MODE_MEC:
      return "MEC";
    case v1::MSO_MODE_PTI:
      return "PTI";
    default:
      return "-";
  }
}

std::string FormatPlanText(const v1::PlanResponse& response) {
  if (!response.plan_text().empty()) return response.plan_text();
  std::string text;
  for (const auto& action : response.plan()) {
    text += validate::FormatTime(action.start_s()) + ": (" + action.name();
    for (const auto& arg : action.arguments()) text += " " + arg;
    text += ") [" + validate::FormatTime(action.duration_s()) + "]\n";
  }
  return text;
}

void PrintPlanResponse(std::ostream& out, const v1::PlanResponse& response) {
  out << "; status: " << v1::PlanStatus_Name(response.status()) << "\n";
  if (!response.message().empty()) out << "; " << response.message() << "\n";
  if (response.plan_size() > 0) {
    out << "; makespan: " << validate::FormatTime(response.makespan_s())
        << " s, actions: " << response.plan_size();
    if (response.has_metric_value())
      out << ", metric: " << validate::FormatTime(response.metric_value());
    out << "\n";
  }
  const auto& stats = response.statistics();
  out << "; search: " << stats.expanded() << " expanded, " << stats.generated() << " generated, "
      << Seconds(stats.search_time_s()) << " s";
  if (stats.first_plan_time_s() >= 0)
    out << ", first plan " << Seconds(stats.first_plan_time_s()) << " s";
  if (stats.peak_memory_mb() > 0) out << ", peak " << stats.peak_memory_mb() << " MB";
  out << "\n";
  if (stats.symmetric_objects() > 0) {
    out << "; symmetry: " << stats.symmetric_objects() << " interchangeable objects in "
        << stats.symmetry_classes() << (stats.symmetry_classes() == 1 ? " class, " : " classes, ")
        << stats.symmetric_drops() << " states dropped\n";
  }
  if (stats.eager_ends() > 0) {
    out << "; eager ends: " << stats.eager_ends()
        << " states with an end that only adds facts took it as their only successor\n";
  }
  if (stats.first_plan_restarts() > 0) {
    out << "; restarts: the first-plan searches began again " << stats.first_plan_restarts()
        << (stats.first_plan_restarts() == 1 ? " time" : " times")
        << " with another seed (deadlines)\n";
  }
  if (stats.seed_rounds() > 0) {
    out << "; rounds with other seeds: " << stats.seed_rounds() << ", " << stats.seed_round_plans()
        << (stats.seed_round_plans() == 1 ? " plan" : " plans")
        << " shorter than the best before\n";
  }
  if (stats.suffix_searches() > 0) {
    out << "; suffix searches: " << stats.suffix_searches() << ", " << stats.suffix_plans()
        << (stats.suffix_plans() == 1 ? " plan" : " plans") << " shorter than the best before\n";
  }
  for (const auto& d : response.diagnostics()) {
    out << "; " << d.file() << ":" << d.line() << ":" << d.column() << ": " << d.message() << "\n";
  }
  out << FormatPlanText(response);
}

void PrintValidateResponse(std::ostream& out, const v1::ValidateResponse& response) {
  if (response.valid()) {
    out << "Plan valid\n";
  } else {
    const auto& f = response.first_failure();
    out << "Plan invalid\n";
    out << "  first failure at t=" << validate::FormatTime(f.time_s());
    if (f.step_index() >= 0) out << ", step " << f.step_index() + 1;
    if (!f.action().empty()) out << " " << f.action();
    out << "\n";
    if (!f.condition().empty()) out << "  condition: " << f.condition() << "\n";
    if (!f.reason().empty()) out << "  reason: " << f.reason() << "\n";
  }
  out << "  makespan: " << validate::FormatTime(response.makespan_s())
      << " s, actions: " << response.action_count();
  if (response.has_metric_value())
    out << ", metric: " << validate::FormatTime(response.metric_value());
  out << "\n";
}

void PrintChart(std::ostream& out, const v1::Chart& chart) {
  const auto& s = chart.summary();
  out << chart.chart_id() << "  " << chart.name() << "  min depth " << chart.minimum_depth_m()
      << " m, buffer " << chart.safety_buffer_m() << " m, " << s.obstacle_count() << " obstacles";
  if (!s.frame().empty()) out << ", frame " << s.frame();
  out << "\n";
  for (const auto& [layer, count] : s.count_by_layer())
    out << "    " << layer << ": " << count << "\n";
}

namespace {
void PrintAlternative(std::ostream& out, const v1::RouteAlternative& alt, bool chosen) {
  out << (chosen ? "* " : "  ") << "alternative " << alt.index() << ": length " << std::fixed
      << std::setprecision(0) << alt.length_m() << " m, sailing " << alt.sailing_time_s()
      << " s, fuel " << std::setprecision(1) << alt.fuel_kg() << " kg, expected grounding cost "
      << std::setprecision(3) << alt.expected_grounding_cost() << ", total cost "
      << alt.total_cost() << "\n";
  for (const std::string& warning : alt.warnings()) out << "    warning: " << warning << "\n";
  out << "      #  latitude    longitude   mode  TTG s   P(grounding)  E[cost]   fuel kg\n";
  int i = 0;
  for (const auto& w : alt.waypoints()) {
    char line[200];
    std::snprintf(line, sizeof line, "    %3d  %10.6f  %10.6f  %-4s  %6.0f  %12.3e  %8.3f  %7.2f\n",
                  i++, w.position().latitude_deg(), w.position().longitude_deg(),
                  MsoModeName(w.mode()), w.time_to_grounding_s(), w.grounding_probability(),
                  w.expected_grounding_cost(), w.fuel_kg());
    out << line;
  }
  out.unsetf(std::ios::floatfield);
}
}  // namespace

void PrintRoute(std::ostream& out, const v1::PlanRouteResponse& response) {
  out << response.alternatives_size()
      << " alternative(s); chosen: " << response.chosen_alternative() << "\n";
  for (const auto& alt : response.alternatives()) {
    PrintAlternative(out, alt, alt.index() == response.chosen_alternative());
  }
  if (response.mode_schedule_size() > 0) {
    out << "MSO mode schedule (chosen route):\n";
    for (const auto& entry : response.mode_schedule()) {
      out << "  " << Seconds(entry.start_s()) << " s  waypoints " << entry.from_waypoint() << "-"
          << entry.to_waypoint() << "  " << MsoModeName(entry.mode()) << " for "
          << Seconds(entry.duration_s()) << " s\n";
    }
  }
}

void PrintRisk(std::ostream& out, const v1::EstimateRiskResponse& response) {
  out << "   #  latitude    longitude   TTG s  grounds  P(grounding)  E[cost]\n";
  int i = 0;
  for (const auto& p : response.points()) {
    char line[200];
    std::snprintf(line, sizeof line, "%4d  %10.6f  %10.6f  %6.0f  %-7s  %12.3e  %8.3f\n", i++,
                  p.position().latitude_deg(), p.position().longitude_deg(),
                  p.time_to_grounding_s(), p.grounds_within_horizon() ? "yes" : "no",
                  p.grounding_probability(), p.expected_cost());
    out << line;
  }
  out << "total expected cost " << response.total_expected_cost() << ", max P(grounding) "
      << response.max_grounding_probability() << "\n";
}

void PrintMission(std::ostream& out, const v1::Mission& mission) {
  out << mission.mission_id() << "  " << mission.spec().name() << "  "
      << v1::MissionState_Name(mission.state()) << "  version " << mission.current_version();
  if (!mission.failure_reason().empty()) out << "  (" << mission.failure_reason() << ")";
  out << "\n";
}

void PrintPlanVersion(std::ostream& out, const v1::PlanVersion& version) {
  out << "plan version " << version.version() << " (" << version.reason() << "), makespan "
      << Seconds(version.makespan_s()) << " s, " << version.tasks_size() << " tasks\n";
  for (const auto& task : version.tasks()) {
    out << "  " << std::setw(9) << Seconds(task.start_s()) << "  " << task.task_id() << "  ("
        << task.action().name();
    for (const auto& arg : task.action().arguments()) out << " " << arg;
    out << ") [" << Seconds(task.duration_s()) << "]\n";
  }
}

std::string FormatTimeMs(std::int64_t ms) {
  const std::time_t seconds = static_cast<std::time_t>(ms / 1000);
  std::tm utc{};
  gmtime_r(&seconds, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M:%SZ", &utc);
  return text;
}

void PrintFeedbackTable(std::ostream& out, const v1::ListFeedbackResponse& response) {
  // The vessel column is as wide as its longest "vessel (its sequence number)".
  std::vector<std::string> vessels;
  std::size_t vessel_width = std::string("vessel (#)").size();
  for (const auto& stored : response.feedback()) {
    vessels.push_back(stored.vessel_id() + " (" + std::to_string(stored.sequence_number()) + ")");
    vessel_width = std::max(vessel_width, vessels.back().size());
  }
  const int width = static_cast<int>(vessel_width);
  char line[512];
  std::snprintf(line, sizeof line,
                "%6s  %-*s  %-20s  %9s  %-20s  %-12s  %9s  %10s  %7s  %9s  %-4s  %4s  %s\n", "seq",
                width, "vessel (#)", "received", "mission s", "kind", "task", "latitude",
                "longitude", "hdg deg", "speed m/s", "mode", "fuel", "detail");
  out << line;
  int row = 0;
  for (const auto& stored : response.feedback()) {
    const v1::Feedback& f = stored.feedback();
    const v1::ShipState& s = f.state();
    std::string kind = v1::Feedback_Kind_Name(f.kind());
    if (kind.rfind("KIND_", 0) == 0) kind = kind.substr(5);
    const std::int64_t received_ms =
        stored.received_at().seconds() * 1000 + stored.received_at().nanos() / 1000000;
    std::snprintf(line, sizeof line,
                  "%6lld  %-*s  %-20s  %9.1f  %-20s  %-12s  %9.5f  %10.5f  %7.1f  %9.2f  %-4s  "
                  "%3.0f%%",
                  static_cast<long long>(stored.sequence()), width, vessels[row++].c_str(),
                  FormatTimeMs(received_ms).c_str(), f.mission_time_s(), kind.c_str(),
                  f.task_id().empty() ? "-" : f.task_id().c_str(), s.position().latitude_deg(),
                  s.position().longitude_deg(), s.heading_deg(), s.speed_mps(),
                  MsoModeName(s.mode()), s.fuel_fraction() * 100);
    out << line;
    if (!f.detail().empty()) out << "  " << f.detail();
    out << "\n";
  }
}

void PrintLogEvent(std::ostream& out, const v1::LogEvent& event) {
  out << "[" << std::setw(9) << Seconds(event.mission_time_s()) << " s] " << event.source() << ": "
      << event.message() << "\n";
}

int ReportError(std::ostream& err, const absl::Status& status) {
  err << "error: " << absl::StatusCodeToString(status.code()) << ": " << status.message() << "\n";
  if (auto payload = status.GetPayload(kDiagnosticsPayloadUrl)) {
    v1::DiagnosticList list;
    if (list.ParseFromString(std::string(*payload))) {
      for (const auto& d : list.diagnostics()) {
        err << "  " << d.file() << ":" << d.line() << ":" << d.column() << ": " << d.message();
        if (!d.symbol().empty()) err << " (found '" << d.symbol() << "'";
        if (!d.expected().empty())
          err << (d.symbol().empty() ? " (" : ", ") << "expected " << d.expected();
        if (!d.symbol().empty() || !d.expected().empty()) err << ")";
        err << "\n";
      }
    }
  }
  switch (status.code()) {
    case absl::StatusCode::kInvalidArgument:
    case absl::StatusCode::kNotFound:
    case absl::StatusCode::kFailedPrecondition:
    case absl::StatusCode::kOutOfRange:
      return kExitBadInput;
    default:
      return kExitServiceError;
  }
}

}  // namespace seaplan::cli
