// seaplan-bench-planner [--time-limit 60] [--memory-limit 2048] [--jobs 1]
// [--filter substr] [--peers FILE] [--peer NAME=COMMAND]... [--seaplan PATH]
// [--first-plan] [--no-in-process] [--print-plans] [DIR]
//
// Runs every p01..p05 of every domain folder of DIR (default
// $SEAPLAN_SHARED/bench, else ../shared/bench) through `seaplan plan` as a
// child process, one problem at a time, as a user would (start-up, parsing,
// grounding, search, output and exit included), and every planner given with
// --peer the same way under the same limits. Each plan is validated again in
// this process. Separately, and labelled so, the in-process time to the
// first plan (parse + ground + search inside this process, no process
// start-up). Then per domain and in total: coverage, IPC time and quality
// scores of every planner over the same problems, with the stored peer
// figures of peers.md ("Every run" table) as a labelled reference.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "child_process.h"
#include "peers.h"
#include "seaplan/common/log.h"
#include "seaplan/search/planner.h"
#include "seaplan/task/grounder.h"
#include "seaplan/validate/validator.h"

namespace fs = std::filesystem;
using seaplan::bench::IsPlanLine;
using seaplan::bench::LastPlan;
using seaplan::bench::Run;

namespace {

struct Job {
  std::string domain, problem;
  fs::path domain_file, problem_file;
};

// A planner run as a child process: its command with {domain}, {problem},
// {time_limit}, {memory_limit} and {plan} replaced (domain and problem are
// appended when the command names neither).
struct Planner {
  std::string name;
  std::vector<std::string> command;
  bool is_seaplan = false;
};

// One planner on one problem, as a whole process.
struct ProcessOutcome {
  Run run;  // time_s: spawn to the first plan's arrival
  std::string status, note, plan_text;
  double wall_s = 0, cpu_s = 0, rss_mb = 0;
};

// seaplan on one problem inside this process (labelled "in-process").
struct InProcessOutcome {
  bool ran = false;
  std::string status;
  double first_s = -1, load_s = 0;
  std::size_t expanded = 0, generated = 0;
};

struct Outcome {
  std::vector<ProcessOutcome> process;  // one per planner, in the order of the planners
  InProcessOutcome in_process;
};

std::string ReadAll(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string Replace(std::string text, const std::string& from, const std::string& to) {
  for (std::size_t at = text.find(from); at != std::string::npos;
       at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// The first "; status: X" line of seaplan's output, else "".
std::string SeaplanStatus(const std::string& out) {
  const std::string key = "; status: ";
  const auto at = out.find(key);
  if (at == std::string::npos) return "";
  std::string status = out.substr(at + key.size(), out.find('\n', at) - at - key.size());
  for (char& c : status) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return status;
}

struct Settings {
  double limit_s = 60, memory_mb = 2048;
  bool first_plan_only = false, in_process = true;
  fs::path scratch;
};

ProcessOutcome RunProcess(const Planner& planner, const Job& job, const Settings& settings,
                          const seaplan::task::LoadResult& loaded, int worker) {
  ProcessOutcome o;
  o.run.domain = job.domain;
  o.run.problem = job.problem;
  o.run.planner = planner.name;
  const fs::path plan_file = settings.scratch / ("plan-" + std::to_string(worker));
  fs::remove(plan_file);
  char limit[32], memory[32];
  std::snprintf(limit, sizeof limit, "%g", settings.limit_s);
  std::snprintf(memory, sizeof memory, "%g", settings.memory_mb);
  std::vector<std::string> argv;
  bool names_files = false, writes_plan_file = false;
  for (const auto& part : planner.command) {
    names_files = names_files || part.find("{domain}") != std::string::npos;
    writes_plan_file = writes_plan_file || part.find("{plan}") != std::string::npos;
    std::string arg = Replace(part, "{domain}", job.domain_file.string());
    arg = Replace(arg, "{problem}", job.problem_file.string());
    arg = Replace(arg, "{time_limit}", limit);
    arg = Replace(arg, "{memory_limit}", memory);
    argv.push_back(Replace(arg, "{plan}", plan_file.string()));
  }
  if (!names_files) {
    argv.push_back(job.domain_file.string());
    argv.push_back(job.problem_file.string());
  }
  // seaplan reports each plan it finds on stderr at once (--stream); other
  // planners are timed by the arrival of their first plan line.
  double first_plan_at = -1;
  auto on_line = [&](bool is_stderr, const std::string& line, double at_s) {
    if (first_plan_at >= 0) return;
    const bool plan_found = planner.is_seaplan ? is_stderr && line.rfind("improved plan:", 0) == 0
                                               : !is_stderr && IsPlanLine(line);
    if (plan_found) first_plan_at = at_s;
  };
  seaplan::bench::ChildLimits limits;
  limits.time_limit_s = settings.limit_s;
  limits.memory_limit_mb = settings.memory_mb;
  const auto child = seaplan::bench::RunChild(argv, limits, on_line);
  o.wall_s = child.wall_s;
  o.cpu_s = child.cpu_s;
  o.rss_mb = child.peak_rss_mb;
  if (!child.started) {
    o.status = "not-started";
    o.note = "cannot run " + argv[0];
    return o;
  }
  const std::string plan_text = writes_plan_file && fs::exists(plan_file)
                                    ? LastPlan(ReadAll(plan_file))
                                    : LastPlan(child.out);
  if (child.killed_for_time) {
    o.status = "timeout(killed)";
  } else if (child.killed_for_memory) {
    o.status = "memout(killed)";
  } else if (child.signal != 0) {
    o.status = "signal " + std::to_string(child.signal);
  } else if (planner.is_seaplan) {
    o.status = SeaplanStatus(child.out);
    if (o.status.empty()) o.status = child.exit_code == 2 ? "load-error" : "error";
  } else {
    o.status = plan_text.empty() ? "rc=" + std::to_string(child.exit_code) : "plan";
  }
  if (plan_text.empty()) {
    // The last line the planner wrote (its error, or its last progress report).
    std::string err = child.err.empty() ? child.out : child.err;
    while (!err.empty() && err.back() == '\n') err.pop_back();
    o.note = err.substr(err.find_last_of('\n') + 1, 200);
    return o;
  }
  // Independent check of the printed plan, as VAL checked the peers'.
  if (!loaded.ok()) {
    o.status = "unchecked";
    o.note = "the bench cannot load the problem to check the plan";
    return o;
  }
  auto parsed = seaplan::validate::ParsePlan(plan_text);
  if (!parsed.ok()) {
    o.status = "INVALID";
    o.note = std::string(parsed.status().message());
    return o;
  }
  const auto v = seaplan::validate::ValidatePlan(*loaded.task, *parsed);
  if (!v.valid) {
    o.status = "INVALID";
    o.note = v.ToString();
    return o;
  }
  o.plan_text = plan_text;
  if (!planner.is_seaplan) o.status = "solved";
  o.run.solved = true;
  o.run.time_s = first_plan_at >= 0 ? first_plan_at : child.wall_s;
  o.run.makespan = v.makespan_s;
  o.run.actions = static_cast<int>(parsed->steps.size());
  return o;
}

InProcessOutcome RunInProcess(const Job& job, const Settings& settings) {
  InProcessOutcome o;
  o.ran = true;
  const auto start = std::chrono::steady_clock::now();
  auto loaded = seaplan::task::LoadTask(ReadAll(job.domain_file), ReadAll(job.problem_file));
  o.load_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!loaded.ok()) {
    o.status = "load-error";
    return o;
  }
  seaplan::search::PlannerOptions options;
  options.time_limit_s = std::max(0.01, settings.limit_s - o.load_s);
  options.memory_limit_mb = static_cast<std::size_t>(settings.memory_mb);
  options.anytime = false;
  const auto r = seaplan::search::SolveTask(*loaded.task, options, seaplan::StopToken());
  o.status = seaplan::search::ToString(r.status);
  o.expanded = r.stats.expanded;
  o.generated = r.stats.generated;
  if (r.stats.first_plan_time_s >= 0) o.first_s = o.load_s + r.stats.first_plan_time_s;
  return o;
}

double Median(std::vector<double> v) {
  if (v.empty()) return -1;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::vector<std::string> SplitWords(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  int jobs = 1;
  std::string filter;
  fs::path dir, peers_file;
  fs::path seaplan_path = fs::read_symlink("/proc/self/exe").parent_path() / "seaplan";
  std::vector<Planner> peers;
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
      settings.limit_s = std::atof(value().c_str());
    } else if (a == "--memory-limit") {
      settings.memory_mb = std::atof(value().c_str());
    } else if (a == "--jobs") {
      jobs = std::max(1, std::atoi(value().c_str()));
    } else if (a == "--filter") {
      filter = value();
    } else if (a == "--first-plan") {
      settings.first_plan_only = true;
    } else if (a == "--no-in-process") {
      settings.in_process = false;
    } else if (a == "--print-plans") {
      print_plans = true;
    } else if (a == "--peers") {
      peers_file = value();
    } else if (a == "--seaplan") {
      seaplan_path = value();
    } else if (a == "--peer") {
      const std::string spec = value();
      const auto eq = spec.find('=');
      Planner peer;
      if (eq != std::string::npos) {
        peer.name = spec.substr(0, eq);
        peer.command = SplitWords(spec.substr(eq + 1));
      }
      if (peer.name.empty() || peer.name == "seaplan" || peer.command.empty()) {
        std::fprintf(stderr, "--peer NAME=COMMAND expected, got '%s'\n", spec.c_str());
        return 2;
      }
      peers.push_back(peer);
    } else if (a == "--help" || a == "-h") {
      std::printf(
          "usage: seaplan-bench-planner [--time-limit 60] [--memory-limit 2048] [--jobs 1] "
          "[--filter substr] [--peers FILE] [--peer NAME=COMMAND]... [--seaplan PATH] "
          "[--first-plan] [--no-in-process] [--print-plans] [DIR]\n");
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    } else {
      dir = a;
    }
  }
  if (!(settings.limit_s > 1) || !(settings.memory_mb > 0)) {
    std::fprintf(stderr, "--time-limit must be > 1 s and --memory-limit > 0 MB\n");
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
  if (!fs::exists(seaplan_path)) {
    std::fprintf(stderr, "%s not found (give --seaplan PATH)\n", seaplan_path.c_str());
    return 2;
  }
  seaplan::log::SetLevel(seaplan::log::Level::kWarn);
  settings.scratch =
      fs::temp_directory_path() / ("seaplan-bench-planner-" + std::to_string(getpid()));
  fs::create_directories(settings.scratch);

  std::vector<Planner> planners = {
      {"seaplan",
       {seaplan_path.string(), "plan", "{domain}", "{problem}", "--time-limit", "{time_limit}",
        "--memory-limit", "{memory_limit}", "--stream"},
       true}};
  if (settings.first_plan_only) planners[0].command.push_back("--no-anytime");
  planners.insert(planners.end(), peers.begin(), peers.end());

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

  std::printf(
      "whole processes: %s, time limit %g s, memory limit %g MB (resident, sampled every 10 ms), "
      "%d at a time\n",
      settings.first_plan_only ? "first plan only (--no-anytime)" : "anytime", settings.limit_s,
      settings.memory_mb, jobs);
  std::printf("%-26s %-4s %-10s %-19s %8s %8s %8s %7s %12s %5s | %-17s %9s %9s\n", "domain", "prob",
              "planner", "status", "first_s", "wall_s", "cpu_s", "rss_mb", "makespan", "acts",
              "in-process status", "first_s", "expanded");
  std::fflush(stdout);
  std::vector<Outcome> outcomes(all.size());
  std::atomic<std::size_t> next{0};
  std::mutex print_mutex;
  auto worker = [&](int worker_index) {
    while (true) {
      const std::size_t i = next++;
      if (i >= all.size()) return;
      const Job& job = all[i];
      const auto loaded =
          seaplan::task::LoadTask(ReadAll(job.domain_file), ReadAll(job.problem_file));
      Outcome& outcome = outcomes[i];
      for (const auto& planner : planners) {
        outcome.process.push_back(RunProcess(planner, job, settings, loaded, worker_index));
      }
      if (settings.in_process && outcome.process[0].run.solved) {
        outcome.in_process = RunInProcess(job, settings);
      }
      std::lock_guard<std::mutex> lock(print_mutex);
      for (std::size_t p = 0; p < planners.size(); ++p) {
        const ProcessOutcome& o = outcome.process[p];
        char first[32] = "-", makespan[32] = "-", acts[16] = "-";
        if (o.run.solved) {
          std::snprintf(first, sizeof first, "%.3f", o.run.time_s);
          std::snprintf(makespan, sizeof makespan, "%.3f", o.run.makespan);
          std::snprintf(acts, sizeof acts, "%d", o.run.actions);
        }
        std::printf("%-26s %-4s %-10s %-19s %8s %8.3f %8.3f %7.0f %12s %5s", job.domain.c_str(),
                    job.problem.c_str(), planners[p].name.c_str(), o.status.c_str(), first,
                    o.wall_s, o.cpu_s, o.rss_mb, makespan, acts);
        const InProcessOutcome& in = outcome.in_process;
        if (p == 0 && in.ran) {
          std::printf(" | %-17s %9.4f %9zu", in.status.c_str(), in.first_s, in.expanded);
        } else if (!o.note.empty()) {
          std::printf(" | %s", o.note.substr(0, o.note.find('\n')).c_str());
        }
        std::printf("\n");
        if (print_plans && !o.plan_text.empty()) std::printf("%s", o.plan_text.c_str());
      }
      std::fflush(stdout);
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(static_cast<std::size_t>(jobs));
  for (int t = 0; t < jobs; ++t) threads.emplace_back(worker, t);
  for (auto& t : threads) t.join();
  fs::remove_all(settings.scratch);

  // Scores over the same problems: the planners run here, and the stored
  // figures of peers.md labelled "(peers.md)".
  std::vector<std::string> labels;
  labels.reserve(planners.size());
  for (const auto& p : planners) labels.push_back(p.name);
  std::map<std::pair<std::string, std::string>, std::map<std::string, Run>> table;
  for (const auto& o : outcomes) {
    for (const auto& r : o.process) table[{r.run.domain, r.run.problem}][r.run.planner] = r.run;
  }
  std::set<std::string> stored;
  for (auto r : seaplan::bench::ParsePeerRuns(ReadAll(peers_file))) {
    auto it = table.find({r.domain, r.problem});
    if (it == table.end()) continue;
    r.planner += " (peers.md)";
    it->second[r.planner] = r;
    stored.insert(r.planner);
  }
  labels.insert(labels.end(), stored.begin(), stored.end());
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
      if (r.solved && r.makespan > 0 && r.time_s <= settings.limit_s)
        best = std::min(best, r.makespan);
    }
    bool any = false;
    for (const auto& p : labels) {
      auto it = runs.find(p);
      if (it == runs.end()) continue;
      const Run& r = it->second;
      Score& s = by_domain[key.first][p];
      ++s.run;
      ++total[p].run;
      // Stored peers ran with 60 s: a plan counts only within this run's limit.
      if (!r.solved || r.time_s > settings.limit_s) continue;
      if (p != "seaplan") any = true;
      ++s.solved;
      ++total[p].solved;
      const double ts = seaplan::bench::TimeScore(r, settings.limit_s);
      const double qs = r.makespan > 0 ? best / r.makespan : 1.0;
      s.time += ts;
      s.quality += qs;
      total[p].time += ts;
      total[p].quality += qs;
    }
    any_peer_solved += any;
  }
  std::printf(
      "\nPer domain (coverage solved/run, IPC time score, IPC quality score), limit %g s; time = "
      "spawn to first plan of a whole process\n",
      settings.limit_s);
  std::printf("%-26s", "domain");
  for (const auto& p : labels) std::printf(" | %-20s", p.c_str());
  std::printf("\n");
  for (const auto& [domain, scores] : by_domain) {
    std::printf("%-26s", domain.c_str());
    for (const auto& p : labels) {
      auto it = scores.find(p);
      char cell[64] = "-";
      if (it != scores.end()) {
        std::snprintf(cell, sizeof cell, "%d/%d %.2f %.2f", it->second.solved, it->second.run,
                      it->second.time, it->second.quality);
      }
      std::printf(" | %-20s", cell);
    }
    std::printf("\n");
  }
  std::printf("%-26s", "TOTAL");
  for (const auto& p : labels) {
    char cell[64];
    std::snprintf(cell, sizeof cell, "%d/%d %.2f %.2f", total[p].solved, total[p].run,
                  total[p].time, total[p].quality);
    std::printf(" | %-20s", cell);
  }
  std::printf("\nany other planner (within the limit): %d/%zu\n", any_peer_solved, table.size());

  // In-process first-plan times and, with --first-plan, the CPU time of
  // seaplan's whole process (it exits at its first plan), keyed like the table.
  std::map<std::pair<std::string, std::string>, double> in_process_s, process_cpu_s;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const auto& in = outcomes[i].in_process;
    const std::pair<std::string, std::string> key{all[i].domain, all[i].problem};
    if (in.ran && in.first_s >= 0) in_process_s[key] = in.first_s;
    if (settings.first_plan_only) process_cpu_s[key] = outcomes[i].process[0].cpu_s;
  }
  std::printf(
      "\nMedian time to the first plan on the problems both solve (seaplan: whole process, spawn "
      "to the first plan's arrival; in-process: parse + ground + search inside the bench, "
      "anytime off, no process start-up):\n");
  for (const auto& p : labels) {
    if (p == "seaplan") continue;
    std::vector<double> ours, theirs, ours_in_process, ours_cpu;
    for (const auto& [key, runs] : table) {
      auto a = runs.find("seaplan");
      auto b = runs.find(p);
      if (a == runs.end() || b == runs.end() || !a->second.solved || !b->second.solved) continue;
      ours.push_back(a->second.time_s);
      theirs.push_back(b->second.time_s);
      if (auto in = in_process_s.find(key); in != in_process_s.end())
        ours_in_process.push_back(in->second);
      if (auto cpu = process_cpu_s.find(key); cpu != process_cpu_s.end())
        ours_cpu.push_back(cpu->second);
    }
    if (ours.empty()) {
      std::printf("  vs %-18s: no problem both solve\n", p.c_str());
      continue;
    }
    const double mo = Median(ours), mt = Median(theirs), mi = Median(ours_in_process);
    std::printf("  vs %-18s: %3zu problems, seaplan whole process %.4f s, %s %.4f s, ratio %.3f",
                p.c_str(), ours.size(), mo, p.c_str(), mt, mt > 0 ? mo / mt : 0.0);
    if (!ours_in_process.empty()) {
      std::printf("; seaplan in-process %.4f s on %zu of them (ratio %.3f, not like for like)", mi,
                  ours_in_process.size(), mt > 0 ? mi / mt : 0.0);
    }
    // On a loaded machine the wall time is mostly waiting for a core; the
    // CPU time of the whole process is what it would take on an idle one.
    if (!ours_cpu.empty()) {
      std::printf("; seaplan whole process CPU time (user + system, to exit) %.4f s (ratio %.3f)",
                  Median(ours_cpu), mt > 0 ? Median(ours_cpu) / mt : 0.0);
    }
    std::printf("\n");
  }
  int invalid = 0;
  for (const auto& o : outcomes) {
    for (const auto& r : o.process) invalid += r.status == "INVALID";
  }
  std::printf("\ninvalid plans: %d\n", invalid);
  return invalid == 0 ? 0 : 1;
}
