// seaplan-bench-missions [--time-limit 60] [--seeds 10]
// [--sizes 3x12x12,4x16x16,5x20x20] [--domains fjord,fjord-fuel]
// [--filter substr] [--target 1.2] [--seaplan PATH] [--examples DIR]
// [--work-dir DIR]
//
// First-plan quality of `seaplan plan` on the fjord examples and on generated
// fjord missions (fjord_mission.h), as a user runs it: whole processes, one
// at a time. Per problem, two runs of the planner:
//   first:   seaplan plan D P --no-anytime --time-limit L -o first.plan
//   anytime: seaplan plan D P --time-limit L --stream -o best.plan
// and every plan written is checked by `seaplan validate D P plan` (its
// makespan is the one reported). The figure is first / best: the first
// plan's makespan over the best one the anytime search found within L
// seconds (target: at most 1.2 on every problem). From the anytime run's
// stream, also the makespan of the last plan it had reported 1 s after it was
// spawned. Exit code 1 when a plan is invalid or the target is missed.
#include <stdlib.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "CLI/CLI.hpp"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "absl/strings/strip.h"
#include "child_process.h"
#include "fjord_mission.h"

namespace fs = std::filesystem;

namespace {

struct Problem {
  std::string name, group;  // group: "examples" or the size, e.g. "fjord 3x12x12"
  fs::path domain, problem;
};

// A plan file checked by `seaplan validate`.
struct Checked {
  bool present = false, valid = false;
  double makespan_s = 0;
  // Sum of the actions' durations over the makespan: how many actions run
  // at once on average (1 for a sequential plan).
  double concurrency = 0;
  std::string note;
};

// Sum of the "[duration]" of every line of a plan file.
double SumOfDurations(const fs::path& plan) {
  std::ifstream in(plan);
  double sum_s = 0;
  for (std::string line; std::getline(in, line);) {
    const auto open = line.rfind('['), close = line.rfind(']');
    double duration_s = 0;
    if (open != std::string::npos && close != std::string::npos && close > open &&
        absl::SimpleAtod(line.substr(open + 1, close - open - 1), &duration_s))
      sum_s += duration_s;
  }
  return sum_s;
}

struct Outcome {
  Checked first, best;
  double first_wall_s = 0;      // spawn to exit of the --no-anytime run
  double best_found_at_s = -1;  // wall time of the anytime run's last improvement
  double makespan_at_1s = -1;   // last improvement reported within 1 s of spawn
  int improvements = 0;
  std::string anytime_status;
};

std::string StatusLine(const std::string& out) {
  const std::string key = "; status: ";
  const auto at = out.find(key);
  if (at == std::string::npos) return "";
  return out.substr(at + key.size(), out.find('\n', at) - at - key.size());
}

std::string LastLine(std::string text) {
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text.substr(text.find_last_of('\n') + 1, 160);
}

Checked Validate(const fs::path& seaplan, const Problem& p, const fs::path& plan) {
  Checked c;
  if (!fs::exists(plan) || fs::file_size(plan) == 0) return c;
  c.present = true;
  seaplan::bench::ChildLimits limits;
  limits.time_limit_s = 120;
  const auto child = seaplan::bench::RunChild(
      {seaplan.string(), "validate", p.domain.string(), p.problem.string(), plan.string()}, limits);
  c.valid = child.exit_code == 0 && child.out.rfind("Plan valid", 0) == 0;
  const auto at = child.out.find("makespan: ");
  if (at != std::string::npos) {
    std::string number = child.out.substr(at + 10);
    number = number.substr(0, number.find(' '));
    if (!absl::SimpleAtod(number, &c.makespan_s)) c.makespan_s = 0;
  }
  if (!c.valid) c.note = LastLine(child.out + child.err);
  if (c.makespan_s > 0) c.concurrency = SumOfDurations(plan) / c.makespan_s;
  return c;
}

Outcome RunProblem(const fs::path& seaplan, const Problem& p, const fs::path& work_dir,
                   double limit_s) {
  Outcome o;
  seaplan::bench::ChildLimits limits;
  limits.time_limit_s = limit_s + 5;  // the planner's own limit stops it first
  const std::string limit = std::to_string(limit_s);
  const fs::path first_plan = work_dir / (p.name + ".first.plan");
  const fs::path best_plan = work_dir / (p.name + ".best.plan");
  fs::remove(first_plan);
  fs::remove(best_plan);

  const auto first =
      seaplan::bench::RunChild({seaplan.string(), "plan", p.domain.string(), p.problem.string(),
                                "--no-anytime", "--time-limit", limit, "-o", first_plan.string()},
                               limits);
  o.first_wall_s = first.wall_s;
  o.first = Validate(seaplan, p, first_plan);
  if (!o.first.present) o.first.note = LastLine(first.out + first.err);

  // "improved plan: makespan X s after T s" on stderr, one line per plan.
  const std::string key = "improved plan: makespan ";
  const auto on_line = [&](bool is_stderr, const std::string& line, double at_s) {
    if (!is_stderr || line.rfind(key, 0) != 0) return;
    double makespan_s = 0;
    std::string number = line.substr(key.size());
    number = number.substr(0, number.find(' '));
    if (!absl::SimpleAtod(number, &makespan_s)) return;
    ++o.improvements;
    o.best_found_at_s = at_s;
    if (at_s <= 1.0) o.makespan_at_1s = makespan_s;
  };
  const auto anytime =
      seaplan::bench::RunChild({seaplan.string(), "plan", p.domain.string(), p.problem.string(),
                                "--time-limit", limit, "--stream", "-o", best_plan.string()},
                               limits, on_line);
  o.anytime_status = StatusLine(anytime.out);
  o.best = Validate(seaplan, p, best_plan);
  if (!o.best.present) o.best.note = LastLine(anytime.out + anytime.err);
  return o;
}

double Quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  const double at = q * static_cast<double>(values.size() - 1);
  const auto low = static_cast<std::size_t>(at);
  const std::size_t high = std::min(low + 1, values.size() - 1);
  return values[low] + (values[high] - values[low]) * (at - static_cast<double>(low));
}

void PrintDistribution(const std::string& label, const std::vector<double>& ratios, double target) {
  if (ratios.empty()) {
    std::printf("%-22s no problem with both plans\n", label.c_str());
    return;
  }
  const auto within =
      std::count_if(ratios.begin(), ratios.end(), [&](double r) { return r <= target + 1e-9; });
  std::printf(
      "%-22s n=%-3zu min %.3f  p25 %.3f  median %.3f  p75 %.3f  p90 %.3f  max %.3f  "
      "within %.2f: %td/%zu\n",
      label.c_str(), ratios.size(), Quantile(ratios, 0), Quantile(ratios, 0.25),
      Quantile(ratios, 0.5), Quantile(ratios, 0.75), Quantile(ratios, 0.9), Quantile(ratios, 1),
      target, within, ratios.size());
}

}  // namespace

int main(int argc, char** argv) {
  double limit_s = 60, target = 1.2;
  int seeds = 10;
  std::string sizes = "3x12x12,4x16x16,5x20x20", domains = "fjord,fjord-fuel", filter;
  fs::path seaplan = fs::read_symlink("/proc/self/exe").parent_path() / "seaplan";
  fs::path examples = SEAPLAN_FJORD_EXAMPLES_DIR, work_dir;
  CLI::App app{"First plan against the anytime best on fjord missions (whole processes)"};
  app.add_option("--time-limit", limit_s, "Planner time limit per run (s)")->capture_default_str();
  app.add_option("--seeds", seeds, "Generated missions per size and domain (seeds 1..N)")
      ->capture_default_str();
  app.add_option("--sizes", sizes, "SHIPSxPORTSxCONTAINERS, comma-separated")
      ->capture_default_str();
  app.add_option("--domains", domains, "fjord and/or fjord-fuel, comma-separated")
      ->capture_default_str();
  app.add_option("--filter", filter, "Only problems whose name contains this");
  app.add_option("--target", target, "Largest acceptable first/best ratio")->capture_default_str();
  app.add_option("--seaplan", seaplan, "The seaplan executable")->capture_default_str();
  app.add_option("--examples", examples, "examples/fjord folder")->capture_default_str();
  app.add_option("--work-dir", work_dir,
                 "Where problems and plans are written (default: new temp)");
  CLI11_PARSE(app, argc, argv);

  if (work_dir.empty()) {
    std::string pattern = (fs::temp_directory_path() / "seaplan-missions-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      std::fprintf(stderr, "cannot create a temporary folder\n");
      return 2;
    }
    work_dir = pattern;
  }
  fs::create_directories(work_dir);

  std::vector<Problem> problems;
  const std::pair<const char*, const char*> example_cases[] = {
      {"case-a", "domain.pddl"},
      {"case-b", "domain.pddl"},
      {"case-c", "domain-fuel.pddl"},
      {"case-c-numeric", "domain-numeric.pddl"}};
  for (const auto& [name, domain] : example_cases) {
    problems.push_back(
        {name, "examples", examples / domain, examples / (std::string(name) + ".pddl")});
    if (!fs::exists(problems.back().problem)) {
      std::fprintf(stderr, "missing %s (see --examples)\n", problems.back().problem.c_str());
      return 2;
    }
  }
  for (const std::string& domain_name : std::vector<std::string>(absl::StrSplit(domains, ','))) {
    if (domain_name != "fjord" && domain_name != "fjord-fuel") {
      std::fprintf(stderr, "unknown domain %s (fjord or fjord-fuel)\n", domain_name.c_str());
      return 2;
    }
    const bool fuel = domain_name == "fjord-fuel";
    for (const std::string& size : std::vector<std::string>(absl::StrSplit(sizes, ','))) {
      const std::vector<std::string> parts = absl::StrSplit(size, 'x');
      seaplan::bench::FjordMissionSpec spec;
      spec.domain =
          fuel ? seaplan::bench::FjordDomain::kFjordFuel : seaplan::bench::FjordDomain::kFjord;
      if (parts.size() != 3 || !absl::SimpleAtoi(parts[0], &spec.ships) ||
          !absl::SimpleAtoi(parts[1], &spec.ports) ||
          !absl::SimpleAtoi(parts[2], &spec.containers)) {
        std::fprintf(stderr, "bad size '%s' (SHIPSxPORTSxCONTAINERS)\n", size.c_str());
        return 2;
      }
      for (int seed = 1; seed <= seeds; ++seed) {
        spec.seed = static_cast<std::uint64_t>(seed);
        const auto text = seaplan::bench::GenerateFjordMission(spec);
        if (!text.ok()) {
          std::fprintf(stderr, "size %s: %s\n", size.c_str(),
                       std::string(text.status().message()).c_str());
          return 2;
        }
        const std::string name = seaplan::bench::FjordMissionName(spec);
        const fs::path file = work_dir / (name + ".pddl");
        std::ofstream(file, std::ios::binary) << *text;
        problems.push_back({name, absl::StrCat(domain_name, " ", size),
                            examples / (fuel ? "domain-fuel.pddl" : "domain.pddl"), file});
      }
    }
  }

  std::printf(
      "seaplan-bench-missions: %s, whole processes, one at a time, time limit %g s per run\n",
      seaplan.c_str(), limit_s);
  std::printf("problems and plans in %s\n\n", work_dir.c_str());
  std::printf("%-32s %12s %7s %5s %12s %8s %5s %5s %12s %7s  %s\n", "problem", "first", "first_s",
              "conc", "best", "best_at", "plans", "conc", "at_1s", "ratio", "note");
  std::map<std::string, std::vector<double>> ratios_by_group;
  std::vector<std::string> group_order;
  std::vector<double> all_ratios;
  int invalid = 0, unsolved = 0, run = 0;
  for (const auto& p : problems) {
    if (!filter.empty() && p.name.find(filter) == std::string::npos) continue;
    ++run;
    const Outcome o = RunProblem(seaplan, p, work_dir, limit_s);
    char first[32] = "-", best[32] = "-", at_1s[32] = "-", ratio[32] = "-", best_at[32] = "-";
    std::string note;
    for (const auto* c : {&o.first, &o.best}) {
      if (c->present && !c->valid) {
        ++invalid;
        note += (c == &o.first ? "first INVALID: " : "best INVALID: ") + c->note + " ";
      }
    }
    if (o.first.valid) std::snprintf(first, sizeof first, "%.3f", o.first.makespan_s);
    if (o.best.valid) std::snprintf(best, sizeof best, "%.3f", o.best.makespan_s);
    if (o.makespan_at_1s > 0) std::snprintf(at_1s, sizeof at_1s, "%.3f", o.makespan_at_1s);
    if (o.best_found_at_s >= 0) std::snprintf(best_at, sizeof best_at, "%.2f", o.best_found_at_s);
    if (o.first.valid && o.best.valid && o.best.makespan_s > 0) {
      const double r = o.first.makespan_s / o.best.makespan_s;
      std::snprintf(ratio, sizeof ratio, "%.3f", r);
      if (ratios_by_group.find(p.group) == ratios_by_group.end()) group_order.push_back(p.group);
      ratios_by_group[p.group].push_back(r);
      all_ratios.push_back(r);
    } else {
      ++unsolved;
      if (!o.first.present) note += "first: " + o.first.note + " ";
      if (!o.best.present) note += "anytime: " + o.best.note + " ";
    }
    std::printf("%-32s %12s %7.2f %5.2f %12s %8s %5d %5.2f %12s %7s  %s\n", p.name.c_str(), first,
                o.first_wall_s, o.first.concurrency, best, best_at, o.improvements,
                o.best.concurrency, at_1s, ratio, note.c_str());
    std::fflush(stdout);
  }

  std::printf(
      "\nfirst: makespan of the --no-anytime run's plan (first_s: that process's wall time);\n"
      "best: makespan of the anytime run's final plan after at most %g s (best_at: wall time of\n"
      "its last improvement, plans: improvements reported); at_1s: the anytime run's plan 1 s\n"
      "after spawn; ratio: first / best; conc: sum of the plan's action durations over its\n"
      "makespan (1: nothing overlaps). All makespans are `seaplan validate`'s.\n\n",
      limit_s);
  std::printf("first / best distribution (target: at most %.2f)\n", target);
  for (const auto& group : group_order) PrintDistribution(group, ratios_by_group[group], target);
  PrintDistribution("all", all_ratios, target);
  const auto missed = std::count_if(all_ratios.begin(), all_ratios.end(),
                                    [&](double r) { return r > target + 1e-9; });
  std::printf("\n%d problems, %d without both plans, %d invalid plans, %td above the target\n", run,
              unsolved, invalid, missed);
  return invalid > 0 || unsolved > 0 || missed > 0 ? 1 : 0;
}
