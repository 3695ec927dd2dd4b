// seaplan-bench-planner [--time-limit 60] [--jobs 1] [--filter substr] [--peers FILE]
// [--first-plan] [--repeat N] [DIR]
//
// Runs the planner on every p01..p05 of every domain folder of DIR (default
// $SEAPLAN_SHARED/bench, else ../shared/bench), validates each plan again
// with the validator, prints one line per problem, then per domain and in
// total: coverage, IPC time score and IPC quality (makespan) score for us
// and for each peer of peers.md ("Every run" table), over the same problems.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "peers.h"
#include "seaplan/common/log.h"
#include "seaplan/search/planner.h"
#include "seaplan/task/grounder.h"
#include "seaplan/validate/validator.h"

namespace fs = std::filesystem;
using seaplan::bench::Run;

namespace {

struct Job {
  std::string domain, problem;
  fs::path domain_file, problem_file;
};

struct Outcome {
  Run run;  // planner "seaplan"
  std::string status;
  double best_s = -1;
  std::size_t expanded = 0, generated = 0, peak_mb = 0;
  bool valid = false;
  double load_s = 0;
  std::string note;
  std::string plan_text;
};

std::string ReadAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// --first-plan: stop at the first plan (anytime off), so that `expanded`
// counts the states of the first search only.
bool g_first_plan_only = false;
// --repeat N: solved problems run N times in all and report the run with the
// earliest first plan (minimum of N: the machine is shared, wall times of
// millisecond runs are mostly scheduling noise). Plans are the same each
// time (fixed seed).
int g_repeat = 1;

Outcome RunOne(const Job& job, double limit_s) {
  Outcome o;
  o.run.domain = job.domain;
  o.run.problem = job.problem;
  o.run.planner = "seaplan";
  const auto start = std::chrono::steady_clock::now();
  auto loaded = seaplan::task::LoadTask(ReadAll(job.domain_file), ReadAll(job.problem_file));
  const double load_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  o.load_s = load_s;
  if (!loaded.ok()) {
    o.status = loaded.unsupported() ? "unsupported" : "load-error";
    o.note = loaded.ErrorText().substr(0, 200);
    return o;
  }
  seaplan::search::PlannerOptions options;
  options.time_limit_s = std::max(0.01, limit_s - load_s);
  options.anytime = !g_first_plan_only;
  const auto r = seaplan::search::SolveTask(*loaded.task, options, seaplan::StopToken());
  o.status = seaplan::search::ToString(r.status);
  o.expanded = r.stats.expanded;
  o.generated = r.stats.generated;
  o.peak_mb = r.stats.peak_memory_mb;
  if (r.plan.steps.empty() && r.status != seaplan::search::PlanStatus::kSolvedSatisficing &&
      r.status != seaplan::search::PlanStatus::kSolvedOptimally) {
    o.note = r.message.substr(0, 200);
    return o;
  }
  // Independent check of the printed plan.
  auto parsed = seaplan::validate::ParsePlan(seaplan::validate::FormatPlan(r.plan));
  if (!parsed.ok()) {
    o.status = "INVALID";
    o.note = std::string(parsed.status().message());
    return o;
  }
  const auto v = seaplan::validate::ValidatePlan(*loaded.task, *parsed);
  o.valid = v.valid;
  if (!v.valid) {
    o.status = "INVALID";
    o.note = v.ToString();
    return o;
  }
  o.plan_text = seaplan::validate::FormatPlan(r.plan);
  o.run.solved = true;
  o.run.time_s = load_s + r.stats.first_plan_time_s;
  o.best_s = load_s + r.stats.best_plan_time_s;
  o.run.makespan = v.makespan_s;
  o.run.actions = static_cast<int>(r.plan.steps.size());
  return o;
}

double Median(std::vector<double> v) {
  if (v.empty()) return -1;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  double limit_s = 60;
  int jobs = 1;
  std::string filter;
  fs::path dir;
  fs::path peers_file;
  bool print_plans = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "missing value for %s\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--time-limit") {
      limit_s = std::atof(value().c_str());
    } else if (a == "--jobs") {
      jobs = std::max(1, std::atoi(value().c_str()));
    } else if (a == "--filter") {
      filter = value();
    } else if (a == "--first-plan") {
      g_first_plan_only = true;
    } else if (a == "--repeat") {
      g_repeat = std::max(1, std::atoi(value().c_str()));
    } else if (a == "--print-plans") {
      print_plans = true;
    } else if (a == "--peers") {
      peers_file = value();
    } else if (a == "--help" || a == "-h") {
      std::printf(
          "usage: seaplan-bench-planner [--time-limit 60] [--jobs 1] [--filter substr] [--peers "
          "FILE] [--print-plans] [--first-plan] [--repeat N] [DIR]\n");
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    } else {
      dir = a;
    }
  }
  if (!(limit_s > 1)) {
    std::fprintf(stderr, "--time-limit must be > 1 s\n");
    return 2;
  }
  if (dir.empty()) {
    const char* shared = std::getenv("SEAPLAN_SHARED");
    dir = shared ? fs::path(shared) / "bench" : fs::path("../shared/bench");
  }
  if (peers_file.empty()) peers_file = dir.parent_path() / "peers.md";
  if (!fs::is_directory(dir)) {
    std::fprintf(stderr, "benchmark folder %s not found\n", dir.c_str());
    return 2;
  }
  seaplan::log::SetLevel(seaplan::log::Level::kWarn);

  std::vector<Job> all;
  std::vector<fs::path> domains;
  for (const auto& e : fs::directory_iterator(dir)) {
    if (e.is_directory()) domains.push_back(e.path());
  }
  std::sort(domains.begin(), domains.end());
  for (const auto& d : domains) {
    for (int k = 1; k <= 5; ++k) {
      char name[16];
      std::snprintf(name, sizeof name, "p%02d", k);
      Job job;
      job.domain = d.filename().string();
      job.problem = name;
      job.problem_file = d / (std::string(name) + ".pddl");
      job.domain_file = d / ("domain-" + std::to_string(k) + ".pddl");
      if (!fs::exists(job.domain_file)) job.domain_file = d / "domain.pddl";
      if (!fs::exists(job.problem_file) || !fs::exists(job.domain_file)) continue;
      if (!filter.empty() && (job.domain + "/" + job.problem).find(filter) == std::string::npos)
        continue;
      all.push_back(job);
    }
  }

  std::vector<Outcome> outcomes(all.size());
  std::atomic<std::size_t> next{0};
  std::mutex print_mutex;
  std::printf("%-26s %-4s %-17s %8s %8s %12s %5s %9s %7s %7s %10s\n", "domain", "prob", "status",
              "first_s", "best_s", "makespan", "acts", "expanded", "peak_mb", "load_s",
              "generated");
  std::fflush(stdout);
  auto worker = [&]() {
    while (true) {
      const std::size_t i = next++;
      if (i >= all.size()) return;
      outcomes[i] = RunOne(all[i], limit_s);
      for (int r = 1; r < g_repeat && outcomes[i].run.solved; ++r) {
        Outcome again = RunOne(all[i], limit_s);
        if (again.run.solved && again.run.time_s < outcomes[i].run.time_s)
          outcomes[i] = std::move(again);
      }
      const Outcome& o = outcomes[i];
      std::lock_guard<std::mutex> lock(print_mutex);
      if (o.run.solved) {
        std::printf("%-26s %-4s %-17s %8.3f %8.3f %12.3f %5d %9zu %7zu %7.3f %10zu\n",
                    o.run.domain.c_str(), o.run.problem.c_str(), o.status.c_str(), o.run.time_s,
                    o.best_s, o.run.makespan, o.run.actions, o.expanded, o.peak_mb, o.load_s,
                    o.generated);
      } else {
        std::printf("%-26s %-4s %-17s %8s %8s %12s %5s %9zu %7zu %7.3f  %s\n", o.run.domain.c_str(),
                    o.run.problem.c_str(), o.status.c_str(), "-", "-", "-", "-", o.expanded,
                    o.peak_mb, o.load_s, o.note.substr(0, o.note.find('\n')).c_str());
      }
      if (print_plans && !o.plan_text.empty()) std::printf("%s", o.plan_text.c_str());
      std::fflush(stdout);
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < jobs; ++t) threads.emplace_back(worker);
  for (auto& t : threads) t.join();

  // Scores against the peers over the same problems.
  std::vector<Run> peer_runs = seaplan::bench::ParsePeerRuns(ReadAll(peers_file));
  std::set<std::string> planner_set;
  std::map<std::pair<std::string, std::string>, std::map<std::string, Run>> table;
  for (const auto& o : outcomes) table[{o.run.domain, o.run.problem}]["seaplan"] = o.run;
  for (const auto& r : peer_runs) {
    auto it = table.find({r.domain, r.problem});
    if (it == table.end()) continue;
    it->second[r.planner] = r;
    planner_set.insert(r.planner);
  }
  std::vector<std::string> planners = {"seaplan"};
  planners.insert(planners.end(), planner_set.begin(), planner_set.end());
  struct Score {
    int solved = 0, run = 0;
    double time = 0, quality = 0;
  };
  std::map<std::string, std::map<std::string, Score>> by_domain;  // domain -> planner -> score
  std::map<std::string, Score> total;
  int any_peer_solved = 0;
  for (const auto& [key, runs] : table) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& [p, r] : runs) {
      if (r.solved && r.makespan > 0) best = std::min(best, r.makespan);
    }
    bool any = false;
    for (const auto& p : planners) {
      auto it = runs.find(p);
      if (it == runs.end()) continue;
      const Run& r = it->second;
      Score& s = by_domain[key.first][p];
      ++s.run;
      ++total[p].run;
      // Peers ran with 60 s; count a peer's plan only within our limit.
      const bool ok = r.solved && (p == "seaplan" || r.time_s <= limit_s);
      if (!ok) continue;
      if (p != "seaplan") any = true;
      ++s.solved;
      ++total[p].solved;
      const double ts = seaplan::bench::TimeScore(r, limit_s);
      const double qs = r.makespan > 0 ? best / r.makespan : 1.0;
      s.time += ts;
      s.quality += qs;
      total[p].time += ts;
      total[p].quality += qs;
    }
    any_peer_solved += any;
  }
  std::printf(
      "\nPer domain (coverage solved/run, IPC time score, IPC quality score), limit %.0f s\n",
      limit_s);
  std::printf("%-26s", "domain");
  for (const auto& p : planners) std::printf(" | %-20s", p.c_str());
  std::printf("\n");
  for (const auto& [domain, scores] : by_domain) {
    std::printf("%-26s", domain.c_str());
    for (const auto& p : planners) {
      auto it = scores.find(p);
      if (it == scores.end()) {
        std::printf(" | %-20s", "-");
      } else {
        char cell[64];
        std::snprintf(cell, sizeof cell, "%d/%d %.2f %.2f", it->second.solved, it->second.run,
                      it->second.time, it->second.quality);
        std::printf(" | %-20s", cell);
      }
    }
    std::printf("\n");
  }
  std::printf("%-26s", "TOTAL");
  for (const auto& p : planners) {
    char cell[64];
    std::snprintf(cell, sizeof cell, "%d/%d %.2f %.2f", total[p].solved, total[p].run,
                  total[p].time, total[p].quality);
    std::printf(" | %-20s", cell);
  }
  std::printf("\nany peer (within the limit): %d/%zu\n", any_peer_solved, table.size());

  std::printf("\nMedian time to first plan on problems both solve:\n");
  for (const auto& p : planners) {
    if (p == "seaplan") continue;
    std::vector<double> ours, theirs;
    for (const auto& [key, runs] : table) {
      auto a = runs.find("seaplan");
      auto b = runs.find(p);
      if (a == runs.end() || b == runs.end() || !a->second.solved || !b->second.solved) continue;
      ours.push_back(a->second.time_s);
      theirs.push_back(b->second.time_s);
    }
    const double mo = Median(ours), mt = Median(theirs);
    std::printf("  vs %-6s: %3zu problems, seaplan median %.4f s, %s median %.4f s, ratio %.3f\n",
                p.c_str(), ours.size(), mo, p.c_str(), mt, mt > 0 ? mo / mt : 0.0);
  }
  int invalid = 0;
  for (const auto& o : outcomes) invalid += o.status == "INVALID";
  std::printf("\ninvalid plans: %d\n", invalid);
  return invalid == 0 ? 0 : 1;
}
