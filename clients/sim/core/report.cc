#include "report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "seaplan/common/json.h"

namespace seaplan::sim {
namespace {

std::string Num(double v) {
  if (!std::isfinite(v)) return "null";
  return absl::StrFormat("%.6g", v);
}
std::string Num3(double v) {
  if (!std::isfinite(v)) return "null";
  return absl::StrFormat("%.3f", v);
}

// Text and attribute values in the SVG plots: names and reasons such as
// "fuel 30% <= 30%" must not break the XML.
std::string XmlText(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        // Control characters other than tab/newline are not allowed in XML 1.0.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r') {
          out += ' ';
        } else {
          out += c;
        }
    }
  }
  return out;
}

const char* KindColour(mission::TaskKind k) {
  switch (k) {
    case mission::TaskKind::kMove:
      return "#4a90d9";
    case mission::TaskKind::kLoad:
      return "#7bc043";
    case mission::TaskKind::kUnload:
      return "#f6a623";
    case mission::TaskKind::kRepair:
      return "#d0021b";
    case mission::TaskKind::kRefuel:
      return "#9b59b6";
    default:
      return "#999999";
  }
}

}  // namespace

std::string ToJson(const MissionReport& r) {
  std::ostringstream o;
  o << "{\n  \"mission_id\": " << JsonString(r.mission_id)
    << ",\n  \"scenario\": " << JsonString(r.scenario)
    << ",\n  \"completed\": " << (r.completed ? "true" : "false")
    << ",\n  \"end_time_s\": " << Num3(r.end_time_s)
    << ",\n  \"safety_distance_m\": " << Num(r.safety_distance_m)
    << ",\n  \"tank_ran_dry\": " << (r.tank_ran_dry ? "true" : "false")
    << ",\n  \"min_fuel_fraction\": " << Num(r.min_fuel_fraction)
    << ",\n  \"fuel_triggered_replans\": " << r.fuel_triggered_replans;
  if (r.land_known) {
    o << ",\n  \"min_land_clearance_m\": " << Num(r.min_land_clearance_m)
      << ",\n  \"min_land_clearance_time_s\": " << Num3(r.min_land_clearance_time_s)
      << ",\n  \"aground_s\": " << Num3(r.aground_s);
  }
  o << ",\n  \"cpa\": [";
  bool first = true;
  for (const auto& [id, c] : r.cpa) {
    o << (first ? "\n" : ",\n") << "    {\"vessel\": " << JsonString(c.vessel)
      << ", \"min_distance_m\": " << Num(c.min_distance_m) << ", \"time_s\": " << Num3(c.time_s)
      << "}";
    first = false;
  }
  o << "\n  ],\n  \"plan_versions\": [";
  first = true;
  for (const mission::PlanVersion& v : r.versions) {
    o << (first ? "\n" : ",\n") << "    {\"version\": " << v.version
      << ", \"reason\": " << JsonString(v.reason)
      << ", \"origin_s\": " << Num3(v.mission_time_origin_s)
      << ", \"makespan_s\": " << Num3(v.makespan_s) << ", \"tasks\": [";
    bool ft = true;
    for (const mission::Task& t : v.tasks) {
      o << (ft ? "" : ", ") << "{\"id\": " << JsonString(t.id)
        << ", \"kind\": " << JsonString(mission::TaskKindName(t.kind))
        << ", \"action\": " << JsonString(t.action.DisplayName())
        << ", \"start_s\": " << Num3(t.start_s) << ", \"duration_s\": " << Num3(t.duration_s);
      if (t.route) {
        // The refined route (local frame, metres): what the executor follows,
        // so a track can be checked against it (cross-track error, land).
        o << ", \"route_length_m\": " << Num3(t.route->length_m)
          << ", \"route_sailing_time_s\": " << Num3(t.route->sailing_time_s) << ", \"route\": [";
        bool fw = true;
        for (const mission::RouteWaypoint& w : t.route->waypoints) {
          o << (fw ? "" : ", ") << "[" << Num3(w.position.east_m) << ", "
            << Num3(w.position.north_m) << ", " << JsonString(mission::MsoModeName(w.mode)) << "]";
          fw = false;
        }
        o << "]";
      }
      o << "}";
      ft = false;
    }
    o << "]}";
    first = false;
  }
  o << "\n  ],\n  \"navigation_log\": [";
  first = true;
  for (const mission::LogEntry& e : r.log.entries()) {
    o << (first ? "\n" : ",\n") << "    {\"t\": " << Num3(e.mission_time_s)
      << ", \"source\": " << JsonString(e.source) << ", \"message\": " << JsonString(e.message)
      << "}";
    first = false;
  }
  o << "\n  ],\n  \"fuel\": [";
  first = true;
  for (const auto& [t, f] : r.fuel) {
    o << (first ? "" : ", ") << "[" << Num3(t) << ", " << Num(f) << "]";
    first = false;
  }
  o << "],\n  \"trajectory\": [";
  first = true;
  for (const TimedPoint& p : r.trajectory) {
    o << (first ? "" : ", ") << "[" << Num3(p.time_s) << ", " << Num3(p.position.east_m) << ", "
      << Num3(p.position.north_m) << "]";
    first = false;
  }
  o << "]\n}\n";
  return o.str();
}

std::string TrajectorySvg(const MissionReport& r, const Rings& obstacles,
                          const mission::LocationTable& locations) {
  double minx = std::numeric_limits<double>::infinity(), miny = minx, maxx = -minx, maxy = -minx;
  auto grow = [&](double x, double y) {
    minx = std::min(minx, x);
    maxx = std::max(maxx, x);
    miny = std::min(miny, y);
    maxy = std::max(maxy, y);
  };
  for (const TimedPoint& p : r.trajectory) grow(p.position.east_m, p.position.north_m);
  for (const auto& [name, p] : locations) grow(p.east_m, p.north_m);
  if (!std::isfinite(minx)) grow(0, 0);
  double margin = std::max({200.0, (maxx - minx) * 0.1, (maxy - miny) * 0.1});
  minx -= margin;
  maxx += margin;
  miny -= margin;
  maxy += margin;
  const double width = 900;
  const double scale = width / std::max(1.0, maxx - minx);
  const double height = (maxy - miny) * scale;
  auto X = [&](double x) { return (x - minx) * scale; };
  auto Y = [&](double y) { return (maxy - y) * scale; };
  std::ostringstream o;
  o << absl::StrFormat(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f "
      "%.0f\">\n",
      width, height, width, height);
  o << "<rect width=\"100%\" height=\"100%\" fill=\"#dceefc\"/>\n";
  for (const auto& ring : obstacles) {
    bool inside = false;
    for (const EastNorth& p : ring) {
      if (p.east_m > minx && p.east_m < maxx && p.north_m > miny && p.north_m < maxy) inside = true;
    }
    if (!inside) continue;
    o << "<polygon fill=\"#c8b88a\" stroke=\"#8a7a50\" stroke-width=\"0.5\" points=\"";
    for (const EastNorth& p : ring) o << absl::StrFormat("%.1f,%.1f ", X(p.east_m), Y(p.north_m));
    o << "\"/>\n";
  }
  const char* colours[] = {"#e67e22", "#16a085", "#8e44ad", "#c0392b"};
  int ci = 0;
  for (const auto& [name, track] : r.traffic_tracks) {
    o << "<polyline fill=\"none\" stroke=\"" << colours[ci++ % 4]
      << "\" stroke-dasharray=\"6,4\" points=\"";
    for (const TimedPoint& p : track)
      o << absl::StrFormat("%.1f,%.1f ", X(p.position.east_m), Y(p.position.north_m));
    o << "\"/>\n";
    if (!track.empty()) {
      o << absl::StrFormat("<text x=\"%.1f\" y=\"%.1f\" font-size=\"12\">%s</text>\n",
                           X(track.front().position.east_m), Y(track.front().position.north_m),
                           XmlText(name));
    }
  }
  o << "<polyline fill=\"none\" stroke=\"#1f3a93\" stroke-width=\"2\" points=\"";
  for (const TimedPoint& p : r.trajectory)
    o << absl::StrFormat("%.1f,%.1f ", X(p.position.east_m), Y(p.position.north_m));
  o << "\"/>\n";
  for (const auto& [name, p] : locations) {
    o << absl::StrFormat("<circle cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"#000\"/>\n", X(p.east_m),
                         Y(p.north_m));
    o << absl::StrFormat("<text x=\"%.1f\" y=\"%.1f\" font-size=\"13\">%s</text>\n",
                         X(p.east_m) + 6, Y(p.north_m) - 6, XmlText(name));
  }
  o << "</svg>\n";
  return o.str();
}

std::string GanttSvg(const MissionReport& r) {
  double end = 1.0;
  size_t rows = 0;
  for (const auto& v : r.versions) {
    for (const auto& t : v.tasks) end = std::max(end, t.end_s());
    rows += v.tasks.size() + 1;
  }
  const double left = 330, width = 1100, row_h = 16;
  const double scale = (width - left - 20) / end;
  const double height = (rows + 2) * row_h + 20;
  std::ostringstream o;
  o << absl::StrFormat(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\">\n", width, height);
  o << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  double y = 20;
  for (const auto& v : r.versions) {
    o << absl::StrFormat(
        "<text x=\"4\" y=\"%.0f\" font-size=\"12\" font-weight=\"bold\">version %d: %s</text>\n",
        y + 12, v.version, XmlText(v.reason));
    y += row_h;
    for (const auto& t : v.tasks) {
      o << absl::StrFormat("<text x=\"12\" y=\"%.0f\" font-size=\"11\">%s</text>\n", y + 11,
                           XmlText(t.action.DisplayName()));
      o << absl::StrFormat(
          "<rect x=\"%.1f\" y=\"%.0f\" width=\"%.1f\" height=\"%.0f\" fill=\"%s\"/>\n",
          left + t.start_s * scale, y + 2, std::max(1.0, t.duration_s * scale), row_h - 4,
          KindColour(t.kind));
      y += row_h;
    }
  }
  for (double t = 0; t <= end; t += std::max(100.0, std::round(end / 10 / 100) * 100)) {
    o << absl::StrFormat("<text x=\"%.1f\" y=\"%.0f\" font-size=\"10\">%.0f</text>\n",
                         left + t * scale, y + 14, t);
  }
  o << "</svg>\n";
  return o.str();
}

Status WriteReport(const std::string& dir, const MissionReport& report, const Rings& obstacles,
                   const mission::LocationTable& locations) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec)
    return absl::InternalError(
        absl::StrCat("cannot create report folder ", dir, ": ", ec.message()));
  auto write = [&](const std::string& name, const std::string& text) -> Status {
    std::ofstream out(dir + "/" + name);
    out << text;
    if (!out) return absl::InternalError(absl::StrCat("cannot write ", dir, "/", name));
    return absl::OkStatus();
  };
  SEAPLAN_RETURN_IF_ERROR(write("report.json", ToJson(report)));
  SEAPLAN_RETURN_IF_ERROR(write("trajectory.svg", TrajectorySvg(report, obstacles, locations)));
  return write("gantt.svg", GanttSvg(report));
}

}  // namespace seaplan::sim
