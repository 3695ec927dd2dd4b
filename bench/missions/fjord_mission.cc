#include "fjord_mission.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>
#include <utility>
#include <vector>

#include "absl/status/status.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace seaplan::bench {
namespace {

// splitmix64: a small generator whose output is fixed by its definition, so a
// seed gives the same mission on every platform and standard library.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t Next() {
    std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [0, n) (the modulo bias is below 1e-17 for these n).
  int Below(int n) { return static_cast<int>(Next() % static_cast<std::uint64_t>(n)); }
  // Uniform in [0, 1).
  double Unit() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }
  double Between(double low, double high) { return low + (high - low) * Unit(); }
  template <typename T>
  void Shuffle(std::vector<T>& values) {
    for (int i = static_cast<int>(values.size()) - 1; i > 0; --i)
      std::swap(values[static_cast<std::size_t>(i)],
                values[static_cast<std::size_t>(Below(i + 1))]);
  }

 private:
  std::uint64_t state_;
};

struct EastNorth {
  double east = 0, north = 0;
};

// Port positions along a winding fjord in the examples' length unit (their
// legs are 52-107 units): about 60 units apart along it, up to ~110 across.
std::vector<EastNorth> FjordPorts(int count, SplitMix64& rng) {
  const double phase = rng.Between(0, 6.283);
  std::vector<EastNorth> ports;
  ports.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    ports.push_back(
        {60.0 * i + rng.Between(-15, 15), 80.0 * std::sin(0.7 * i + phase) + rng.Between(-30, 30)});
  }
  return ports;
}

int RouteLength(const EastNorth& a, const EastNorth& b) {
  return std::max(1, static_cast<int>(std::lround(std::hypot(a.east - b.east, a.north - b.north))));
}

std::string PortName(int i) {
  return absl::StrFormat("port-%02d", i + 1);
}
std::string ContainerName(int i) {
  return absl::StrFormat("cont-%02d", i + 1);
}
std::string ShipName(int i) {
  return absl::StrCat("ship", i);
}

// `count` distinct values of [0, n) in random order (count <= n).
std::vector<int> DistinctBelow(int n, int count, SplitMix64& rng) {
  std::vector<int> values(static_cast<std::size_t>(n));
  std::iota(values.begin(), values.end(), 0);
  rng.Shuffle(values);
  values.resize(static_cast<std::size_t>(count));
  return values;
}

}  // namespace

absl::Status FjordMissionSpec::Validate() const {
  if (ships < 1 || ships > 26) return absl::InvalidArgumentError("ships must be in 1..26");
  if (ports < 2 || ports > 99) return absl::InvalidArgumentError("ports must be in 2..99");
  if (ports < ships) return absl::InvalidArgumentError("need at least as many ports as ships");
  if (containers < 1 || containers > 99)
    return absl::InvalidArgumentError("containers must be in 1..99");
  if (nearest_routes < 0) return absl::InvalidArgumentError("nearest_routes must be >= 0");
  return absl::OkStatus();
}

const char* FjordDomainName(FjordDomain domain) {
  return domain == FjordDomain::kFjordFuel ? "fjord-fuel" : "fjord";
}

std::string FjordMissionName(const FjordMissionSpec& spec) {
  return absl::StrFormat("%s-s%d-p%d-c%d-seed%d", FjordDomainName(spec.domain), spec.ships,
                         spec.ports, spec.containers, spec.seed);
}

absl::StatusOr<std::string> GenerateFjordMission(const FjordMissionSpec& spec) {
  if (auto status = spec.Validate(); !status.ok()) return status;
  SplitMix64 rng(
      spec.seed * 0x2545f4914f6cdd1dULL + static_cast<std::uint64_t>(spec.ships) * 1000003 +
      static_cast<std::uint64_t>(spec.ports) * 1009 + static_cast<std::uint64_t>(spec.containers));
  const bool fuel_domain = spec.domain == FjordDomain::kFjordFuel;
  const int team_count = std::max(1, spec.ports / 6);

  const auto positions = FjordPorts(spec.ports, rng);
  const auto repair_ports = DistinctBelow(spec.ports, team_count, rng);
  const auto refuel_ports = DistinctBelow(spec.ports, team_count, rng);

  // Routes: along the fjord, to the nearest ports, and in fjord-fuel from
  // every port to its nearest charger (move-fueling-ship needs a direct route).
  std::set<std::pair<int, int>> routes;
  auto add_route = [&](int a, int b) {
    if (a != b) routes.insert({std::min(a, b), std::max(a, b)});
  };
  for (int i = 0; i + 1 < spec.ports; ++i) add_route(i, i + 1);
  for (int i = 0; i < spec.ports; ++i) {
    std::vector<int> others;
    for (int j = 0; j < spec.ports; ++j)
      if (j != i) others.push_back(j);
    auto by_length = [&](int a, int b) {
      return std::make_pair(RouteLength(positions[static_cast<std::size_t>(i)],
                                        positions[static_cast<std::size_t>(a)]),
                            a) < std::make_pair(RouteLength(positions[static_cast<std::size_t>(i)],
                                                            positions[static_cast<std::size_t>(b)]),
                                                b);
    };
    std::sort(others.begin(), others.end(), by_length);
    for (int k = 0; k < spec.nearest_routes && k < static_cast<int>(others.size()); ++k)
      add_route(i, others[static_cast<std::size_t>(k)]);
    if (fuel_domain) {
      auto chargers = refuel_ports;
      std::sort(chargers.begin(), chargers.end(), by_length);
      add_route(i, chargers.front());
    }
  }

  // Ships start at different ports, so several can sail at once.
  const auto start_ports = DistinctBelow(spec.ports, spec.ships, rng);
  const auto container_order = DistinctBelow(spec.containers, spec.containers, rng);
  std::vector<int> container_origin;
  container_origin.reserve(static_cast<std::size_t>(spec.containers));
  for (int c = 0; c < spec.containers; ++c) container_origin.push_back(rng.Below(spec.ports));
  std::string init, goal;
  std::size_t next_container = 0;
  for (int v = 0; v < spec.ships; ++v) {
    const std::string ship = ShipName(v);
    const int speed_hundredths = 15 + rng.Below(11);  // 0.15..0.25, the examples' 0.18 among them
    absl::StrAppend(&init, "    (at ", ship, " ",
                    PortName(start_ports[static_cast<std::size_t>(v)]), ") (available ", ship,
                    ") (no_rep ", ship, ")");
    absl::StrAppendFormat(&init, " (= (speed %s) 0.%02d)", ship, speed_hundredths);
    if (fuel_domain) {
      // The last ship starts below the refuelling threshold (case C's replan);
      // the others with a third's chance.
      const bool no_fuel = v == spec.ships - 1 || rng.Below(3) == 0;
      absl::StrAppend(&init, no_fuel ? " (no_fuel " : " (fuel ", ship, ")\n");
    } else {
      absl::StrAppend(&init, " (no_fuel ", ship, ")\n");  // as case A: moves anyway
    }
    absl::StrAppend(&goal, "    (at ", ship, " ", PortName(rng.Below(spec.ports)), ")");
    if (rng.Below(2) == 0) absl::StrAppend(&goal, " (repaired ", ship, ")");
    if (!fuel_domain && rng.Below(2) == 0) absl::StrAppend(&goal, " (fuel ", ship, ")");
    // At most one container on board at the end: a ship carries one at a time.
    if (next_container < container_order.size() && rng.Below(3) == 0) {
      absl::StrAppend(&goal, " (loaded ", ContainerName(container_order[next_container++]), " ",
                      ship, ")");
    }
    absl::StrAppend(&goal, "\n");
  }
  for (int c = 0; c < spec.containers; ++c) {
    absl::StrAppend(&init, "    (at ", ContainerName(c), " ",
                    PortName(container_origin[static_cast<std::size_t>(c)]), ")\n");
  }
  for (std::size_t k = next_container; k < container_order.size(); ++k) {
    const int c = container_order[k];
    // Anywhere but where it starts.
    const int origin = container_origin[static_cast<std::size_t>(c)];
    const int destination = (origin + 1 + rng.Below(spec.ports - 1)) % spec.ports;
    absl::StrAppend(&goal, "    (at ", ContainerName(c), " ", PortName(destination), ")\n");
  }

  std::string text =
      absl::StrCat("; Generated by seaplan-mission-gen: ", spec.ships, " ships, ", spec.ports,
                   " ports, ", spec.containers, " containers, seed ", spec.seed,
                   ".\n(define (problem ", FjordMissionName(spec), ")\n", "  (:domain ",
                   FjordDomainName(spec.domain), ")\n  (:objects\n   ");
  for (int v = 0; v < spec.ships; ++v) absl::StrAppend(&text, " ", ShipName(v));
  absl::StrAppend(&text, " - ship\n   ");
  for (int i = 0; i < spec.ports; ++i) absl::StrAppend(&text, " ", PortName(i));
  absl::StrAppend(&text, " - port\n   ");
  for (int c = 0; c < spec.containers; ++c) absl::StrAppend(&text, " ", ContainerName(c));
  absl::StrAppend(&text, " - cont\n   ");
  for (int t = 0; t < team_count; ++t) absl::StrAppend(&text, " teamr", t);
  absl::StrAppend(&text, " - team_rep\n   ");
  for (int t = 0; t < team_count; ++t) absl::StrAppend(&text, " teamf", t);
  absl::StrAppend(&text, " - team_refuel)\n  (:init\n", init);
  for (int t = 0; t < team_count; ++t) {
    absl::StrAppend(&text, "    (at teamr", t, " ",
                    PortName(repair_ports[static_cast<std::size_t>(t)]), ") (at teamf", t, " ",
                    PortName(refuel_ports[static_cast<std::size_t>(t)]), ")\n");
  }
  for (const auto& [a, b] : routes) {
    const int length =
        RouteLength(positions[static_cast<std::size_t>(a)], positions[static_cast<std::size_t>(b)]);
    absl::StrAppendFormat(&text,
                          "    (connected %1$s %2$s) (connected %2$s %1$s) (= (distance %1$s %2$s) "
                          "%3$d) (= (distance %2$s %1$s) %3$d)\n",
                          PortName(a), PortName(b), length);
  }
  absl::StrAppend(&text, "  )\n  (:goal (and\n", goal,
                  "  ))\n  (:metric minimize (total-time)))\n");
  return text;
}

}  // namespace seaplan::bench
