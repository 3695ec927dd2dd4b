#include "scenario.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "absl/strings/ascii.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"

namespace seaplan::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

std::vector<std::string> Words(std::string_view v) {
  return absl::StrSplit(absl::string_view(v.data(), v.size()), absl::ByAnyChar(" \t"),
                        absl::SkipEmpty());
}

bool ParseDoubles(const std::vector<std::string>& w, size_t from, size_t count,
                  std::vector<double>* out) {
  if (w.size() < from + count) return false;
  for (size_t i = from; i < from + count; ++i) {
    double v;
    if (!absl::SimpleAtod(w[i], &v) || !std::isfinite(v)) return false;
    out->push_back(v);
  }
  return true;
}

}  // namespace

StatusOr<Scenario> ParseScenario(std::string_view text, std::string_view file) {
  Scenario s;
  s.file = std::string(file);
  int line_no = 0;
  std::vector<std::string> lines =
      absl::StrSplit(absl::string_view(text.data(), text.size()), '\n');
  for (const std::string& raw : lines) {
    ++line_no;
    std::string line = raw.substr(0, raw.find('#'));
    std::string l(absl::StripAsciiWhitespace(line));
    if (l.empty()) continue;
    auto err = [&](std::string_view what) {
      return absl::InvalidArgumentError(
          absl::StrCat(std::string(file), ":", line_no, ": ", std::string(what)));
    };
    size_t eq = l.find('=');
    if (eq == std::string::npos) return err("expected 'key = value'");
    std::string key(absl::StripAsciiWhitespace(l.substr(0, eq)));
    std::string value(absl::StripAsciiWhitespace(l.substr(eq + 1)));
    std::vector<std::string> w = Words(value);
    std::vector<double> d;
    auto number = [&](double* out) -> Status {
      if (!ParseDoubles(w, 0, 1, &d) || w.size() != 1)
        return err(absl::StrCat(key, ": expected one number"));
      *out = d[0];
      return absl::OkStatus();
    };
    auto latlon = [&](size_t from, chart::LatLon* out) -> Status {
      std::vector<double> v;
      if (!ParseDoubles(w, from, 2, &v) || std::abs(v[0]) > 90 || std::abs(v[1]) > 180) {
        return err(absl::StrCat(key, ": expected 'lat lon' in degrees"));
      }
      *out = {v[0], v[1]};
      return absl::OkStatus();
    };
    if (key == "name") {
      s.name = value;
    } else if (key == "domain") {
      s.domain_path = value;
    } else if (key == "problem") {
      s.problem_path = value;
    } else if (key == "chart") {
      s.chart_path = value;
    } else if (key == "location") {
      chart::LatLon p;
      if (w.size() != 3) return err("location: expected 'name lat lon'");
      SEAPLAN_RETURN_IF_ERROR(latlon(1, &p));
      s.locations.emplace_back(absl::AsciiStrToLower(w[0]), p);
    } else if (key == "ship_object") {
      s.ship_object = absl::AsciiStrToLower(value);
    } else if (key == "vessel_id") {
      s.vessel_id = value;
    } else if (key == "service_speed_mps") {
      SEAPLAN_RETURN_IF_ERROR(number(&s.service_speed_mps));
      if (!(s.service_speed_mps > 0)) return err("service_speed_mps must be > 0");
    } else if (key == "start") {
      chart::LatLon p;
      SEAPLAN_RETURN_IF_ERROR(latlon(0, &p));
      s.start = p;
    } else if (key == "start_heading_deg") {
      SEAPLAN_RETURN_IF_ERROR(number(&s.start_heading_deg));
    } else if (key == "initial_fuel") {
      SEAPLAN_RETURN_IF_ERROR(number(&s.initial_fuel));
      if (s.initial_fuel < 0 || s.initial_fuel > 1) return err("initial_fuel must be in [0, 1]");
    } else if (key == "fuel_model") {
      if (value == "percentage") {
        s.fuel_model = FuelModelKind::kPercentage;
      } else if (value == "machinery") {
        s.fuel_model = FuelModelKind::kMachinery;
      } else {
        return err("fuel_model: expected 'percentage' or 'machinery'");
      }
    } else if (key == "fuel_threshold") {
      SEAPLAN_RETURN_IF_ERROR(number(&s.fuel_threshold));
    } else if (key == "fuel_function") {
      s.fuel_function = absl::AsciiStrToLower(value);
    } else if (key == "position_deviation_m") {
      SEAPLAN_RETURN_IF_ERROR(number(&s.position_deviation_m));
    } else if (key == "delay_tolerance_s") {
      SEAPLAN_RETURN_IF_ERROR(number(&s.delay_tolerance_s));
    } else if (key == "safety_distance_m") {
      SEAPLAN_RETURN_IF_ERROR(number(&s.safety_distance_m));
    } else if (key == "planner_time_limit_s") {
      SEAPLAN_RETURN_IF_ERROR(number(&s.planner_time_limit_s));
    } else if (key == "planner_max_expansions") {
      if (w.size() != 1 || !absl::SimpleAtoi(w[0], &s.planner_max_expansions)) {
        return err("planner_max_expansions: expected a whole number >= 0 (0: no limit)");
      }
    } else if (key == "time_factor") {
      SEAPLAN_RETURN_IF_ERROR(number(&s.time_factor));
    } else if (key == "port_operation") {
      if (w.size() != 2 || !ParseDoubles(w, 1, 1, &d) || d[0] < 0) {
        return err("port_operation: expected 'action seconds'");
      }
      s.port_operations.emplace_back(absl::AsciiStrToLower(w[0]), d[0]);
    } else if (key == "wind" || key == "current") {
      if (w.size() != 2 || !ParseDoubles(w, 0, 2, &d) || d[0] < 0) {
        return err(absl::StrCat(key, ": expected 'speed_mps from_deg'"));
      }
      (key == "wind" ? s.wind_speed_mps : s.current_speed_mps) = d[0];
      (key == "wind" ? s.wind_from_deg : s.current_from_deg) = d[1];
    } else if (key == "grid") {
      chart::LatLon p;
      SEAPLAN_RETURN_IF_ERROR(latlon(0, &p));
      if (w.size() != 3 || !ParseDoubles(w, 2, 1, &d) || !(d[0] > 0)) {
        return err("grid: expected 'lat lon cell_m'");
      }
      s.grid_origin = p;
      s.grid_cell_m = d[0];
    } else if (key == "gnss_jump") {
      if (w.size() != 6 || !ParseDoubles(w, 0, 6, &d) || d[1] < d[0]) {
        return err("gnss_jump: expected 'start_s end_s from_i from_j to_i to_j'");
      }
      s.gnss_jumps.push_back({d[0], d[1], {d[2], d[3]}, {d[4], d[5]}});
    } else if (key == "traffic") {
      std::vector<std::string> parts = absl::StrSplit(value, ';');
      ScenarioTraffic t;
      for (size_t i = 0; i < parts.size(); ++i) {
        std::vector<std::string> pw = Words(parts[i]);
        size_t off = 0;
        if (i == 0) {
          if (pw.size() != 5)
            return err("traffic: expected 'name kind t lat lon ; t lat lon ; ...'");
          t.name = pw[0];
          t.kind = pw[1];
          off = 2;
        }
        std::vector<double> v;
        if (pw.size() != off + 3 || !ParseDoubles(pw, off, 3, &v)) {
          return err("traffic: each point is 't lat lon'");
        }
        if (!t.track.empty() && v[0] <= t.track.back().time_s)
          return err("traffic: times must increase");
        t.track.push_back({v[0], {v[1], v[2]}});
      }
      s.traffic.push_back(std::move(t));
    } else {
      return err(absl::StrCat("unknown key '", key, "'"));
    }
  }
  if (s.domain_path.empty() || s.problem_path.empty()) {
    return absl::InvalidArgumentError(
        absl::StrCat(std::string(file), ": 'domain' and 'problem' are required"));
  }
  if (s.locations.empty()) {
    return absl::InvalidArgumentError(
        absl::StrCat(std::string(file), ": at least one 'location' is required"));
  }
  if (!s.gnss_jumps.empty() && !s.grid_origin) {
    return absl::InvalidArgumentError(
        absl::StrCat(std::string(file), ": gnss_jump needs a 'grid'"));
  }
  return s;
}

StatusOr<Scenario> LoadScenario(const std::string& path) {
  std::ifstream in(path);
  if (!in) return absl::NotFoundError(absl::StrCat("cannot read scenario ", path));
  std::stringstream ss;
  ss << in.rdbuf();
  return ParseScenario(ss.str(), path);
}

StatusOr<std::string> ResolvePath(const Scenario& s, const std::string& path,
                                  const std::string& shared_dir) {
  if (absl::StartsWith(path, "shared:")) {
    if (shared_dir.empty()) {
      return absl::FailedPreconditionError(
          absl::StrCat(path, ": set SEAPLAN_SHARED to the shared data folder"));
    }
    return (std::filesystem::path(shared_dir) / path.substr(7)).string();
  }
  std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(s.file).parent_path() / p).lexically_normal().string();
}

mission::LocationTable LocalLocations(const Scenario& s, const chart::LocalFrame& frame) {
  mission::LocationTable t;
  for (const auto& [name, ll] : s.locations) {
    EastNorth p = frame.ToLocal(ll);
    t[name] = {p.east_m, p.north_m};
  }
  return t;
}

StatusOr<ExecutorConfig> MakeExecutorConfig(const Scenario& s, const chart::LocalFrame& frame,
                                            const std::string& ship_location) {
  ExecutorConfig c;
  c.vessel_id = s.vessel_id;
  auto locs = LocalLocations(s, frame);
  if (s.start) {
    EastNorth p = frame.ToLocal(*s.start);
    c.start = {p.east_m, p.north_m};
  } else if (auto it = locs.find(ship_location); it != locs.end()) {
    c.start = {it->second.east_m, it->second.north_m};
  } else {
    EastNorth p = frame.ToLocal(s.locations.front().second);
    c.start = {p.east_m, p.north_m};
  }
  c.start_heading_rad = s.start_heading_deg * kDeg;
  c.service_speed_mps = s.service_speed_mps;
  c.deviation_limit_m = s.position_deviation_m;
  c.avoidance.safety_distance_m = s.safety_distance_m;
  c.fuel.kind = s.fuel_model;
  c.initial_fuel_fraction = s.initial_fuel;
  c.fuel_threshold_fraction = s.fuel_threshold;
  c.environment.wind_speed_mps = s.wind_speed_mps;
  c.environment.wind_direction_from_rad = s.wind_from_deg * kDeg;
  // Current "from" (maritime convention of the API) -> water velocity toward.
  double toward = (s.current_from_deg + 180.0) * kDeg;
  c.environment.current_north_mps = s.current_speed_mps * std::cos(toward);
  c.environment.current_east_mps = s.current_speed_mps * std::sin(toward);
  if (s.grid_origin) {
    EastNorth g = frame.ToLocal(*s.grid_origin);
    c.grid = {{g.east_m, g.north_m}, s.grid_cell_m};
  }
  c.gnss_jumps = s.gnss_jumps;
  int id = 1;
  for (const ScenarioTraffic& t : s.traffic) {
    TrafficVessel v;
    v.id = id++;
    v.name = t.name;
    v.kind = t.kind;
    for (const ScenarioTrafficPoint& p : t.track) {
      EastNorth l = frame.ToLocal(p.position);
      v.track.push_back({p.time_s, {l.east_m, l.north_m}});
    }
    c.traffic.push_back(std::move(v));
  }
  return c;
}

void PerturbConfig(uint64_t seed, ExecutorConfig* c, double traffic_shift_s) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> shift(-traffic_shift_s, traffic_shift_s);
  for (TrafficVessel& v : c->traffic) {
    const double dt = shift(rng);
    for (TrackPoint& p : v.track) p.time_s += dt;
  }
  std::uniform_real_distribution<double> speed(0.8, 1.2), turn(-20.0 * kDeg, 20.0 * kDeg);
  c->environment.wind_speed_mps *= speed(rng);
  c->environment.wind_direction_from_rad += turn(rng);
}

}  // namespace seaplan::sim
