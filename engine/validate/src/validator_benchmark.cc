// Validation speed: the planner validates every plan it returns, so a
// 100-step plan must validate in well under a millisecond.
//
//   cmake --build build --target seaplan-bench-validate
//   build/bin/seaplan-bench-validate
//
// Tasks: a synthetic chain (100 sequential moves over 101 locations, each
// reading and decreasing fuel, with an invariant) inside a task with 20,000
// unrelated ground actions, so that the cost of mapping steps to actions
// shows; a 100-step plan with 50 pairs of simultaneous non-interfering steps
// (mutex checks on every pair); and the fjord case A repaired plan through the
// real parser and grounder.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "seaplan/task/grounder.h"
#include "seaplan/validate/plan.h"
#include "seaplan/validate/validator.h"
#include "task_builder_test_util.h"

namespace seaplan::validate {
namespace {

using testing::TaskBuilder;

constexpr int kSteps = 100;
constexpr int kDistractors = 20000;

std::string Loc(int i) {
  return "l" + std::to_string(i);
}

// Sequential moves l0 -> l1 -> ... -> l100.
std::shared_ptr<const task::GroundTask> ChainTask() {
  TaskBuilder b;
  b.Var("(fuel)", 1000);
  b.Init("(at l0)");
  for (int i = 0; i < kSteps; ++i) {
    auto a = TaskBuilder::Durative("(move " + Loc(i) + " " + Loc(i + 1) + ")", 10);
    a.at_start.positive = {b.Fact("(at " + Loc(i) + ")")};
    a.at_start.numeric = {
        {b.VarExpr("(fuel)"), task::Comparator::kGreaterEqual, task::NumericExpr::Constant(1)}};
    a.over_all.positive = {b.Fact("(open " + Loc(i) + ")")};
    a.start_effects.del = {b.Fact("(at " + Loc(i) + ")")};
    a.start_effects.numeric = {
        {b.Var("(fuel)"), task::AssignOp::kDecrease, task::NumericExpr::Constant(1)}};
    a.end_effects.add = {b.Fact("(at " + Loc(i + 1) + ")")};
    b.Init("(open " + Loc(i) + ")");
    b.Add(a);
  }
  for (int i = 0; i < kDistractors; ++i) {
    auto a = TaskBuilder::Durative("(survey z" + std::to_string(i) + ")", 5);
    a.end_effects.add = {b.Fact("(surveyed z" + std::to_string(i % 100) + ")")};
    b.Add(a);
  }
  b.Goal("(at " + Loc(kSteps) + ")");
  return std::make_shared<const task::GroundTask>(std::move(b.task()));
}

Plan ChainPlan() {
  Plan plan;
  double t = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    plan.steps.push_back({t, "move", {Loc(i), Loc(i + 1)}, 10.0, i + 1});
    t += 10.001;
  }
  return plan;
}

// 50 rounds of two simultaneous, independent steps.
std::shared_ptr<const task::GroundTask> PairsTask() {
  TaskBuilder b;
  for (int i = 0; i < kSteps; ++i) {
    auto a = TaskBuilder::Durative("(work w" + std::to_string(i) + ")", 10);
    a.at_start.positive = {b.Fact("(ready w" + std::to_string(i) + ")")};
    a.over_all.positive = {b.Fact("(power)")};
    a.start_effects.del = {b.Fact("(ready w" + std::to_string(i) + ")")};
    a.end_effects.add = {b.Fact("(done w" + std::to_string(i) + ")")};
    b.Init("(ready w" + std::to_string(i) + ")");
    b.Goal("(done w" + std::to_string(i) + ")");
    b.Add(a);
  }
  b.Init("(power)");
  return std::make_shared<const task::GroundTask>(std::move(b.task()));
}

Plan PairsPlan() {
  Plan plan;
  for (int i = 0; i < kSteps; ++i) {
    const int pair = i / 2;  // two steps start together
    plan.steps.push_back({pair * 10.001, "work", {"w" + std::to_string(i)}, 10.0, i + 1});
  }
  return plan;
}

void BM_ValidatorChain100(benchmark::State& state) {
  const auto validator = *Validator::Create(ChainTask());
  const Plan plan = ChainPlan();
  if (!validator.Validate(plan).valid) state.SkipWithError("chain plan should be valid");
  for (auto _ : state) benchmark::DoNotOptimize(validator.Validate(plan));
  state.SetItemsProcessed(state.iterations() * kSteps);
}
BENCHMARK(BM_ValidatorChain100)->Unit(benchmark::kMicrosecond);

void BM_ValidatePlanOneShotChain100(benchmark::State& state) {
  const auto task = ChainTask();
  const Plan plan = ChainPlan();
  for (auto _ : state) benchmark::DoNotOptimize(ValidatePlan(*task, plan));
  state.SetItemsProcessed(state.iterations() * kSteps);
}
BENCHMARK(BM_ValidatePlanOneShotChain100)->Unit(benchmark::kMicrosecond);

void BM_ValidatorSimultaneousPairs100(benchmark::State& state) {
  const auto validator = *Validator::Create(PairsTask());
  const Plan plan = PairsPlan();
  if (!validator.Validate(plan).valid) state.SkipWithError("pairs plan should be valid");
  for (auto _ : state) benchmark::DoNotOptimize(validator.Validate(plan));
  state.SetItemsProcessed(state.iterations() * kSteps);
}
BENCHMARK(BM_ValidatorSimultaneousPairs100)->Unit(benchmark::kMicrosecond);

std::string ReadFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

void BM_ValidatorFjordCaseA(benchmark::State& state) {
  const char* env = std::getenv("SEAPLAN_SOURCE_DIR");
  const std::string dir =
      std::string(env != nullptr ? env : SEAPLAN_SOURCE_DIR_DEFAULT) + "/examples/fjord/";
  const auto loaded = task::LoadTask(ReadFile(dir + "domain.pddl"), ReadFile(dir + "case-a.pddl"));
  const auto plan = ParsePlan(ReadFile(dir + "case-a-repaired.plan"));
  if (!loaded.ok() || !plan.ok()) {
    state.SkipWithError("cannot load examples/fjord (set SEAPLAN_SOURCE_DIR)");
    return;
  }
  const auto validator = *Validator::Create(loaded.task);
  if (!validator.Validate(*plan).valid) state.SkipWithError("case A repaired plan should be valid");
  for (auto _ : state) benchmark::DoNotOptimize(validator.Validate(*plan));
}
BENCHMARK(BM_ValidatorFjordCaseA)->Unit(benchmark::kMicrosecond);

void BM_ParseAndFormatPlan100(benchmark::State& state) {
  const std::string text = FormatPlan(ChainPlan());
  for (auto _ : state) {
    auto plan = ParsePlan(text);
    benchmark::DoNotOptimize(FormatPlan(*plan));
  }
}
BENCHMARK(BM_ParseAndFormatPlan100)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace seaplan::validate

BENCHMARK_MAIN();
