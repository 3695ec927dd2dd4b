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

namespace {

// The console's colours for the MSO modes, so the report reads the same.
const char* ModeColour(mission::MsoMode m) {
  switch (m) {
    case mission::MsoMode::kPto:
      return "#2f7fd8";
    case mission::MsoMode::kMec:
      return "#1fa37a";
    case mission::MsoMode::kPti:
      return "#e08a1e";
    default:
      return "#1f3a93";
  }
}

// The largest 1, 2 or 5 times a power of ten not above `limit` (> 0).
double RoundDown125(double limit) {
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  for (const double f : {5.0, 2.0, 1.0}) {
    if (f * decade <= limit) return f * decade;
  }
  return decade;
}

std::string LengthLabel(double m) {
  constexpr double kMetresPerNm = 1852.0;
  const std::string metric =
      m >= 1000 ? absl::StrFormat("%g km", m / 1000) : absl::StrFormat("%g m", m);
  return absl::StrFormat("%s (%.2f NM)", metric, m / kMetresPerNm);
}

// Mission time as h:mm:ss.
std::string ClockLabel(double s) {
  const long total = std::lround(s);
  return absl::StrFormat("%d:%02d:%02d", total / 3600, total / 60 % 60, total % 60);
}

// A time-mark interval giving about `marks` marks over `span_s`.
double MarkInterval(double span_s, double marks) {
  for (const double step : {60.0, 120.0, 300.0, 600.0, 900.0, 1800.0, 3600.0, 7200.0}) {
    if (span_s / step <= marks) return step;
  }
  return 3600.0 * std::ceil(span_s / marks / 3600.0);
}

}  // namespace

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
  const double scale = width / std::max(1.0, maxx - minx);  // px per metre
  // Room below the chart for the scale bar, the time-mark note and the title.
  const double chart_height = (maxy - miny) * scale;
  const double height = chart_height + 50;
  auto X = [&](double x) { return (x - minx) * scale; };
  auto Y = [&](double y) { return (maxy - y) * scale; };
  std::ostringstream o;
  o << absl::StrFormat(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f "
      "%.0f\" font-family=\"sans-serif\">\n",
      width, height, width, height);
  o << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  o << absl::StrFormat("<rect width=\"%.0f\" height=\"%.1f\" fill=\"#dceefc\"/>\n", width,
                       chart_height);
  for (const auto& ring : obstacles) {
    bool inside = false;
    for (const EastNorth& p : ring) {
      if (p.east_m > minx && p.east_m < maxx && p.north_m > miny && p.north_m < maxy) inside = true;
    }
    if (!inside) continue;
    o << "<polygon class=\"land\" fill=\"#c8b88a\" stroke=\"#8a7a50\" stroke-width=\"0.5\" "
         "points=\"";
    for (const EastNorth& p : ring) o << absl::StrFormat("%.1f,%.1f ", X(p.east_m), Y(p.north_m));
    o << "\"/>\n";
  }
  const char* colours[] = {"#e67e22", "#16a085", "#8e44ad", "#c0392b"};
  int ci = 0;
  for (const auto& [name, track] : r.traffic_tracks) {
    o << "<polyline class=\"traffic\" fill=\"none\" stroke=\"" << colours[ci++ % 4]
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
  // The track, one polyline per run of one machinery mode (each run starts
  // at the point where the previous one ended, so the line is unbroken).
  for (std::size_t i = 0; i + 1 < r.trajectory.size();) {
    const mission::MsoMode mode = r.trajectory[i + 1].mode;
    o << absl::StrFormat(
        "<polyline class=\"track\" data-mode=\"%s\" fill=\"none\" stroke=\"%s\" "
        "stroke-width=\"2.5\" points=\"",
        mission::MsoModeName(mode), ModeColour(mode));
    std::size_t j = i;
    for (; j < r.trajectory.size() && (j == i || r.trajectory[j].mode == mode); ++j) {
      o << absl::StrFormat("%.1f,%.1f ", X(r.trajectory[j].position.east_m),
                           Y(r.trajectory[j].position.north_m));
    }
    o << "\"/>\n";
    i = j - 1;
  }
  // Time marks: the first position sampled at or after each whole interval.
  if (!r.trajectory.empty()) {
    const double t0 = r.trajectory.front().time_s;
    const double step = MarkInterval(r.trajectory.back().time_s - t0, 12);
    double next = std::ceil(t0 / step) * step;
    for (const TimedPoint& p : r.trajectory) {
      if (p.time_s + 1e-9 < next) continue;
      o << absl::StrFormat(
          "<g class=\"time-mark\" data-t=\"%.0f\"><circle cx=\"%.1f\" cy=\"%.1f\" r=\"3\" "
          "fill=\"#fff\" stroke=\"#1f3a93\"/><text x=\"%.1f\" y=\"%.1f\" font-size=\"10\" "
          "fill=\"#1f3a93\">%s</text></g>\n",
          p.time_s, X(p.position.east_m), Y(p.position.north_m), X(p.position.east_m) + 5,
          Y(p.position.north_m) + 12, ClockLabel(p.time_s));
      next = (std::floor(p.time_s / step) + 1) * step;
    }
  }
  for (const auto& [name, p] : locations) {
    o << absl::StrFormat(
        "<circle class=\"location\" cx=\"%.1f\" cy=\"%.1f\" r=\"4\" fill=\"#000\"/>\n", X(p.east_m),
        Y(p.north_m));
    o << absl::StrFormat("<text x=\"%.1f\" y=\"%.1f\" font-size=\"13\">%s</text>\n",
                         X(p.east_m) + 6, Y(p.north_m) - 6, XmlText(name));
  }
  // North arrow (the plot is north up).
  o << absl::StrFormat(
      "<g class=\"north-arrow\"><polygon points=\"%.1f,10 %.1f,34 %.1f,28 %.1f,34\" "
      "fill=\"#222\"/><text x=\"%.1f\" y=\"47\" font-size=\"12\" text-anchor=\"middle\">N</text>"
      "</g>\n",
      width - 24, width - 16, width - 24, width - 32, width - 24);
  // Legend.
  struct Entry {
    std::string label, colour;
    bool dashed;
  };
  std::vector<Entry> entries;
  for (const mission::MsoMode m :
       {mission::MsoMode::kPto, mission::MsoMode::kMec, mission::MsoMode::kPti}) {
    entries.push_back(
        {absl::StrCat("track, ", std::string(mission::MsoModeName(m))), ModeColour(m), false});
  }
  if (!r.traffic_tracks.empty()) entries.push_back({"traffic", colours[0], true});
  o << absl::StrFormat(
      "<g class=\"legend\"><rect x=\"8\" y=\"8\" width=\"170\" height=\"%d\" fill=\"#fff\" "
      "fill-opacity=\"0.85\" stroke=\"#888\"/>\n",
      static_cast<int>(entries.size() + 2) * 16 + 8);
  double ly = 24;
  for (const Entry& e : entries) {
    o << absl::StrFormat(
        "<line x1=\"16\" y1=\"%.0f\" x2=\"40\" y2=\"%.0f\" stroke=\"%s\" stroke-width=\"2.5\"%s/>"
        "<text x=\"46\" y=\"%.0f\" font-size=\"11\">%s</text>\n",
        ly - 4, ly - 4, e.colour, e.dashed ? " stroke-dasharray=\"6,4\"" : "", ly, e.label);
    ly += 16;
  }
  o << absl::StrFormat(
      "<rect x=\"16\" y=\"%.0f\" width=\"24\" height=\"9\" fill=\"#c8b88a\" stroke=\"#8a7a50\"/>"
      "<text x=\"46\" y=\"%.0f\" font-size=\"11\">land</text>\n",
      ly - 9, ly);
  ly += 16;
  o << absl::StrFormat(
      "<circle cx=\"28\" cy=\"%.0f\" r=\"3\" fill=\"#fff\" stroke=\"#1f3a93\"/>"
      "<text x=\"46\" y=\"%.0f\" font-size=\"11\">mission time h:mm:ss</text></g>\n",
      ly - 4, ly);
  // Scale bar: a round length about a fifth of the width.
  const double bar_m = RoundDown125(width / 5 / scale);
  const double bar_y = chart_height + 20;
  o << absl::StrFormat(
      "<g class=\"scale-bar\" data-m=\"%g\"><line x1=\"10\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" "
      "stroke=\"#000\" stroke-width=\"3\"/><line x1=\"10\" y1=\"%.1f\" x2=\"10\" y2=\"%.1f\" "
      "stroke=\"#000\"/><line x1=\"%.1f\" y1=\"%.1f\" x2=\"%.1f\" y2=\"%.1f\" stroke=\"#000\"/>"
      "<text x=\"10\" y=\"%.1f\" font-size=\"12\">%s</text></g>\n",
      bar_m, bar_y, 10 + bar_m * scale, bar_y, bar_y - 5, bar_y + 5, 10 + bar_m * scale, bar_y - 5,
      10 + bar_m * scale, bar_y + 5, bar_y + 18, LengthLabel(bar_m));
  const double end_s = r.trajectory.empty() ? 0.0 : r.trajectory.back().time_s;
  o << absl::StrFormat(
      "<text x=\"%.0f\" y=\"%.1f\" font-size=\"12\" text-anchor=\"end\">%s%s, mission time "
      "0:00:00 to %s</text>\n",
      width - 10, bar_y + 18, XmlText(r.scenario.empty() ? "mission" : r.scenario),
      r.mission_id.empty() ? "" : XmlText(absl::StrCat(" ", r.mission_id)), ClockLabel(end_s));
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
  const double legend_h = 24;
  const double height = (rows + 2) * row_h + 36 + legend_h;
  std::ostringstream o;
  o << absl::StrFormat(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"%.0f\" height=\"%.0f\" viewBox=\"0 0 %.0f "
      "%.0f\" font-family=\"sans-serif\">\n",
      width, height, width, height);
  o << "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  // Legend: the task kinds' colours.
  double lx = 4;
  for (const mission::TaskKind k :
       {mission::TaskKind::kMove, mission::TaskKind::kLoad, mission::TaskKind::kUnload,
        mission::TaskKind::kRepair, mission::TaskKind::kRefuel, mission::TaskKind::kOther}) {
    const std::string_view name = mission::TaskKindName(k);
    o << absl::StrFormat(
        "<g class=\"legend\"><rect x=\"%.0f\" y=\"6\" width=\"14\" height=\"10\" fill=\"%s\"/>"
        "<text x=\"%.0f\" y=\"15\" font-size=\"11\">%s</text></g>\n",
        lx, KindColour(k), lx + 18, XmlText(name));
    lx += 30 + 7.0 * static_cast<double>(name.size());
  }
  const double top = legend_h;
  const double step = std::max(60.0, MarkInterval(end, 10));
  const double axis_bottom = top + rows * row_h + 8;
  for (double t = 0; t <= end + 1e-9; t += step) {
    o << absl::StrFormat(
        "<line class=\"time-mark\" x1=\"%.1f\" y1=\"%.0f\" x2=\"%.1f\" y2=\"%.0f\" "
        "stroke=\"#ddd\"/>\n",
        left + t * scale, top, left + t * scale, axis_bottom);
  }
  double y = top;
  for (const auto& v : r.versions) {
    o << absl::StrFormat(
        "<text x=\"4\" y=\"%.0f\" font-size=\"12\" font-weight=\"bold\">version %d: %s</text>\n",
        y + 12, v.version, XmlText(v.reason));
    y += row_h;
    for (const auto& t : v.tasks) {
      o << absl::StrFormat("<text x=\"12\" y=\"%.0f\" font-size=\"11\">%s</text>\n", y + 11,
                           XmlText(t.action.DisplayName()));
      o << absl::StrFormat(
          "<rect class=\"task\" x=\"%.1f\" y=\"%.0f\" width=\"%.1f\" height=\"%.0f\" "
          "fill=\"%s\"><title>%s</title></rect>\n",
          left + t.start_s * scale, y + 2, std::max(1.0, t.duration_s * scale), row_h - 4,
          KindColour(t.kind),
          XmlText(absl::StrCat(t.action.DisplayName(), ": ", ClockLabel(t.start_s), " to ",
                               ClockLabel(t.end_s()))));
      y += row_h;
    }
  }
  for (double t = 0; t <= end + 1e-9; t += step) {
    o << absl::StrFormat(
        "<text x=\"%.1f\" y=\"%.0f\" font-size=\"10\" text-anchor=\"middle\">%s</text>\n",
        left + t * scale, axis_bottom + 12, ClockLabel(t));
  }
  o << absl::StrFormat(
      "<text x=\"%.0f\" y=\"%.0f\" font-size=\"11\">mission time (h:mm:ss)</text>\n", left,
      axis_bottom + 28);
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
