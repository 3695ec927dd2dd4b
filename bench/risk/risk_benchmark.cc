// Drifting-grounding risk benchmarks: the library (precomputed dynamics,
// no allocation, tabulated P(G)) against a naive C++ port of the public
// Python (naive_baseline.h), in one binary; prints naive/fast ratios.
//
// Scenario: the AMM TTG settings (600 s horizon, 30 s steps, wind 10 m/s
// from -110 deg, current 1 m/s toward -110 deg, 2 m/s initial surge) with a
// 128-vertex island in the drift path, from 16 start points (most ground
// after 15-21 steps; the public code averages ~18).
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>
#include <string>
#include <vector>

#include "benchmark/benchmark.h"
#include "naive_baseline.h"
#include "seaplan/risk/drifting_grounding.h"
#include "seaplan/risk/grounding_risk.h"
#include "seaplan/risk/time_to_grounding.h"

namespace seaplan::bench {
namespace {

using ship::MsoMode;

struct Scenario {
  ship::ShipParams ship;
  ship::Environment env;
  risk::PolygonObstacles obstacles;
  std::vector<ship::ShipState> starts;
  std::vector<double> ttgs;  // TTG values to query (multiples of 30 s and off-grid)
};

const Scenario& GetScenario() {
  static const Scenario* s = [] {
    std::vector<Eigen::Vector2d> island;
    for (int i = 0; i < 128; ++i) {
      const double a = 2 * std::numbers::pi * i / 128;
      island.push_back({150 + 300 * std::cos(a), -650 + 300 * std::sin(a)});
    }
    auto obs = risk::PolygonObstacles::Create({island});
    auto* sc =
        new Scenario{ship::ShipParams{},
                     ship::Environment::WithCurrentToward(1.0, -110 * std::numbers::pi / 180),
                     *std::move(obs),
                     {},
                     {}};
    sc->env.wind_speed_mps = 10;
    sc->env.wind_direction_from_rad = -110 * std::numbers::pi / 180;
    for (int i = 0; i < 16; ++i) {
      sc->starts.push_back(ship::ShipState::At(-150 + 20 * i, 40.0 * (i % 4), 0.3, 2.0));
    }
    for (int i = 0; i < 64; ++i) sc->ttgs.push_back(i % 2 == 0 ? 30.0 * (i % 22) : 7.3 * i);
    return sc;
  }();
  return *s;
}

void BM_TimeToGrounding(benchmark::State& state) {
  const Scenario& sc = GetScenario();
  auto sim = risk::TimeToGroundingSimulator::Create(sc.ship);
  size_t i = 0;
  int steps = 0, grounded = 0;
  for (auto _ : state) {
    const risk::TtgResult r = sim->Run(sc.starts[i++ & 15], sc.env, sc.obstacles);
    steps += r.steps;
    grounded += r.grounded;
    benchmark::DoNotOptimize(r);
  }
  state.counters["steps/run"] = benchmark::Counter(steps, benchmark::Counter::kAvgIterations);
  state.counters["grounded"] = benchmark::Counter(grounded, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_TimeToGrounding);

void BM_TimeToGrounding_Naive(benchmark::State& state) {
  const Scenario& sc = GetScenario();
  size_t i = 0;
  int steps = 0;
  for (auto _ : state) {
    const risk::TtgResult r =
        NaiveTimeToGrounding(sc.ship, sc.starts[i++ & 15], sc.env, sc.obstacles, 600, 30);
    steps += r.steps;
    benchmark::DoNotOptimize(r);
  }
  state.counters["steps/run"] = benchmark::Counter(steps, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_TimeToGrounding_Naive);

// P(G | mode) for all three modes at one TTG.
void BM_GroundingProbability(benchmark::State& state) {
  const Scenario& sc = GetScenario();
  auto model = risk::DriftingGroundingModel::Create();
  size_t i = 0;
  for (auto _ : state) benchmark::DoNotOptimize(model->GroundingProbabilities(sc.ttgs[i++ & 63]));
}
BENCHMARK(BM_GroundingProbability);

void BM_GroundingProbabilityExact(benchmark::State& state) {
  const Scenario& sc = GetScenario();
  auto model = risk::DriftingGroundingModel::Create();
  size_t i = 0;
  for (auto _ : state) {
    const double t = sc.ttgs[i++ & 63];
    for (MsoMode m : ship::kAllMsoModes)
      benchmark::DoNotOptimize(model->GroundingProbabilityExact(m, t));
  }
}
BENCHMARK(BM_GroundingProbabilityExact);

void BM_GroundingProbability_Naive(benchmark::State& state) {
  const Scenario& sc = GetScenario();
  const risk::DriftingGroundingParams params;
  size_t i = 0;
  for (auto _ : state) {
    const double t = sc.ttgs[i++ & 63];
    for (MsoMode m : ship::kAllMsoModes)
      benchmark::DoNotOptimize(NaiveGroundingProbability(params, m, t));
  }
}
BENCHMARK(BM_GroundingProbability_Naive);

// One particle's risk: TTG + three mode probabilities.
void BM_PointRisk(benchmark::State& state) {
  const Scenario& sc = GetScenario();
  auto eval = risk::GroundingRiskEvaluator::Create(sc.ship);
  size_t i = 0;
  for (auto _ : state)
    benchmark::DoNotOptimize(eval->Evaluate(sc.starts[i++ & 15], sc.env, sc.obstacles));
}
BENCHMARK(BM_PointRisk);

void BM_PointRisk_Naive(benchmark::State& state) {
  const Scenario& sc = GetScenario();
  const risk::DriftingGroundingParams params;
  size_t i = 0;
  for (auto _ : state) {
    const risk::TtgResult r =
        NaiveTimeToGrounding(sc.ship, sc.starts[i++ & 15], sc.env, sc.obstacles, 600, 30);
    for (MsoMode m : ship::kAllMsoModes)
      benchmark::DoNotOptimize(NaiveGroundingProbability(params, m, r.ttg_s));
  }
}
BENCHMARK(BM_PointRisk_Naive);

// Collects per-benchmark times to print naive/fast ratios at the end.
class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& r : runs) {
      // Plain runs, or the median when --benchmark_repetitions is used.
      if (r.aggregate_name.empty() || r.aggregate_name == "median") {
        times_[r.run_name.function_name] = r.GetAdjustedCPUTime();
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }
  void PrintRatios() const {
    const std::pair<const char*, const char*> pairs[] = {
        {"BM_TimeToGrounding_Naive", "BM_TimeToGrounding"},
        {"BM_GroundingProbability_Naive", "BM_GroundingProbability"},
        {"BM_GroundingProbability_Naive", "BM_GroundingProbabilityExact"},
        {"BM_PointRisk_Naive", "BM_PointRisk"}};
    std::printf("\nspeed-up (naive / library CPU time, same inputs):\n");
    for (const auto& [slow, fast] : pairs) {
      auto s = times_.find(slow), f = times_.find(fast);
      if (s == times_.end() || f == times_.end() || f->second <= 0) continue;
      std::printf("  %-30s / %-30s = %7.1fx\n", slow, fast, s->second / f->second);
    }
  }

 private:
  std::map<std::string, double> times_;
};

// The baseline must compute the same numbers, or the ratio means nothing.
bool SelfCheck() {
  const Scenario& sc = GetScenario();
  auto sim = risk::TimeToGroundingSimulator::Create(sc.ship);
  auto model = risk::DriftingGroundingModel::Create();
  bool ok = true;
  for (const ship::ShipState& s : sc.starts) {
    const risk::TtgResult a = sim->Run(s, sc.env, sc.obstacles);
    const risk::TtgResult b = NaiveTimeToGrounding(sc.ship, s, sc.env, sc.obstacles, 600, 30);
    if (a.ttg_s != b.ttg_s || a.grounded != b.grounded) {
      std::printf("  TTG mismatch: %g/%d vs naive %g/%d\n", a.ttg_s, a.grounded, b.ttg_s,
                  b.grounded);
      ok = false;
    }
    for (MsoMode m : ship::kAllMsoModes) {
      const double p = model->GroundingProbability(m, a.ttg_s);
      const double q = NaiveGroundingProbability(risk::DriftingGroundingParams{}, m, a.ttg_s);
      // The baseline's 1 - (1 - sum) form cancels: absolute tolerance.
      if (std::abs(p - q) > 1e-14) {
        std::printf("  P mismatch at TTG %g: %.17g vs naive %.17g\n", a.ttg_s, p, q);
        ok = false;
      }
    }
  }
  std::printf("self-check (library == naive baseline on all 16 start points): %s\n",
              ok ? "ok" : "MISMATCH");
  return ok;
}

}  // namespace
}  // namespace seaplan::bench

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  if (!seaplan::bench::SelfCheck()) return 2;
  seaplan::bench::RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.PrintRatios();
  benchmark::Shutdown();
  return 0;
}
