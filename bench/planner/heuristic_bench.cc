// The relaxed-plan heuristic's cost per evaluation with its operator groups
// (RelaxedPlanHeuristic::SetGroupOperators, the default) against the same
// heuristic without them, on the same states in the same process; prints
// the ratio. The task is this file's own driverlog-like haul world: trucks
// driven by whichever driver boarded them (so each drive exists once per
// driver), packages loaded and unloaded, drivers walking between places.
// Its size argument n gives n drivers, n trucks, 3n - 1 places on a ring
// with chords and 8n / 3 packages, the sizes driverlog-2014's problems grow
// by (n = 14: about 60,000 ground actions).
#include <cstdio>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "benchmark/benchmark.h"
#include "heuristics/relaxed_plan_heuristic.h"
#include "seaplan/task/grounder.h"
#include "snap_task.h"
#include "state_registry.h"

namespace seaplan::bench {
namespace {

constexpr char kDomain[] = R"((define (domain haul)
  (:requirements :typing :durative-actions)
  (:types truck driver package place)
  (:predicates (at ?x - (either truck driver package) ?p - place) (in ?k - package ?t - truck)
    (driving ?d - driver ?t - truck) (empty ?t - truck) (road ?a ?b - place)
    (path ?a ?b - place))
  (:durative-action load :parameters (?k - package ?t - truck ?p - place)
    :duration (= ?duration 2)
    :condition (and (at start (at ?k ?p)) (over all (at ?t ?p)))
    :effect (and (at start (not (at ?k ?p))) (at end (in ?k ?t))))
  (:durative-action unload :parameters (?k - package ?t - truck ?p - place)
    :duration (= ?duration 2)
    :condition (and (at start (in ?k ?t)) (over all (at ?t ?p)))
    :effect (and (at start (not (in ?k ?t))) (at end (at ?k ?p))))
  (:durative-action board :parameters (?d - driver ?t - truck ?p - place)
    :duration (= ?duration 1)
    :condition (and (at start (at ?d ?p)) (at start (empty ?t)) (over all (at ?t ?p)))
    :effect (and (at start (not (at ?d ?p))) (at start (not (empty ?t)))
      (at end (driving ?d ?t))))
  (:durative-action disembark :parameters (?d - driver ?t - truck ?p - place)
    :duration (= ?duration 1)
    :condition (and (at start (driving ?d ?t)) (over all (at ?t ?p)))
    :effect (and (at start (not (driving ?d ?t))) (at end (empty ?t)) (at end (at ?d ?p))))
  (:durative-action drive :parameters (?t - truck ?from ?to - place ?d - driver)
    :duration (= ?duration 10)
    :condition (and (at start (at ?t ?from)) (at start (road ?from ?to))
      (over all (driving ?d ?t)))
    :effect (and (at start (not (at ?t ?from))) (at end (at ?t ?to))))
  (:durative-action walk :parameters (?d - driver ?from ?to - place)
    :duration (= ?duration 20)
    :condition (and (at start (at ?d ?from)) (at start (path ?from ?to)))
    :effect (and (at start (not (at ?d ?from))) (at end (at ?d ?to))))))";

struct World {
  std::shared_ptr<const task::GroundTask> task;
  std::unique_ptr<search::SnapTask> snap;
  std::vector<search::StateData> states;
};

std::string Name(const char* kind, int i) {
  return std::string(kind) + std::to_string(i);
}

// The problem of size n and 32 states of it: every truck at a random
// place, driven by a driver or empty, the other drivers at random places,
// the packages at random places or in trucks.
World MakeWorld(int n) {
  const int places = 3 * n - 1, packages = 8 * n / 3;
  std::mt19937 rng(7);
  auto pick = [&](int k) { return static_cast<int>(rng() % static_cast<unsigned>(k)); };
  std::string p = "(define (problem haul-" + std::to_string(n) + ") (:domain haul) (:objects";
  for (int i = 0; i < n; ++i) p += " " + Name("t", i) + " - truck " + Name("d", i) + " - driver";
  for (int i = 0; i < packages; ++i) p += " " + Name("k", i) + " - package";
  for (int i = 0; i < places; ++i) p += " " + Name("s", i) + " - place";
  p += ") (:init";
  auto link = [&](const char* kind, int a, int b) {
    p += " (" + std::string(kind) + " " + Name("s", a) + " " + Name("s", b) + ") (" + kind + " " +
         Name("s", b) + " " + Name("s", a) + ")";
  };
  for (int i = 0; i < places; ++i) {
    link("road", i, (i + 1) % places);
    link("road", i, (i + 5) % places);
    link("path", i, (i + 1) % places);
  }
  for (int i = 0; i < n; ++i) {
    p += " (at " + Name("t", i) + " " + Name("s", pick(places)) + ") (empty " + Name("t", i) + ")";
    p += " (at " + Name("d", i) + " " + Name("s", pick(places)) + ")";
  }
  for (int i = 0; i < packages; ++i)
    p += " (at " + Name("k", i) + " " + Name("s", pick(places)) + ")";
  p += ") (:goal (and";
  for (int i = 0; i < packages; ++i)
    p += " (at " + Name("k", i) + " " + Name("s", pick(places)) + ")";
  for (int i = 0; i < n; i += 2) p += " (at " + Name("t", i) + " " + Name("s", pick(places)) + ")";
  p += ")))";
  World w;
  auto loaded = task::LoadTask(kDomain, p);
  if (!loaded.ok()) {
    std::fprintf(stderr, "haul task does not load: %s\n", loaded.ErrorText().c_str());
    std::exit(2);
  }
  w.task = loaded.task;
  w.snap = std::make_unique<search::SnapTask>(*w.task);
  std::map<std::string, task::FactId> fact;
  for (std::size_t f = 0; f < w.task->facts.size(); ++f) {
    fact[w.task->facts[f].DisplayName()] = static_cast<task::FactId>(f);
  }
  search::StateRegistry registry(w.snap->num_facts(), w.snap->num_vars());
  auto set = [&](search::StateData& s, const std::string& name) {
    auto it = fact.find(name);
    if (it != fact.end()) s.Set(it->second);  // a fact the grounder pruned is unreachable anyway
  };
  for (int k = 0; k < 32; ++k) {
    search::StateData s = registry.MakeEmpty();
    for (std::size_t f = 0; f < w.task->facts.size(); ++f) {
      if (w.task->facts[f].predicate == "road" || w.task->facts[f].predicate == "path") {
        s.Set(static_cast<task::FactId>(f));
      }
    }
    std::vector<int> driver_of(static_cast<std::size_t>(n), -1);
    for (int i = 0; i < n; ++i) {
      set(s, "(at " + Name("t", i) + " " + Name("s", pick(places)) + ")");
      const int t = pick(2 * n);  // about half the drivers drive
      if (t < n && driver_of[static_cast<std::size_t>(t)] < 0) {
        driver_of[static_cast<std::size_t>(t)] = i;
        set(s, "(driving " + Name("d", i) + " " + Name("t", t) + ")");
      } else {
        set(s, "(at " + Name("d", i) + " " + Name("s", pick(places)) + ")");
      }
    }
    for (int t = 0; t < n; ++t) {
      if (driver_of[static_cast<std::size_t>(t)] < 0) set(s, "(empty " + Name("t", t) + ")");
    }
    for (int i = 0; i < packages; ++i) {
      if (pick(3) == 0) {
        set(s, "(in " + Name("k", i) + " " + Name("t", pick(n)) + ")");
      } else {
        set(s, "(at " + Name("k", i) + " " + Name("s", pick(places)) + ")");
      }
    }
    w.states.push_back(std::move(s));
  }
  return w;
}

const World& GetWorld(int n) {
  static std::map<int, World> worlds;
  auto it = worlds.find(n);
  if (it == worlds.end()) it = worlds.emplace(n, MakeWorld(n)).first;
  return it->second;
}

void Evaluate(benchmark::State& state, bool grouped) {
  const World& w = GetWorld(static_cast<int>(state.range(0)));
  search::RelaxedPlanHeuristic heuristic(*w.snap, 0.001);
  heuristic.SetGroupOperators(grouped);
  std::vector<search::SnapId> preferred;
  double h_sum = 0;
  std::size_t next = 0;
  for (auto _ : state) {
    const int h = heuristic.Evaluate(w.states[next], &preferred);
    benchmark::DoNotOptimize(h);
    h_sum += h;
    next = (next + 1) % w.states.size();
  }
  state.counters["h"] = benchmark::Counter(h_sum, benchmark::Counter::kAvgIterations);
  state.counters["groups"] = heuristic.num_operator_groups();
  state.counters["actions"] = static_cast<double>(w.task->actions.size());
}

void BM_RelaxedPlan_Exact(benchmark::State& state) {
  Evaluate(state, false);
}
void BM_RelaxedPlan_Grouped(benchmark::State& state) {
  Evaluate(state, true);
}
BENCHMARK(BM_RelaxedPlan_Exact)->Arg(4)->Arg(14)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RelaxedPlan_Grouped)->Arg(4)->Arg(14)->Unit(benchmark::kMicrosecond);

// Collects per-benchmark CPU times to print exact / grouped at the end.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      if (r.aggregate_name.empty() || r.aggregate_name == "median") {
        times_[r.run_name.function_name + "/" + r.run_name.args] = r.GetAdjustedCPUTime();
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }
  void PrintRatios() const {
    std::printf("\nspeed-up (exact / grouped CPU time per evaluation, same states):\n");
    for (const auto& [name, exact] : times_) {
      const std::string prefix = "BM_RelaxedPlan_Exact/";
      if (name.rfind(prefix, 0) != 0) continue;
      const std::string size = name.substr(prefix.size());
      auto grouped = times_.find("BM_RelaxedPlan_Grouped/" + size);
      if (grouped == times_.end() || grouped->second <= 0) continue;
      std::printf("  n = %-4s %7.2fx\n", size.c_str(), exact / grouped->second);
    }
  }

 private:
  std::map<std::string, double> times_;
};

}  // namespace
}  // namespace seaplan::bench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  seaplan::bench::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.PrintRatios();
  benchmark::Shutdown();
  return 0;
}
