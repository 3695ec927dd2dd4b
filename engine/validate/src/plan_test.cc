#include "seaplan/validate/plan.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace seaplan::validate {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

TEST(ParsePlanTest, ReadsIpcFormatWithCommentsCaseAndCrLf) {
  const auto plan = ParsePlan(
      "\xEF\xBB\xBF; Plan found by a planner\r\n"
      "\r\n"
      "0.000: (Load-Cont SHIP0 port-a cont-x)  [60.000] ; first\r\n"
      "   60.001:(move-ship ship0 port-a port-b)[288.888888888889]\n"
      "70 (drop ship0)\n"
      "+1e2: (wait)   \n"
      "; trailing comment without newline");
  ASSERT_TRUE(plan.ok()) << plan.status();
  ASSERT_EQ(plan->steps.size(), 4u);
  const PlanStep& load = plan->steps[0];
  EXPECT_EQ(load.start_s, 0.0);
  EXPECT_EQ(load.name, "load-cont");
  EXPECT_THAT(load.args, ElementsAre("ship0", "port-a", "cont-x"));
  EXPECT_EQ(load.duration_s, 60.0);
  EXPECT_EQ(load.line, 3);
  EXPECT_EQ(plan->steps[1].start_s, 60.001);
  EXPECT_EQ(plan->steps[1].duration_s, 288.888888888889);
  EXPECT_EQ(plan->steps[1].line, 4);
  // Instantaneous steps have no "[d]" and no colon is needed.
  EXPECT_EQ(plan->steps[2].name, "drop");
  EXPECT_EQ(plan->steps[2].duration_s, 0.0);
  EXPECT_EQ(plan->steps[3].start_s, 100.0);
  EXPECT_TRUE(plan->steps[3].args.empty());
}

TEST(ParsePlanTest, EmptyTextIsTheEmptyPlan) {
  const auto plan = ParsePlan("; nothing\n\n   \n");
  ASSERT_TRUE(plan.ok());
  EXPECT_TRUE(plan->steps.empty());
}

struct BadPlan {
  const char* text;
  const char* where;
  const char* what;
};

class ParsePlanErrorTest : public ::testing::TestWithParam<BadPlan> {};

TEST_P(ParsePlanErrorTest, SaysLineAndColumn) {
  const auto plan = ParsePlan(GetParam().text);
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(plan.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_THAT(plan.status().message(), HasSubstr(GetParam().where));
  EXPECT_THAT(plan.status().message(), HasSubstr(GetParam().what));
}

INSTANTIATE_TEST_SUITE_P(
    Errors, ParsePlanErrorTest,
    ::testing::Values(
        BadPlan{"0: (a b) [1]\nx: (a b) [1]\n", "plan line 2, column 1", "expected a start time"},
        BadPlan{"0: a b [1]", "plan line 1, column 4", "expected '('"},
        BadPlan{"0: (a b [1]", "plan line 1, column 9", "expected an argument or ')'"},
        BadPlan{"0: ()", "plan line 1, column 5", "expected an action name"},
        BadPlan{"0: (a (b))", "plan line 1, column 7", "expected an argument or ')'"},
        BadPlan{"0: (a b) [x]", "plan line 1, column 11", "expected a duration"},
        BadPlan{"0: (a b) [1", "plan line 1, column 12", "expected ']'"},
        BadPlan{"0: (a b) [1] extra", "plan line 1, column 14", "unexpected"},
        BadPlan{"nan: (a b) [1]", "plan line 1, column 1", "finite"},
        BadPlan{"0: (a b) [inf]", "plan line 1, column 11", "finite"},
        BadPlan{"1e999: (a)", "plan line 1, column 1", "out of range"},
        BadPlan{"\r\n\r\n  0.5 (a b c\r\n", "plan line 3, column 13",
                "expected an argument or ')'"}));

TEST(ParsePlanTest, ArbitraryBytesGiveAPlanOrAnErrorNeverACrash) {
  // Deterministic pseudo-random lines built from plan-like characters.
  const std::string alphabet = "0123456789.:;()[] -+eEnaifx\t\r\n\xff";
  std::uint32_t state = 12345;
  auto next = [&] {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  };
  const std::string valid = "0.5: (a b) [1]\n12 (c)\n";
  int parsed = 0, rejected = 0;
  for (int i = 0; i < 3000; ++i) {
    std::string text;
    if (i % 2 == 0) {
      const std::uint32_t length = next() % 60;
      for (std::uint32_t k = 0; k < length; ++k) text += alphabet[next() % alphabet.size()];
    } else {  // a valid plan with a few characters changed
      text = valid;
      for (int k = 0; k < 2; ++k) text[next() % text.size()] = alphabet[next() % alphabet.size()];
    }
    const auto plan = ParsePlan(text);
    ++(plan.ok() ? parsed : rejected);
    if (!plan.ok()) {
      EXPECT_THAT(plan.status().message(), HasSubstr("plan line ")) << text;
    } else {
      // Whatever parsed prints and parses back to the same plan.
      const auto again = ParsePlan(FormatPlan(*plan));
      ASSERT_TRUE(again.ok()) << text;
      Plan without_lines = *plan;
      for (auto& step : without_lines.steps) step.line = 0;
      Plan again_without_lines = *again;
      for (auto& step : again_without_lines.steps) step.line = 0;
      EXPECT_EQ(again_without_lines, without_lines) << text;
    }
  }
  EXPECT_GT(parsed, 100);
  EXPECT_GT(rejected, 100);
}

TEST(FormatPlanTest, PrintsShortestExactNumbers) {
  EXPECT_EQ(FormatTime(0.0), "0");
  EXPECT_EQ(FormatTime(-0.0), "0");
  EXPECT_EQ(FormatTime(60.0), "60");
  EXPECT_EQ(FormatTime(60.001), "60.001");
  EXPECT_EQ(FormatTime(288.5), "288.5");
  EXPECT_EQ(FormatTime(0.0005), "0.0005");
  // Off the decimal grid: every digit needed to get the same double back.
  EXPECT_EQ(std::stod(FormatTime(52.0 / 0.18)), 52.0 / 0.18);

  Plan plan;
  plan.steps.push_back({0.0, "load-cont", {"ship0", "port-a", "cont-x"}, 60.0, 0});
  plan.steps.push_back({60.001, "drop", {}, 0.0, 0});
  EXPECT_EQ(FormatPlan(plan),
            "0: (load-cont ship0 port-a cont-x) [60]\n"
            "60.001: (drop)\n");
}

TEST(FormatPlanTest, RoundTripIsExactAndKeepsEpsilonSeparations) {
  // A schedule like the planner's: exact durations, 1 ms separations.
  Plan plan;
  double t = 0.0;
  int line = 0;
  for (const double length : {52.0, 102.0, 107.0, 87.0}) {
    const double d = length / 0.18;
    plan.steps.push_back({t, "move-ship", {"ship0", "a", "b"}, d, ++line});
    t += d + 0.001;
    plan.steps.push_back({t, "unload", {"x"}, 50.0, ++line});
    t += 50.0 + 0.001;
  }
  plan.steps.push_back({t, "tick", {}, 0.0, ++line});
  const std::string text = FormatPlan(plan);
  const auto reparsed = ParsePlan(text);
  ASSERT_TRUE(reparsed.ok()) << reparsed.status();
  EXPECT_EQ(*reparsed, plan) << text;
  // Every separation survives printing exactly.
  for (std::size_t i = 0; i + 1 < plan.steps.size(); ++i) {
    EXPECT_EQ(reparsed->steps[i + 1].start_s - reparsed->steps[i].end_s(),
              plan.steps[i + 1].start_s - plan.steps[i].end_s());
  }
  // And formatting is stable.
  EXPECT_EQ(FormatPlan(*reparsed), text);
}

}  // namespace
}  // namespace seaplan::validate
