// The encounter suite (encounter_suite.h) under both collision-avoidance
// policies: per situation and policy, the closest approach to each vessel,
// the side it was passed on, the role taken, the COLREG checks, the time
// lost against the same leg without traffic and the largest deviation from
// the path; then how many situations each policy passes and its run time as
// a ratio to the velocity obstacles' in the same process. `sbmpc-basic` is
// the MPC with its former behaviour set and prediction (course offsets and
// speed factors only, every vessel on its present velocity), to measure the
// parallel tracks and the uncertainty margin against in the same run.
//
//   build/bin/colav_bench [--policy sbmpc|sbmpc-basic|vo|both|all] [--situation NAME] [--log]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "encounter_suite.h"

namespace {

using seaplan::colav::CollisionAvoidanceOptions;
using seaplan::colav::Policy;
namespace suite = seaplan::colav::suite;

struct Totals {
  int passed = 0;
  int run = 0;
  double seconds = 0.0;
};

}  // namespace

int main(int argc, char** argv) {
  std::string policy = "both", only;
  bool show_log = false;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--policy") && i + 1 < argc) {
      policy = argv[++i];
    } else if (!std::strcmp(argv[i], "--situation") && i + 1 < argc) {
      only = argv[++i];
    } else if (!std::strcmp(argv[i], "--log")) {
      show_log = true;
    } else {
      std::fprintf(stderr,
                   "usage: colav_bench [--policy sbmpc|sbmpc-basic|vo|both|all] [--situation "
                   "NAME] [--log]\n");
      return 2;
    }
  }
  struct Variant {
    std::string name;
    CollisionAvoidanceOptions options;
  };
  std::vector<Variant> policies;
  if (policy == "sbmpc" || policy == "both" || policy == "all") policies.push_back({"sbmpc", {}});
  if (policy == "sbmpc-basic" || policy == "all") {
    CollisionAvoidanceOptions basic;
    basic.track_offsets_m.clear();
    basic.uncertain_speed_mps = 0;
    policies.push_back({"basic", basic});
  }
  if (policy == "vo" || policy == "both" || policy == "all") {
    CollisionAvoidanceOptions vo;
    vo.policy = Policy::kVelocityObstacle;
    policies.push_back({"vo", vo});
  }
  if (policies.empty()) {
    std::fprintf(stderr,
                 "colav_bench: --policy must be sbmpc, sbmpc-basic, vo, both or all, not '%s'\n",
                 policy.c_str());
    return 2;
  }
  std::printf("%-38s %-5s %-24s %-16s %-13s %6s %6s %6s  %s\n", "situation", "colav",
              "min CPA per vessel (m)", "passed on", "roles", "lost%", "dev m", "land m", "checks");
  std::vector<Totals> totals(policies.size());
  bool any = false;
  for (size_t p = 0; p < policies.size(); ++p) {
    for (const suite::Situation& s : suite::Situations(policies[p].options)) {
      if (!only.empty() && s.name != only) continue;
      any = true;
      const auto t0 = std::chrono::steady_clock::now();
      auto r = suite::Run(s);
      totals[p].seconds +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      if (!r.ok()) {
        std::fprintf(stderr, "%s: %s\n", s.name.c_str(), r.status().ToString().c_str());
        return 1;
      }
      std::string cpas, sides, roles;
      for (size_t i = 0; i < r->outcome.vessels.size(); ++i) {
        const auto& v = r->outcome.vessels[i];
        const char* sep = i ? "/" : "";
        cpas += sep + std::to_string(static_cast<int>(std::lround(v.min_distance_m)));
        sides += sep + std::string(v.bearing_rad < 0 ? "port" : "stbd");
        roles += sep + std::string(seaplan::colav::RoleName(v.role)).substr(0, 5);
      }
      ++totals[p].run;
      if (r->failures.empty()) ++totals[p].passed;
      std::string checks = r->failures.empty() ? "ok" : "";
      for (const std::string& f : r->failures) checks += (checks.empty() ? "" : "; ") + f;
      const std::string land =
          s.setup.land.empty()
              ? "-"
              : std::to_string(static_cast<int>(std::lround(r->outcome.min_land_clearance_m)));
      std::printf("%-38s %-5s %-24s %-16s %-13s %6.1f %6.0f %6s  %s\n", s.name.c_str(),
                  policies[p].name.c_str(), cpas.c_str(), sides.c_str(), roles.c_str(),
                  r->time_lost * 100.0, r->outcome.max_path_deviation_m, land.c_str(),
                  checks.c_str());
      if (show_log) {
        for (const std::string& line : r->outcome.log) std::printf("    %s\n", line.c_str());
      }
    }
  }
  if (!any) {
    std::fprintf(stderr, "colav_bench: no situation named '%s'\n", only.c_str());
    return 2;
  }
  for (size_t p = 0; p < policies.size(); ++p) {
    std::printf("%s: %d of %d situations pass every check, %.1f s\n", policies[p].name.c_str(),
                totals[p].passed, totals[p].run, totals[p].seconds);
  }
  for (size_t p = 1; p < policies.size(); ++p) {
    if (totals[p].seconds > 0) {
      std::printf("run time %s / %s: %.1f\n", policies[0].name.c_str(), policies[p].name.c_str(),
                  totals[0].seconds / totals[p].seconds);
    }
  }
  return 0;
}
