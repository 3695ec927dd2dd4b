// seaplan-bench-ground [DIR] [--only NAME] : parses and grounds every problem
// of a folder laid out like the shared bench set (DIR/<domain>/pNN.pddl with
// DIR/<domain>/domain.pddl or domain-<k>.pddl for pNN) and prints, per
// problem, parse and ground times, ground sizes and the peak heap used while
// loading; then the paper's case-A fjord problem (built in) as a named line
// and the totals.
//
// Peak memory: this program replaces global operator new/delete to track the
// live heap, so "peak_mb" is the high-water mark of heap bytes during that
// problem's LoadTask (what the grounder itself needs), independent of the
// order problems run in; the process's ru_maxrss is printed at the end.
//
// --digest adds a column with a 64-bit hash of the whole ground task (facts,
// numeric variables, actions with every condition and effect, initial state,
// timed literals, goal and metric, in their order), so that two builds of
// the grounder can be checked to produce identical tasks. --stages adds the
// time of each grounding stage (symbols, schemas, reachability,
// instantiation; ms, from the run with the best ground_ms).
#include <malloc.h>
#include <sys/resource.h>
#include <time.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "fjord_case_a.h"
#include "seaplan/task/grounder.h"

namespace {

std::atomic<long long> g_live{0};
std::atomic<long long> g_peak{0};

void Track(void* p) {
  if (p == nullptr) return;
  const long long now = g_live += static_cast<long long>(malloc_usable_size(p));
  long long peak = g_peak.load();
  while (now > peak && !g_peak.compare_exchange_weak(peak, now)) {
  }
}

}  // namespace

void* operator new(std::size_t n) {
  void* p = std::malloc(n == 0 ? 1 : n);
  if (p == nullptr) throw std::bad_alloc();
  Track(p);
  return p;
}
void operator delete(void* p) noexcept {
  if (p == nullptr) return;
  g_live -= static_cast<long long>(malloc_usable_size(p));
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  operator delete(p);
}

namespace {

namespace fs = std::filesystem;

// Thread CPU time: on a shared, loaded machine wall-clock figures include
// preemption; CPU time shows what the work itself costs.
double CpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) / 1e6;
}

// FNV-1a over a canonical rendering of the task: any difference in content
// or order changes it.
class Digest {
 public:
  void Add(std::string_view text) {
    for (char c : text) Byte(static_cast<unsigned char>(c));
    Byte(0);
  }
  void Add(std::int64_t value) {
    for (int i = 0; i < 8; ++i) Byte(static_cast<unsigned char>(value >> (8 * i)));
  }
  void Add(double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    Add(static_cast<std::int64_t>(bits));
  }
  template <typename T>
  void AddAll(const std::vector<T>& values) {
    Add(static_cast<std::int64_t>(values.size()));
    for (const auto& v : values) Add(v);
  }
  void Add(const seaplan::task::NumericExpr& e) {
    Add(static_cast<std::int64_t>(e.nodes.size()));
    for (const auto& n : e.nodes) {
      Add(static_cast<std::int64_t>(n.op));
      Add(n.value);
      Add(static_cast<std::int64_t>(n.var));
      Add(static_cast<std::int64_t>(n.lhs));
      Add(static_cast<std::int64_t>(n.rhs));
    }
  }
  void Add(const seaplan::task::NumericCondition& c) {
    Add(c.lhs);
    Add(static_cast<std::int64_t>(c.comparator));
    Add(c.rhs);
  }
  void Add(const seaplan::task::NumericEffect& e) {
    Add(static_cast<std::int64_t>(e.var));
    Add(static_cast<std::int64_t>(e.op));
    Add(e.value);
  }
  void Add(const seaplan::task::Condition& c) {
    AddIds(c.positive);
    AddIds(c.negative);
    AddAll(c.numeric);
  }
  void Add(const seaplan::task::ConditionalEffect& e) {
    Add(e.condition);
    Add(static_cast<std::int64_t>(e.condition_time));
    AddIds(e.add);
    AddIds(e.del);
    AddAll(e.numeric);
  }
  void Add(const seaplan::task::Effects& e) {
    AddIds(e.add);
    AddIds(e.del);
    AddAll(e.numeric);
    AddAll(e.conditional);
  }
  void Add(const seaplan::task::GroundTask& task) {
    Add(task.domain_name);
    Add(task.problem_name);
    Add(static_cast<std::int64_t>(task.facts.size()));
    for (const auto& f : task.facts) Add(f.DisplayName());
    Add(static_cast<std::int64_t>(task.numeric_vars.size()));
    for (const auto& v : task.numeric_vars) Add(v.DisplayName());
    Add(static_cast<std::int64_t>(task.actions.size()));
    for (const auto& a : task.actions) {
      Add(a.DisplayName());
      Add(static_cast<std::int64_t>(a.variant));
      Add(static_cast<std::int64_t>(a.is_durative));
      Add(static_cast<std::int64_t>(a.duration.size()));
      for (const auto& d : a.duration) {
        Add(static_cast<std::int64_t>(d.comparator));
        Add(d.value);
      }
      Add(a.at_start);
      Add(a.over_all);
      Add(a.at_end);
      Add(a.start_effects);
      Add(a.end_effects);
    }
    AddIds(task.initial_facts);
    AddAll(task.initial_values);
    Add(static_cast<std::int64_t>(task.timed_literals.size()));
    for (const auto& t : task.timed_literals) {
      Add(t.time_s);
      Add(static_cast<std::int64_t>(t.fact));
      Add(static_cast<std::int64_t>(t.value));
    }
    Add(static_cast<std::int64_t>(task.timed_fluents.size()));
    for (const auto& t : task.timed_fluents) {
      Add(t.time_s);
      Add(static_cast<std::int64_t>(t.var));
      Add(t.value);
    }
    Add(task.goal);
    Add(static_cast<std::int64_t>(task.metric.minimize));
    Add(task.metric.expression);
  }
  std::uint64_t value() const { return hash_; }

 private:
  void AddIds(const std::vector<std::int32_t>& ids) {
    Add(static_cast<std::int64_t>(ids.size()));
    for (std::int32_t id : ids) Add(static_cast<std::int64_t>(id));
  }
  void Byte(unsigned char b) {
    hash_ ^= b;
    hash_ *= 1099511628211ull;
  }
  std::uint64_t hash_ = 1469598103934665603ull;
};

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

struct Row {
  std::string name;
  std::string status;
  double parse_ms = 0, ground_ms = 0;
  seaplan::task::TaskSize size;
  double peak_mb = 0;
  double first_ms = 0;                        // the first (cold) call, parse + ground
  double median_ms = 0;                       // median of all runs, parse + ground
  double cpu_ms = 0;                          // thread CPU time of the first call
  std::uint64_t digest = 0;                   // of the ground task (0 when none)
  seaplan::task::GroundingStageTimes stages;  // of the run with the best ground_ms
  std::string note;
};

Row Run(const std::string& name, const std::string& domain, const std::string& problem,
        int repeats) {
  Row row;
  row.name = name;
  const long long base = g_live.load();
  g_peak.store(base);
  const double cpu0 = CpuMs();
  auto result = seaplan::task::LoadTask(domain, problem);
  row.cpu_ms = CpuMs() - cpu0;
  row.peak_mb = static_cast<double>(g_peak.load() - base) / (1024.0 * 1024.0);
  row.status = result.ok() ? "ok" : (result.unsupported() ? "UNSUPPORTED" : "ERROR");
  row.parse_ms = result.stats.parse_ms;
  row.ground_ms = result.stats.ground_ms;
  row.stages = result.stats.stages;
  row.first_ms = row.parse_ms + row.ground_ms;
  if (result.task) {
    row.size = result.task->Size();
    Digest digest;
    digest.Add(*result.task);
    row.digest = digest.value();
  }
  for (const auto& d : result.diagnostics) {
    if (d.severity == seaplan::pddl::Severity::kError) {
      row.note = d.ToString();
      break;
    }
  }
  // Small problems: report the best of several runs (timer resolution, warm
  // caches, and other processes on a shared machine), plus the median.
  std::vector<double> totals{row.first_ms};
  for (int i = 1; i < repeats; ++i) {
    auto again = seaplan::task::LoadTask(domain, problem);
    row.parse_ms = std::min(row.parse_ms, again.stats.parse_ms);
    if (again.stats.ground_ms < row.ground_ms) {
      row.ground_ms = again.stats.ground_ms;
      row.stages = again.stats.stages;
    }
    totals.push_back(again.stats.parse_ms + again.stats.ground_ms);
  }
  std::sort(totals.begin(), totals.end());
  row.median_ms = totals[totals.size() / 2];
  return row;
}

void Print(const Row& r, bool with_digest, bool with_stages) {
  std::printf("%-40s %-11s %9.3f %9.3f %9.3f %9.3f %8zu %6zu %9zu %8.2f", r.name.c_str(),
              r.status.c_str(), r.parse_ms, r.ground_ms, r.parse_ms + r.ground_ms, r.cpu_ms,
              r.size.facts, r.size.numeric_vars, r.size.actions, r.peak_mb);
  if (with_digest) std::printf(" %016llx", static_cast<unsigned long long>(r.digest));
  if (with_stages) {
    std::printf(" %8.3f %8.3f %8.3f %8.3f", r.stages.symbols_ms, r.stages.schemas_ms,
                r.stages.reachability_ms, r.stages.instantiation_ms);
  }
  std::printf("%s%s\n", r.note.empty() ? "" : "  ", r.note.c_str());
}

fs::path DefaultDir() {
  if (const char* shared = std::getenv("SEAPLAN_SHARED"); shared != nullptr && *shared != '\0') {
    return fs::path(shared) / "bench";
  }
  if (fs::exists("../shared/bench")) return "../shared/bench";
#ifdef SEAPLAN_SHARED_DEFAULT
  return fs::path(SEAPLAN_SHARED_DEFAULT) / "bench";
#else
  return "../shared/bench";
#endif
}

}  // namespace

int main(int argc, char** argv) {
  fs::path dir;
  std::string only;
  bool with_digest = false;
  bool with_stages = false;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--only" && i + 1 < argc) {
      only = argv[++i];
    } else if (arg == "--digest") {
      with_digest = true;
    } else if (arg == "--stages") {
      with_stages = true;
    } else if (arg == "-h" || arg == "--help") {
      std::printf("usage: %s [DIR] [--only DOMAIN] [--digest] [--stages]\n", argv[0]);
      return 0;
    } else {
      dir = arg;
    }
  }
  if (dir.empty()) dir = DefaultDir();

  std::printf("%-40s %-11s %9s %9s %9s %9s %8s %6s %9s %8s\n", "problem", "status", "parse_ms",
              "ground_ms", "total_ms", "cpu1_ms", "facts", "nvars", "actions", "peak_mb");
  if (with_digest) std::printf("(then: digest of the ground task)\n");
  if (with_stages) {
    std::printf("(then: symbols_ms schemas_ms reachability_ms instantiation_ms)\n");
  }
  // The case-A-sized problem: best of 200 runs (it takes well under 1 ms).
  Row fjord = Run("fjord-case-a (built in)", seaplan::bench::kFjordDomain,
                  seaplan::bench::kFjordProblemCaseA, 200);
  Print(fjord, with_digest, with_stages);

  std::vector<fs::path> domains;
  if (fs::is_directory(dir)) {
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.is_directory()) domains.push_back(entry.path());
    }
  } else {
    std::fprintf(stderr, "benchmark folder %s not found (pass DIR or set SEAPLAN_SHARED)\n",
                 dir.c_str());
  }
  std::sort(domains.begin(), domains.end());
  double total_parse = 0, total_ground = 0, worst = 0;
  seaplan::task::GroundingStageTimes total_stages;
  std::string worst_name;
  int count = 0, ok = 0, unsupported = 0, errors = 0;
  for (const auto& d : domains) {
    if (!only.empty() && d.filename() != only) continue;
    std::vector<fs::path> problems;
    for (const auto& entry : fs::directory_iterator(d)) {
      const std::string f = entry.path().filename().string();
      if (f.size() > 5 && f[0] == 'p' && f.ends_with(".pddl") &&
          std::isdigit(static_cast<unsigned char>(f[1]))) {
        problems.push_back(entry.path());
      }
    }
    std::sort(problems.begin(), problems.end());
    for (const auto& p : problems) {
      const std::string stem = p.stem().string();  // pNN
      const int k = std::atoi(stem.c_str() + 1);
      fs::path domain_file = d / ("domain-" + std::to_string(k) + ".pddl");
      if (!fs::exists(domain_file)) domain_file = d / "domain.pddl";
      const std::string domain_text = ReadFile(domain_file);
      const std::string problem_text = ReadFile(p);
      Row probe = Run(d.filename().string() + "/" + stem, domain_text, problem_text, 1);
      if (probe.parse_ms + probe.ground_ms < 20) {
        probe = Run(d.filename().string() + "/" + stem, domain_text, problem_text, 5);
      }
      Print(probe, with_digest, with_stages);
      ++count;
      ok += probe.status == "ok";
      unsupported += probe.status == "UNSUPPORTED";
      errors += probe.status == "ERROR";
      total_parse += probe.parse_ms;
      total_ground += probe.ground_ms;
      total_stages.symbols_ms += probe.stages.symbols_ms;
      total_stages.schemas_ms += probe.stages.schemas_ms;
      total_stages.reachability_ms += probe.stages.reachability_ms;
      total_stages.instantiation_ms += probe.stages.instantiation_ms;
      if (probe.parse_ms + probe.ground_ms > worst) {
        worst = probe.parse_ms + probe.ground_ms;
        worst_name = probe.name;
      }
    }
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf(
      "\nTOTAL %d problems: %d ok, %d unsupported, %d errors; parse %.1f ms, ground %.1f ms\n",
      count, ok, unsupported, errors, total_parse, total_ground);
  if (with_stages) {
    std::printf(
        "STAGES symbols %.1f ms, schemas %.1f ms, reachability %.1f ms, instantiation %.1f ms\n",
        total_stages.symbols_ms, total_stages.schemas_ms, total_stages.reachability_ms,
        total_stages.instantiation_ms);
  }
  std::printf("LARGEST %s: %.1f ms (target < 2000 ms)\n", worst_name.c_str(), worst);
  std::printf(
      "CASE-A fjord-case-a: parse+ground %.3f ms best, %.3f ms median of 200 (target < 1 ms); "
      "first cold call "
      "%.3f ms wall, %.3f ms CPU\n",
      fjord.parse_ms + fjord.ground_ms, fjord.median_ms, fjord.first_ms, fjord.cpu_ms);
  std::printf("process ru_maxrss: %.1f MB\n", static_cast<double>(usage.ru_maxrss) / 1024.0);
  return 0;  // errors are results here (tms-2011 is known to be invalid), printed above
}
