// End-to-end tests of `seaplan`: exit codes (0 success, 1 no plan / invalid,
// 2 bad input or usage, 3 server unreachable), IPC plan output, JSON output,
// and the same commands against a running seaplan-server.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "seaplan/testing/child_process.h"
#include "seaplan/testing/large_pddl.h"
#include "seaplan/testing/shared_data.h"
#include "seaplan/testing/test_token.h"

namespace seaplan::testing {
namespace {

namespace fs = std::filesystem;

struct CommandResult {
  int exit_code = -1;
  std::string out;
  std::string err;
};

fs::path ScratchDir() {
  auto dir = fs::temp_directory_path() / ("seaplan-cli-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

std::string Quote(const std::string& arg) {
  std::string quoted = "'";
  for (char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// Runs `binary` (default build/bin/seaplan) with `args`; stdout and stderr
// captured separately. `address_space_kb` > 0: under `ulimit -v` (as
// benchmark runners limit a planner).
CommandResult RunSeaplan(const std::vector<std::string>& args,
                         const fs::path& binary = BinDir() / "seaplan", int address_space_kb = 0) {
  static int counter = 0;
  const auto dir = ScratchDir();
  const auto out = dir / ("out" + std::to_string(counter));
  const auto err = dir / ("err" + std::to_string(counter++));
  std::string command = Quote(binary.string());
  for (const auto& arg : args) command += " " + Quote(arg);
  if (address_space_kb > 0) {
    command =
        "sh -c " + Quote("ulimit -v " + std::to_string(address_space_kb) + " && exec " + command);
  }
  command += " >" + Quote(out.string()) + " 2>" + Quote(err.string());
  const int status = std::system(command.c_str());
  CommandResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = ReadFile(out);
  result.err = ReadFile(err);
  return result;
}

std::string Example(const std::string& name) {
  return (SourceDir() / "examples/fjord" / name).string();
}

std::string WriteScratch(const std::string& name, const std::string& content) {
  const auto path = ScratchDir() / name;
  std::ofstream(path) << content;
  return path.string();
}

TEST(CliInProcessTest, PlanPrintsAValidIpcPlan) {
  const auto plan_file = (ScratchDir() / "case-a.plan").string();
  auto plan = RunSeaplan({"plan", Example("domain.pddl"), Example("case-a.pddl"), "--time-limit",
                          "5", "-o", plan_file});
  ASSERT_EQ(plan.exit_code, 0) << plan.err;
  EXPECT_NE(plan.out.find("(move-ship ship0 port-a port-b)"), std::string::npos) << plan.out;
  EXPECT_NE(plan.out.find("; status: SOLVED"), std::string::npos) << plan.out;
  // The written plan is accepted by the validator.
  auto check = RunSeaplan({"validate", Example("domain.pddl"), Example("case-a.pddl"), plan_file});
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  EXPECT_NE(check.out.find("Plan valid"), std::string::npos);
}

// A task whose goal holds at the start has the empty plan: -o writes it,
// over whatever the file held, and the validator accepts it.
TEST(CliInProcessTest, AnEmptyPlanIsWrittenOverAnOldFile) {
  const auto plan_file = WriteScratch("empty.plan", "0.000: (move-ship ship0 port-a port-b) [1]\n");
  const auto problem = WriteScratch("at-goal.pddl", R"((define (problem at-goal) (:domain fjord)
  (:objects ship0 - ship port-a - port)
  (:init (at ship0 port-a))
  (:goal (at ship0 port-a))))");
  auto plan = RunSeaplan({"plan", Example("domain.pddl"), problem, "-o", plan_file});
  ASSERT_EQ(plan.exit_code, 0) << plan.out << plan.err;
  EXPECT_EQ(ReadFile(plan_file).find("move-ship"), std::string::npos) << ReadFile(plan_file);
  auto check = RunSeaplan({"validate", Example("domain.pddl"), problem, plan_file});
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
}

// A plan file that is not a regular file (a symlink here; /dev/stdout, a
// pipe) is written through, not replaced by a new file renamed over it:
// renamed over, `-o /dev/null` once turned /dev/null into a regular file.
TEST(CliInProcessTest, APlanFileThatIsASymlinkIsWrittenThrough) {
  const auto target = WriteScratch("through-target.plan", "old content\n");
  const auto link = ScratchDir() / "through-link.plan";
  std::filesystem::remove(link);
  std::filesystem::create_symlink(target, link);
  auto plan = RunSeaplan({"plan", Example("domain.pddl"), Example("case-a.pddl"), "--no-anytime",
                          "-o", link.string()});
  ASSERT_EQ(plan.exit_code, 0) << plan.out << plan.err;
  EXPECT_TRUE(std::filesystem::is_symlink(link));
  EXPECT_NE(ReadFile(target).find("move-ship"), std::string::npos) << ReadFile(target);
  auto check = RunSeaplan({"validate", Example("domain.pddl"), Example("case-a.pddl"), target});
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
}

// --max-expansions reaches the planner: 5 expansions find no plan for case
// A (the search needs more), and the status names the limit.
TEST(CliInProcessTest, MaxExpansionsLimitsTheSearch) {
  auto few = RunSeaplan({"plan", Example("domain.pddl"), Example("case-a.pddl"), "--time-limit",
                         "60", "--max-expansions", "5"});
  EXPECT_EQ(few.exit_code, 1) << few.out << few.err;
  EXPECT_NE(few.out.find("expansion limit (5) reached before a plan was found"), std::string::npos)
      << few.out;
  EXPECT_NE(few.out.find("search: 5 expanded"), std::string::npos) << few.out;
  auto bad = RunSeaplan(
      {"plan", Example("domain.pddl"), Example("case-a.pddl"), "--max-expansions", "-3"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("expected a whole number >= 0, got -3"), std::string::npos) << bad.err;
}

// --cpu-limit reaches the planner: 0.2 s of CPU time do not solve the
// 22-bit toggle task, and the status names the limit; a negative limit is
// a usage error.
TEST(CliInProcessTest, CpuLimitLimitsTheSearch) {
  const auto testdata = SourceDir() / "engine/search/testdata";
  auto few = RunSeaplan({"plan", (testdata / "toggle-domain.pddl").string(),
                         (testdata / "toggle-22.pddl").string(), "--time-limit", "60",
                         "--cpu-limit", "0.2"});
  EXPECT_EQ(few.exit_code, 1) << few.out << few.err;
  EXPECT_NE(few.out.find("CPU time limit (0.2 s) reached before a plan was found"),
            std::string::npos)
      << few.out;
  auto bad =
      RunSeaplan({"plan", Example("domain.pddl"), Example("case-a.pddl"), "--cpu-limit", "-3"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--cpu-limit"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("expected a number of seconds >= 0, got -3"), std::string::npos)
      << bad.err;
  auto word =
      RunSeaplan({"plan", Example("domain.pddl"), Example("case-a.pddl"), "--cpu-limit", "ten"});
  EXPECT_EQ(word.exit_code, 2);
  EXPECT_NE(word.err.find("got ten"), std::string::npos) << word.err;
}

// Under an address-space limit (ulimit -v, as benchmark runners set it) an
// allocation fails before the memory limit's poll sees it coming; the plans
// found until then are kept: the anytime search on this mission runs out of
// 200 MB within a few seconds, long after its first plan.
TEST(CliInProcessTest, AnAddressSpaceLimitKeepsThePlanFoundSoFar) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizers reserve more address space than the limit";
#endif
  const auto mission = SourceDir() / "engine/search/testdata/fjord-s3-p8-c8-seed8.pddl";
  const auto plan = ScratchDir() / "address-space.plan";
  const CommandResult run =
      RunSeaplan({"plan", Example("domain.pddl"), mission.string(), "--time-limit", "300",
                  "--memory-limit", "4096", "-o", plan.string()},
                 BinDir() / "seaplan", 200000);
  const std::string printed = run.out + run.err;
  ASSERT_NE(run.exit_code, -1) << printed;  // exited, not killed
  EXPECT_EQ(run.exit_code, 0) << printed;
  EXPECT_NE(printed.find("memory ran out (an allocation failed) after"), std::string::npos)
      << printed;
  auto valid = RunSeaplan({"validate", Example("domain.pddl"), mission.string(), plan.string()});
  EXPECT_EQ(valid.exit_code, 0) << valid.out << valid.err;
}

// A task whose grounding cannot fit (200^3 ground actions under 400 MB of
// address space) is a result, MEMOUT, exit 1, not an abort: grounding runs
// on the planning worker thread, where nothing else would catch it.
TEST(CliInProcessTest, AGroundingTooLargeForTheAddressSpaceIsAMemout) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  GTEST_SKIP() << "the sanitizers reserve more address space than the limit";
#endif
  const PddlTexts task = CubicGroundingTask(200);  // 8 million ground actions
  const std::string domain = WriteScratch("huge-domain.pddl", task.domain);
  const std::string problem = WriteScratch("huge-problem.pddl", task.problem);
  const CommandResult run =
      RunSeaplan({"plan", domain, problem, "--time-limit", "120"}, BinDir() / "seaplan", 400000);
  const std::string printed = run.out + run.err;
  ASSERT_NE(run.exit_code, -1) << printed;  // exited, not killed
  EXPECT_EQ(run.exit_code, 1) << printed;
  EXPECT_NE(printed.find("; status: MEMOUT"), std::string::npos) << printed;
  EXPECT_NE(printed.find("memory ran out (an allocation failed) while grounding"),
            std::string::npos)
      << printed;
}

// With -o each improved plan is in the file as soon as it is found: a
// process killed from outside (here SIGKILL after 2 s; the first plan of
// this mission comes within 0.05 s, the anytime search runs to its limit)
// leaves a whole, valid plan.
TEST(CliInProcessTest, AKilledPlannerLeavesItsBestPlanSoFar) {
  const auto mission = SourceDir() / "engine/search/testdata/fjord-s3-p8-c8-seed8.pddl";
  const auto plan = ScratchDir() / "killed.plan";
  fs::remove(plan);
  const std::string command = "timeout -s KILL 2 " + Quote((BinDir() / "seaplan").string()) +
                              " plan " + Quote(Example("domain.pddl")) + " " +
                              Quote(mission.string()) + " --time-limit 300 -o " +
                              Quote(plan.string()) + " >/dev/null 2>&1";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 137) << "not killed: the test needs a longer search";
  ASSERT_TRUE(fs::exists(plan));
  auto valid = RunSeaplan({"validate", Example("domain.pddl"), mission.string(), plan.string()});
  EXPECT_EQ(valid.exit_code, 0) << valid.out << valid.err;
}

// --switch-after is accepted (0: the newest-first search alone, which
// solves case A; that the share reaches the planner's options is checked
// in server/core's adapter test); a share past 1 is a usage error.
TEST(CliInProcessTest, SwitchAfterIsAShareOfTheBudget) {
  auto alone = RunSeaplan({"plan", Example("domain.pddl"), Example("case-a.pddl"), "--switch-after",
                           "0", "--no-anytime"});
  EXPECT_EQ(alone.exit_code, 0) << alone.out << alone.err;
  EXPECT_NE(alone.out.find("; makespan:"), std::string::npos) << alone.out;
  auto bad =
      RunSeaplan({"plan", Example("domain.pddl"), Example("case-a.pddl"), "--switch-after", "1.5"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--switch-after"), std::string::npos) << bad.err;
}

// --seed-rounds and --suffix-searches reach the planner: with 0 none runs
// and none is reported; by default they run and the plan's statistics say
// how many; a negative share is a usage error.
TEST(CliInProcessTest, SeedRoundsAndSuffixSearchesAreReportedAndCanBeTurnedOff) {
  auto both = RunSeaplan({"plan", Example("domain.pddl"), Example("case-a.pddl"), "--no-anytime"});
  EXPECT_EQ(both.exit_code, 0) << both.out << both.err;
  for (const auto& [flag, line] : {std::pair{"--seed-rounds", "; rounds with other seeds"},
                                   std::pair{"--suffix-searches", "; suffix searches"}}) {
    SCOPED_TRACE(flag);
    EXPECT_NE(both.out.find(std::string(line) + ": "), std::string::npos) << both.out;
    auto none = RunSeaplan(
        {"plan", Example("domain.pddl"), Example("case-a.pddl"), "--no-anytime", flag, "0"});
    EXPECT_EQ(none.exit_code, 0) << none.out << none.err;
    EXPECT_NE(none.out.find("; makespan:"), std::string::npos) << none.out;
    EXPECT_EQ(none.out.find(line), std::string::npos) << none.out;
    auto bad = RunSeaplan({"plan", Example("domain.pddl"), Example("case-a.pddl"), flag, "-1"});
    EXPECT_EQ(bad.exit_code, 2);
    EXPECT_NE(bad.err.find(std::string(flag) + ": expected a number >= 0, got -1"),
              std::string::npos)
        << bad.err;
  }
}

// --no-type-based is accepted and plans. Case A's first plan comes before
// the type-based list's first turn, so the search is the same with it
// (what the list changes is tested in engine/search's planner_test).
TEST(CliInProcessTest, NoTypeBasedPlans) {
  const auto searched = [&](bool type_based) {
    std::vector<std::string> args = {"plan",         Example("domain.pddl"), Example("case-a.pddl"),
                                     "--no-anytime", "--time-limit",         "60"};
    if (!type_based) args.push_back("--no-type-based");
    auto run = RunSeaplan(args);
    EXPECT_EQ(run.exit_code, 0) << run.out << run.err;
    const auto at = run.out.find("; search: ");
    EXPECT_NE(at, std::string::npos) << run.out;
    return at == std::string::npos ? std::string() : run.out.substr(at, run.out.find(',', at) - at);
  };
  EXPECT_EQ(searched(false), searched(true));
}

// The landmark count is on by default (and with --landmarks): the planner
// finds the task's landmarks (the debug log says how many); --no-landmarks
// reaches the planner, which then does not look for them.
TEST(CliInProcessTest, NoLandmarksFlagTurnsOffTheLandmarkCount) {
  const auto run = [&](const char* flag) {
    std::vector<std::string> args = {
        "--log-level",          "debug",        "plan",         Example("domain.pddl"),
        Example("case-a.pddl"), "--no-anytime", "--time-limit", "60"};
    if (flag != nullptr) args.push_back(flag);
    return RunSeaplan(args);
  };
  for (const char* flag : {static_cast<const char*>(nullptr), "--landmarks"}) {
    SCOPED_TRACE(flag == nullptr ? "default" : flag);
    const auto with = run(flag);
    EXPECT_EQ(with.exit_code, 0) << with.out << with.err;
    EXPECT_NE(with.err.find(" landmarks, "), std::string::npos) << with.err;
    EXPECT_EQ(with.err.find("planner: 0 landmarks"), std::string::npos) << with.err;
  }
  const auto without = run("--no-landmarks");
  EXPECT_EQ(without.exit_code, 0) << without.out << without.err;
  EXPECT_EQ(without.err.find(" landmarks, "), std::string::npos) << without.err;
}

// The symmetry reduction is on by default and --no-symmetry turns it off:
// on a task whose goal treats two crates alike, the statistics name the
// interchangeable objects only without the flag.
TEST(CliInProcessTest, NoSymmetryFlagTurnsOffTheSymmetryReduction) {
  const auto domain = WriteScratch("crates-domain.pddl", R"(
(define (domain crates)
  (:requirements :typing :durative-actions)
  (:types crate slot)
  (:predicates (on ?c - crate ?s - slot) (holding ?c - crate) (free) (done ?c - crate))
  (:durative-action lift
    :parameters (?c - crate ?s - slot)
    :duration (= ?duration 2)
    :condition (and (at start (on ?c ?s)) (at start (free)))
    :effect (and (at start (not (on ?c ?s))) (at start (not (free))) (at end (holding ?c))))
  (:durative-action drop
    :parameters (?c - crate ?s - slot)
    :duration (= ?duration 1)
    :condition (at start (holding ?c))
    :effect (and (at start (not (holding ?c))) (at end (free)) (at end (on ?c ?s))
                 (at end (done ?c)))))
)");
  const auto problem = WriteScratch("crates-problem.pddl", R"(
(define (problem two)
  (:domain crates)
  (:objects a b - crate s1 s2 - slot)
  (:init (on a s1) (on b s2) (free))
  (:goal (and (done a) (done b))))
)");
  const auto with = RunSeaplan({"plan", domain, problem, "--no-anytime", "--time-limit", "30"});
  EXPECT_EQ(with.exit_code, 0) << with.out << with.err;
  EXPECT_NE(with.out.find("; symmetry: 4 interchangeable objects in 2 classes"), std::string::npos)
      << with.out;
  const auto without =
      RunSeaplan({"plan", domain, problem, "--no-anytime", "--time-limit", "30", "--no-symmetry"});
  EXPECT_EQ(without.exit_code, 0) << without.out << without.err;
  EXPECT_EQ(without.out.find("; symmetry:"), std::string::npos) << without.out;
}

// Eager ends are on by default and --no-eager-ends turns them off: on case
// A, where a ship's arrival is such an end, the output has the line that
// counts the states they cut only when the flag is not given.
TEST(CliInProcessTest, NoEagerEndsFlagTurnsOffEagerEnds) {
  const auto domain = Example("domain.pddl");
  const auto problem = Example("case-a.pddl");
  const auto with = RunSeaplan({"plan", domain, problem, "--no-anytime", "--time-limit", "30"});
  EXPECT_EQ(with.exit_code, 0) << with.out << with.err;
  EXPECT_NE(with.out.find("; eager ends: "), std::string::npos) << with.out;
  const auto without = RunSeaplan(
      {"plan", domain, problem, "--no-anytime", "--time-limit", "30", "--no-eager-ends"});
  EXPECT_EQ(without.exit_code, 0) << without.out << without.err;
  EXPECT_EQ(without.out.find("; eager ends:"), std::string::npos) << without.out;
}

// Under a deadline the output says how often the first-plan searches began
// again with another seed (the toggle task has no plan: the run ends at
// its expansion limit, the first search past its 5,000 steps).
TEST(CliInProcessTest, PlanOutputCountsRestartsUnderDeadlines) {
  const auto testdata = SourceDir() / "engine/search/testdata";
  const auto result = RunSeaplan({"plan", (testdata / "toggle-deadline-domain.pddl").string(),
                                  (testdata / "toggle-deadline-22.pddl").string(), "--no-anytime",
                                  "--max-expansions", "8000", "--switch-after", "1"});
  EXPECT_NE(result.out.find("; restarts: the first-plan searches began again 1 time with "
                            "another seed (deadlines)"),
            std::string::npos)
      << result.out << result.err;
}

TEST(CliInProcessTest, InvalidPlanExitsOneAndNamesTheFailure) {
  auto result = RunSeaplan(
      {"validate", Example("domain.pddl"), Example("case-a.pddl"), Example("case-a-paper.plan")});
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.out.find("Plan invalid"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("first failure"), std::string::npos) << result.out;
}

TEST(CliInProcessTest, MalformedPddlExitsTwoWithLocation) {
  const auto domain =
      WriteScratch("bad-domain.pddl",
                   "(define (domain d)\n  (:requirements :strips)\n  (:predicates (p))\n"
                   "  (:action a :parameters () :precondition (q) :effect (p)))\n");
  const auto problem =
      WriteScratch("bad-problem.pddl", "(define (problem p) (:domain d) (:init) (:goal (p)))\n");
  auto result = RunSeaplan({"plan", domain, problem, "--time-limit", "1"});
  EXPECT_EQ(result.exit_code, 2) << result.out << result.err;
  // The undeclared predicate q on line 4 is named with its position.
  EXPECT_NE(result.err.find("domain:4:"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find('q'), std::string::npos) << result.err;
}

TEST(CliInProcessTest, MissingFileAndUsageErrorsExitTwo) {
  EXPECT_EQ(RunSeaplan({"plan", "/nonexistent/domain.pddl", Example("case-a.pddl")}).exit_code, 2);
  EXPECT_EQ(RunSeaplan({"plan"}).exit_code, 2);
  EXPECT_EQ(RunSeaplan({"no-such-command"}).exit_code, 2);
  EXPECT_EQ(
      RunSeaplan({"route", "--from", "95,10", "--to", "63,10", "--chart-file", "x"}).exit_code, 2);
}

TEST(CliInProcessTest, UnsolvableProblemExitsOne) {
  const auto domain =
      WriteScratch("unsolvable-domain.pddl",
                   "(define (domain u)\n  (:requirements :durative-actions)\n"
                   "  (:predicates (p) (q))\n"
                   "  (:durative-action a :parameters () :duration (= ?duration 1)\n"
                   "    :condition (at start (q)) :effect (at end (p))))\n");
  const auto problem = WriteScratch("unsolvable-problem.pddl",
                                    "(define (problem up) (:domain u) (:init) (:goal (p)))\n");
  auto result = RunSeaplan({"plan", domain, problem, "--time-limit", "5"});
  EXPECT_EQ(result.exit_code, 1) << result.out << result.err;
  EXPECT_EQ(result.out.find("(a)"), std::string::npos);
}

TEST(CliInProcessTest, JsonOutputIsTheApiMessage) {
  auto result = RunSeaplan({"--json", "plan", Example("domain.pddl"), Example("case-a.pddl"),
                            "--time-limit", "2", "--no-anytime"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.out.rfind('{', 0), 0u) << result.out;
  EXPECT_NE(result.out.find("\"status\":\"SOLVED_"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("\"makespanS\""), std::string::npos) << result.out;
}

std::string Chart() {
  return (SourceDir() / "examples/scenarios/fjord-entrance.geojson").string();
}

// Port B to port C of the fjord scenario: the island lies between them.
const std::vector<std::string> kRouteArgs = {
    "--from", "63.445835,10.346208", "--to", "63.442244,10.386389", "--wind-speed",
    "10",     "--wind-from",         "250"};

TEST(CliInProcessTest, RouteWritesAlternativesAndGeoJson) {
  const auto geojson = (ScratchDir() / "route.geojson").string();
  std::vector<std::string> args = {"route", "--chart-file", Chart(), "--min-depth",
                                   "5",     "--geojson",    geojson};
  args.insert(args.end(), kRouteArgs.begin(), kRouteArgs.end());
  auto result = RunSeaplan(args);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("alternative(s); chosen"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("MSO mode schedule"), std::string::npos) << result.out;
  const std::string map = ReadFile(geojson);
  EXPECT_NE(map.find("\"kind\":\"obstacle\""), std::string::npos);
  EXPECT_NE(map.find("\"kind\":\"route\""), std::string::npos);
  EXPECT_NE(map.find("(chosen)"), std::string::npos);
}

TEST(CliInProcessTest, RouteFromInsideLandIsBadInput) {
  // 63.43,10.40 lies on the south shore polygon of the scenario chart.
  auto result = RunSeaplan(
      {"route", "--chart-file", Chart(), "--from", "63.43,10.40", "--to", "63.442244,10.386389"});
  EXPECT_EQ(result.exit_code, 2) << result.out << result.err;
  // In the user's latitude/longitude, with where the water is.
  EXPECT_NE(result.err.find("start 63.43000,10.40000"), std::string::npos) << result.err;
  EXPECT_NE(result.err.find("nearest navigable point is"), std::string::npos) << result.err;
}

TEST(CliInProcessTest, RouteTakesAChartFolderByPath) {
  // A folder of chart files (as a shapefile set or a FileGDB comes): every
  // file in it is sent, named by its path inside the folder.
  const fs::path folder = ScratchDir() / "chart-folder";
  fs::create_directories(folder / "layers");
  fs::copy_file(Chart(), folder / "layers" / fs::path(Chart()).filename(),
                fs::copy_options::overwrite_existing);
  std::vector<std::string> args = {"route", "--chart-file", folder.string() + "/", "--min-depth",
                                   "5"};
  args.insert(args.end(), kRouteArgs.begin(), kRouteArgs.end());
  auto result = RunSeaplan(args);
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_NE(result.out.find("alternative(s); chosen"), std::string::npos) << result.out;
}

// A chart of an L-shaped channel `width_m` wide at 63 N 10 E (GeoJSON, land
// on both sides): east along the channel, then north at the bend.
std::string LChannelChart(double width_m) {
  const double lat0 = 63.0, lon0 = 10.0, m_per_deg_lat = 111320.0;
  const double m_per_deg_lon = m_per_deg_lat * std::cos(lat0 * M_PI / 180.0);
  auto rect = [&](double x0, double y0, double x1, double y1) {
    std::string ring;
    for (auto [x, y] : {std::pair{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}, {x0, y0}}) {
      ring += (ring.empty() ? "[" : ",[") + std::to_string(lon0 + x / m_per_deg_lon) + "," +
              std::to_string(lat0 + y / m_per_deg_lat) + "]";
    }
    return "{\"type\":\"Feature\",\"properties\":{\"name\":\"land\"},\"geometry\":"
           "{\"type\":\"Polygon\",\"coordinates\":[[" +
           ring + "]]}}";
  };
  const double h = width_m / 2.0;
  return "{\"type\":\"FeatureCollection\",\"features\":[" + rect(-2000, h, -h, 2000) + "," +
         rect(-2000, -2000, 2000, -h) + "," + rect(h, -h, 2000, 2000) + "]}";
}

TEST(CliInProcessTest, RouteWarnsOfATurnTheHullCannotSail) {
  // A 90 deg bend in a channel 80 m wide: 50 m of it clear of the charted
  // land's 15 m growth, narrower than the turning circles the fillets are
  // tried on (450 m down to 300 m) need round the inner corner (88 m at
  // 300 m). The route is still given (Level 1 connects), with the warning
  // naming the turn and why.
  const auto chart = WriteScratch("l-channel.geojson", LChannelChart(80.0));
  // From 1.5 km west of the bend to 1.5 km north of it, on the centre line.
  const std::vector<std::string> args = {"route",
                                         "--chart-file",
                                         chart,
                                         "--min-depth",
                                         "5",
                                         "--from",
                                         "63.0,9.970320",
                                         "--to",
                                         "63.013475,10.0",
                                         "--safety-distance",
                                         "10",
                                         "--segments",
                                         "6",
                                         "--particles",
                                         "8",
                                         "--iterations",
                                         "10"};
  auto result = RunSeaplan(args);
  ASSERT_EQ(result.exit_code, 0) << result.out << result.err;
  EXPECT_NE(result.out.find("alternative(s); chosen"), std::string::npos) << result.out;
  EXPECT_NE(result.out.find("warning: the turn of "), std::string::npos) << result.out;
  EXPECT_NE(
      result.out.find("cannot be sailed on a turning circle of 300 to 450 m: the water is too "
                      "narrow for it"),
      std::string::npos)
      << result.out;
  // The same warning is in the API message (--json).
  std::vector<std::string> json_args = {"--json"};
  json_args.insert(json_args.end(), args.begin(), args.end());
  auto json = RunSeaplan(json_args);
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\"warnings\":[\"the turn of "), std::string::npos) << json.out;

  // 1000 m wide, the same bend is filleted: no warning.
  const auto wide = WriteScratch("wide-channel.geojson", LChannelChart(1000.0));
  std::vector<std::string> wide_args = args;
  wide_args[2] = wide;
  auto filleted = RunSeaplan(wide_args);
  ASSERT_EQ(filleted.exit_code, 0) << filleted.out << filleted.err;
  EXPECT_NE(filleted.out.find("alternative(s); chosen"), std::string::npos) << filleted.out;
  EXPECT_EQ(filleted.out.find("warning:"), std::string::npos) << filleted.out;
}

TEST(CliInProcessTest, MissionsNeedAServer) {
  auto result = RunSeaplan({"mission", "list"});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_NE(result.err.find("--server"), std::string::npos) << result.err;
  auto feedback = RunSeaplan({"mission", "feedback", "m-1"});
  EXPECT_EQ(feedback.exit_code, 2);
  EXPECT_NE(feedback.err.find("--server"), std::string::npos) << feedback.err;
}

// seaplan runs plan and validate itself and hands chart, route and risk to
// seaplan-charts beside it; without it those fail clearly, plan still works.
TEST(CliInProcessTest, ChartCommandsRunInSeaplanChartsBesideIt) {
  auto listed = RunSeaplan({"chart", "list"});
  EXPECT_EQ(listed.exit_code, 0) << listed.err;
  EXPECT_NE(listed.out.find("no charts"), std::string::npos) << listed.out;

  const auto alone = ScratchDir() / "alone";
  fs::create_directories(alone);
  fs::copy_file(BinDir() / "seaplan", alone / "seaplan", fs::copy_options::overwrite_existing);
  auto missing = RunSeaplan({"chart", "list"}, alone / "seaplan");
  EXPECT_EQ(missing.exit_code, 3);
  EXPECT_NE(missing.err.find("seaplan-charts"), std::string::npos) << missing.err;
  auto plan =
      RunSeaplan({"plan", Example("domain.pddl"), Example("case-a.pddl")}, alone / "seaplan");
  EXPECT_EQ(plan.exit_code, 0) << plan.err;
}

TEST(CliRemoteTest, UnreachableServerExitsThree) {
  auto result =
      RunSeaplan({"--server", "127.0.0.1:1", "--timeout", "2", "validate", Example("domain.pddl"),
                  Example("case-a.pddl"), Example("case-a-repaired.plan")});
  EXPECT_EQ(result.exit_code, 3) << result.out << result.err;
}

// A real seaplan-server on ephemeral loopback ports, killed at the end. It
// accepts the fixtures' admin token, which the `seaplan` processes the
// tests start present (SEAPLAN_TOKEN).
class ServerProcess {
 public:
  ServerProcess() {
    dir_ =
        ScratchDir() /
        ("server-" + std::to_string(std::chrono::steady_clock::now().time_since_epoch().count()));
    fs::create_directories(dir_);
    const auto port_file = dir_ / "ports";
    const std::string token_file =
        seaplan::testing::WriteTestAdminTokenFile(dir_ / "admin-token").string();
    seaplan::testing::PassTestAdminTokenToChildren();
    pid_ = fork();
    if (pid_ == 0) {
      const std::string bin = (BinDir() / "seaplan-server").string();
      const std::string data = (dir_ / "data").string();
      const std::string ports = port_file.string();
      execl(bin.c_str(), bin.c_str(), "--grpc-addr", "127.0.0.1:0", "--http-addr", "127.0.0.1:0",
            "--data-dir", data.c_str(), "--port-file", ports.c_str(), "--log-level", "warn",
            "--admin-token-file", token_file.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    const auto readiness =
        seaplan::testing::WaitUntilChildReady(pid_, std::chrono::seconds(10), [&] {
          std::ifstream in(port_file);
          std::string line;
          while (std::getline(in, line)) {
            if (line.rfind("grpc=", 0) == 0) port_ = line.substr(5);
          }
          return !port_.empty();
        });
    if (readiness == seaplan::testing::ChildReadiness::kExited) pid_ = -1;  // reaped
  }
  ~ServerProcess() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      int status = 0;
      for (int i = 0; i < 100 && waitpid(pid_, &status, WNOHANG) == 0; ++i) {
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
      }
      kill(pid_, SIGKILL);
      waitpid(pid_, &status, 0);
    }
  }
  std::string address() const { return "127.0.0.1:" + port_; }
  bool started() const { return !port_.empty(); }

 private:
  fs::path dir_;
  pid_t pid_ = -1;
  std::string port_;
};

// Tokens through the CLI: an admin creates a viewer token (printed once),
// the viewer reads but may not cancel, the admin revokes it and it stops
// working; no token at all is refused, saying how to give one.
TEST(CliRemoteTest, TokenCommandsAndTheirEffect) {
  ServerProcess server;
  ASSERT_TRUE(server.started()) << "seaplan-server did not report its ports";
  const std::string addr = server.address();

  auto created = RunSeaplan(
      {"--server", addr, "token", "create", "--role", "viewer", "--description", "cli test"});
  ASSERT_EQ(created.exit_code, 0) << created.err;
  const std::string viewer = created.out.substr(0, created.out.find('\n'));
  ASSERT_EQ(viewer.rfind("seaplan_", 0), 0u) << created.out;
  const std::string viewer_id = viewer.substr(8, 16);
  EXPECT_NE(created.err.find("shown only now"), std::string::npos) << created.err;

  auto listed = RunSeaplan({"--server", addr, "token", "list"});
  ASSERT_EQ(listed.exit_code, 0) << listed.err;
  EXPECT_NE(listed.out.find(viewer_id + "  viewer"), std::string::npos) << listed.out;
  EXPECT_EQ(listed.out.find(viewer), std::string::npos) << "a secret was listed";

  // --token wins over SEAPLAN_TOKEN (the admin's, set by the fixture).
  auto read = RunSeaplan({"--server", addr, "--token", viewer, "mission", "list"});
  EXPECT_EQ(read.exit_code, 0) << read.err;
  auto cancel = RunSeaplan({"--server", addr, "--token", viewer, "mission", "cancel", "m-x"});
  EXPECT_EQ(cancel.exit_code, 3) << cancel.err;
  EXPECT_NE(cancel.err.find("may not call MissionService/CancelMission"), std::string::npos)
      << cancel.err;
  const std::string token_file = WriteScratch("viewer.token", viewer + "\n");
  auto from_file = RunSeaplan({"--server", addr, "--token-file", token_file, "token", "list"});
  EXPECT_EQ(from_file.exit_code, 3) << from_file.err;  // a viewer lists no tokens
  EXPECT_NE(from_file.err.find("PERMISSION_DENIED"), std::string::npos) << from_file.err;

  auto revoked = RunSeaplan({"--server", addr, "token", "revoke", viewer_id});
  ASSERT_EQ(revoked.exit_code, 0) << revoked.err;
  EXPECT_NE(revoked.out.find("REVOKED"), std::string::npos) << revoked.out;
  auto after = RunSeaplan({"--server", addr, "--token", viewer, "mission", "list"});
  EXPECT_EQ(after.exit_code, 3);
  EXPECT_NE(after.err.find("revoked"), std::string::npos) << after.err;

  auto audit = RunSeaplan({"--server", addr, "audit"});
  ASSERT_EQ(audit.exit_code, 0) << audit.err;
  EXPECT_NE(audit.out.find("AccessService/CreateToken  " + viewer_id), std::string::npos)
      << audit.out;
  EXPECT_NE(audit.out.find("AccessService/RevokeToken  " + viewer_id), std::string::npos)
      << audit.out;

  auto none = RunSeaplan(
      {"-u", "SEAPLAN_TOKEN", (BinDir() / "seaplan").string(), "--server", addr, "mission", "list"},
      "/usr/bin/env");
  EXPECT_EQ(none.exit_code, 3);
  EXPECT_NE(none.err.find("--token"), std::string::npos) << none.err;
  auto missing = RunSeaplan({"--server", addr, "--token-file", "/nonexistent", "mission", "list"});
  EXPECT_EQ(missing.exit_code, 2) << missing.err;
}

TEST(CliRemoteTest, CommandsWorkAgainstARunningServer) {
  ServerProcess server;
  ASSERT_TRUE(server.started()) << "seaplan-server did not report its ports";
  const std::string addr = server.address();

  auto plan = RunSeaplan({"--server", addr, "plan", Example("domain.pddl"), Example("case-a.pddl"),
                          "--time-limit", "5"});
  EXPECT_EQ(plan.exit_code, 0) << plan.err;
  EXPECT_NE(plan.out.find("(refuel-ship ship0 port-e teamf0)"), std::string::npos) << plan.out;
  // -o takes the plans from the server's stream as they come.
  const std::string plan_file = (ScratchDir() / "remote.plan").string();
  auto written = RunSeaplan({"--server", addr, "plan", Example("domain.pddl"),
                             Example("case-a.pddl"), "--time-limit", "5", "-o", plan_file});
  EXPECT_EQ(written.exit_code, 0) << written.err;
  auto written_valid =
      RunSeaplan({"validate", Example("domain.pddl"), Example("case-a.pddl"), plan_file});
  EXPECT_EQ(written_valid.exit_code, 0) << written_valid.out << written_valid.err;

  auto valid = RunSeaplan({"--server", addr, "validate", Example("domain.pddl"),
                           Example("case-a.pddl"), Example("case-a-repaired.plan")});
  EXPECT_EQ(valid.exit_code, 0) << valid.out << valid.err;
  auto invalid = RunSeaplan({"--server", addr, "validate", Example("domain.pddl"),
                             Example("case-a.pddl"), Example("case-a-paper.plan")});
  EXPECT_EQ(invalid.exit_code, 1) << invalid.out << invalid.err;

  auto charts = RunSeaplan({"--server", addr, "chart", "list"});
  EXPECT_EQ(charts.exit_code, 0) << charts.err;
  EXPECT_NE(charts.out.find("no charts"), std::string::npos) << charts.out;

  // A chart uploaded through the CLI, then a route on it by id.
  auto upload =
      RunSeaplan({"--server", addr, "--json", "chart", "upload", Chart(), "--min-depth", "5"});
  ASSERT_EQ(upload.exit_code, 0) << upload.err;
  const auto id_at = upload.out.find("\"chartId\":\"");
  ASSERT_NE(id_at, std::string::npos) << upload.out;
  const auto id_start = id_at + std::string("\"chartId\":\"").size();
  const std::string chart_id =
      upload.out.substr(id_start, upload.out.find('"', id_start) - id_start);
  auto listed = RunSeaplan({"--server", addr, "chart", "list"});
  EXPECT_NE(listed.out.find(chart_id), std::string::npos) << listed.out;
  std::vector<std::string> route_args = {"--server", addr, "route", "--chart", chart_id};
  route_args.insert(route_args.end(), kRouteArgs.begin(), kRouteArgs.end());
  auto route = RunSeaplan(route_args);
  EXPECT_EQ(route.exit_code, 0) << route.err;
  EXPECT_NE(route.out.find("alternative(s); chosen"), std::string::npos) << route.out;

  auto missing = RunSeaplan({"--server", addr, "mission", "get", "no-such-mission"});
  EXPECT_EQ(missing.exit_code, 2) << missing.out << missing.err;
  EXPECT_NE(missing.err.find("NOT_FOUND"), std::string::npos) << missing.err;
}

// `chart delete`: only an admin may; the chart is gone afterwards and a
// second delete is NOT_FOUND (bad input, exit 2).
TEST(CliRemoteTest, ChartDeleteRemovesTheChartForAnAdminOnly) {
  ServerProcess server;
  ASSERT_TRUE(server.started()) << "seaplan-server did not report its ports";
  const std::string addr = server.address();
  const std::string harbour = (SourceDir() / "engine/chart/testdata/harbour.geojson").string();
  auto upload = RunSeaplan({"--server", addr, "--json", "chart", "upload", harbour});
  ASSERT_EQ(upload.exit_code, 0) << upload.err;
  const std::string key = "\"chartId\":\"";
  const auto id_start = upload.out.find(key) + key.size();
  ASSERT_NE(upload.out.find(key), std::string::npos) << upload.out;
  const std::string chart_id =
      upload.out.substr(id_start, upload.out.find('"', id_start) - id_start);

  auto created = RunSeaplan({"--server", addr, "token", "create", "--role", "operator"});
  ASSERT_EQ(created.exit_code, 0) << created.err;
  const std::string operator_token = created.out.substr(0, created.out.find('\n'));
  auto denied =
      RunSeaplan({"--server", addr, "--token", operator_token, "chart", "delete", chart_id});
  EXPECT_EQ(denied.exit_code, 3) << denied.out << denied.err;
  EXPECT_NE(denied.err.find("PERMISSION_DENIED"), std::string::npos) << denied.err;
  EXPECT_NE(RunSeaplan({"--server", addr, "chart", "list"}).out.find(chart_id), std::string::npos);

  auto deleted = RunSeaplan({"--server", addr, "chart", "delete", chart_id});
  ASSERT_EQ(deleted.exit_code, 0) << deleted.err;
  EXPECT_EQ(deleted.out, "deleted chart " + chart_id + "\n");
  auto listed = RunSeaplan({"--server", addr, "chart", "list"});
  EXPECT_NE(listed.out.find("no charts"), std::string::npos) << listed.out;
  auto again = RunSeaplan({"--server", addr, "chart", "delete", chart_id});
  EXPECT_EQ(again.exit_code, 2) << again.out << again.err;
  EXPECT_NE(again.err.find("NOT_FOUND"), std::string::npos) << again.err;
  auto audit = RunSeaplan({"--server", addr, "audit"});
  EXPECT_NE(audit.out.find("ChartService/DeleteChart  " + chart_id), std::string::npos)
      << audit.out;
}

// Every `"key":"number"` of a JSON text, in order (int64 fields are strings
// in proto3 JSON; "sequence" does not match "sequenceNumber").
std::vector<long long> JsonInt64s(const std::string& json, const std::string& key) {
  std::vector<long long> values;
  const std::regex pattern("\"" + key + "\":\"(\\d+)\"");
  for (auto it = std::sregex_iterator(json.begin(), json.end(), pattern);
       it != std::sregex_iterator(); ++it) {
    values.push_back(std::stoll((*it)[1].str()));
  }
  return values;
}

// `mission feedback` lists what seaplan-sim reported on a real mission:
// every stored report once, oldest first, whatever the page size; --limit
// stops early and says where to go on; --after-sequence goes on from there.
TEST(CliRemoteTest, MissionFeedbackListsTheStoredReportsPaged) {
  ServerProcess server;
  ASSERT_TRUE(server.started()) << "seaplan-server did not report its ports";
  const std::string addr = server.address();
  const auto report_dir = ScratchDir() / "feedback-sim";
  auto sim = RunSeaplan({"--server", addr, "--scenario",
                         (SourceDir() / "examples/scenarios/case-a.scenario").string(),
                         "--report-dir", report_dir.string(), "--replan-timeout-s", "60"},
                        BinDir() / "seaplan-sim");
  ASSERT_EQ(sim.exit_code, 0) << sim.out << sim.err;

  auto missions = RunSeaplan({"--server", addr, "--json", "mission", "list"});
  ASSERT_EQ(missions.exit_code, 0) << missions.err;
  std::smatch id;
  ASSERT_TRUE(std::regex_search(missions.out, id, std::regex("\"missionId\":\"([^\"]+)\"")))
      << missions.out;
  const std::string mission_id = id[1].str();

  auto all = RunSeaplan({"--server", addr, "--json", "mission", "feedback", mission_id});
  ASSERT_EQ(all.exit_code, 0) << all.err;
  const std::vector<long long> sequences = JsonInt64s(all.out, "sequence");
  ASSERT_GE(sequences.size(), 4u) << all.out.substr(0, 2000);
  for (std::size_t i = 1; i < sequences.size(); ++i) EXPECT_LT(sequences[i - 1], sequences[i]);
  EXPECT_EQ(all.out.find("nextAfterSequence"), std::string::npos) << "nothing is left";
  EXPECT_NE(all.out.find("\"kind\":\"KIND_TASK_COMPLETED\""), std::string::npos);
  EXPECT_NE(all.out.find("\"vesselId\":\"mass-1\""), std::string::npos);

  // The table, two reports per call: a header and one row per report.
  auto table =
      RunSeaplan({"--server", addr, "mission", "feedback", mission_id, "--page-size", "2"});
  ASSERT_EQ(table.exit_code, 0) << table.err;
  std::istringstream lines(table.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_NE(line.find("seq"), std::string::npos) << line;
  EXPECT_NE(line.find("mission s"), std::string::npos) << line;
  std::vector<long long> rows;
  while (std::getline(lines, line)) rows.push_back(std::stoll(line));
  EXPECT_EQ(rows, sequences);
  EXPECT_NE(table.out.find("TASK_COMPLETED"), std::string::npos) << table.out;
  EXPECT_NE(table.out.find("mass-1"), std::string::npos) << table.out;

  // Three reports, over two calls, then the rest from the cursor given.
  auto first = RunSeaplan({"--server", addr, "--json", "mission", "feedback", mission_id,
                           "--page-size", "2", "--limit", "3"});
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_EQ(JsonInt64s(first.out, "sequence"),
            std::vector<long long>(sequences.begin(), sequences.begin() + 3));
  EXPECT_EQ(JsonInt64s(first.out, "nextAfterSequence"), std::vector<long long>{sequences[2]});
  auto first_table =
      RunSeaplan({"--server", addr, "mission", "feedback", mission_id, "--limit", "3"});
  EXPECT_NE(first_table.err.find("--after-sequence " + std::to_string(sequences[2])),
            std::string::npos)
      << first_table.err;
  auto rest = RunSeaplan({"--server", addr, "--json", "mission", "feedback", mission_id,
                          "--after-sequence", std::to_string(sequences[2])});
  ASSERT_EQ(rest.exit_code, 0) << rest.err;
  EXPECT_EQ(JsonInt64s(rest.out, "sequence"),
            std::vector<long long>(sequences.begin() + 3, sequences.end()));

  auto after_all = RunSeaplan({"--server", addr, "mission", "feedback", mission_id,
                               "--after-sequence", std::to_string(sequences.back())});
  EXPECT_EQ(after_all.exit_code, 0) << after_all.err;
  EXPECT_EQ(after_all.out, "no feedback\n");

  auto unknown = RunSeaplan({"--server", addr, "mission", "feedback", "no-such-mission"});
  EXPECT_EQ(unknown.exit_code, 2) << unknown.out << unknown.err;
  EXPECT_NE(unknown.err.find("NOT_FOUND"), std::string::npos) << unknown.err;
  auto bad_page =
      RunSeaplan({"--server", addr, "mission", "feedback", mission_id, "--page-size=-1"});
  EXPECT_EQ(bad_page.exit_code, 2) << bad_page.out << bad_page.err;
  EXPECT_NE(bad_page.err.find("page_size must not be negative"), std::string::npos) << bad_page.err;
}

}  // namespace
}  // namespace seaplan::testing
