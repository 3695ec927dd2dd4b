#include "scenario.h"

#include <gtest/gtest.h>

#include <cmath>

#include "absl/strings/str_cat.h"

namespace seaplan::sim {
namespace {

TEST(ScenarioTest, ParsesEveryKey) {
  auto s = ParseScenario(R"(# case B
name = case-b
domain = ../fjord/domain.pddl
problem = ../fjord/case-a.pddl
location = port-a 63.44 10.35   # comment
location = PORT-B 63.445 10.37
service_speed_mps = 3.6
grid = 63.43 10.33 25
gnss_jump = 100 170 38 35 30 50
traffic = ferry ferry 0 63.45 10.36 ; 900 63.43 10.40
port_operation = load-cont 60
wind = 10 250
fuel_model = machinery
planner_max_expansions = 25000
)",
                         "/x/scenarios/b.scenario");
  ASSERT_TRUE(s.ok()) << s.status();
  EXPECT_EQ(s->locations.size(), 2u);
  EXPECT_EQ(s->locations[1].first, "port-b");
  ASSERT_EQ(s->gnss_jumps.size(), 1u);
  EXPECT_DOUBLE_EQ(s->gnss_jumps[0].to_cell.north_m, 50);
  ASSERT_EQ(s->traffic.size(), 1u);
  EXPECT_EQ(s->traffic[0].track.size(), 2u);
  EXPECT_EQ(s->fuel_model, FuelModelKind::kMachinery);
  EXPECT_EQ(s->planner_max_expansions, 25000u);
  EXPECT_EQ(*ResolvePath(*s, s->domain_path, ""), "/x/fjord/domain.pddl");
  EXPECT_EQ(*ResolvePath(*s, "shared:enc/t.geojson", "/sh"), "/sh/enc/t.geojson");
  EXPECT_FALSE(ResolvePath(*s, "shared:enc/t.geojson", "").ok());

  auto frame = chart::LocalFrame::ForCentre({63.44, 10.35});
  auto cfg = MakeExecutorConfig(*s, frame, "port-b");
  ASSERT_TRUE(cfg.ok());
  auto locs = LocalLocations(*s, frame);
  EXPECT_NEAR(cfg->start.east_m, locs["port-b"].east_m, 1e-9);
  // (38,35) and (30,50) are 8 cells west and 15 north apart.
  EastNorth d = cfg->grid.Cell(30, 50) - cfg->grid.Cell(38, 35);
  EXPECT_NEAR(d.east_m, -200, 1e-9);
  EXPECT_NEAR(d.north_m, 375, 1e-9);
}

TEST(ScenarioTest, BadLinesNameTheLine) {
  auto s = ParseScenario("domain = d\nproblem = p\nlocation = a 91 10\n", "f.scenario");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.status().message().find("f.scenario:3"), std::string::npos) << s.status();
  auto u = ParseScenario("domain = d\nproblem = p\nfoo = 1\n", "f");
  EXPECT_NE(u.status().message().find("unknown key 'foo'"), std::string::npos);
  auto g =
      ParseScenario("domain = d\nproblem = p\nlocation = a 1 2\ngnss_jump = 1 2 3 4 5 6\n", "f");
  EXPECT_NE(g.status().message().find("grid"), std::string::npos);
  for (const char* bad : {"-1", "1.5", "many", "1 2"}) {
    auto e = ParseScenario(absl::StrCat("domain = d\nplanner_max_expansions = ", bad, "\n"), "f");
    ASSERT_FALSE(e.ok()) << bad;
    EXPECT_NE(e.status().message().find("f:2: planner_max_expansions"), std::string::npos)
        << e.status();
  }
  auto none = ParseScenario("domain = d\nproblem = p\nlocation = a 1 2\n", "f");
  ASSERT_TRUE(none.ok()) << none.status();
  EXPECT_EQ(none->planner_max_expansions, 0u) << "no limit unless given";
}

TEST(ScenarioTest, SeedsShiftTheTrafficAndTheWindWithinTheirBoundsReproducibly) {
  ExecutorConfig base;
  base.environment.wind_speed_mps = 10.0;
  base.environment.wind_direction_from_rad = 1.0;
  for (int i = 0; i < 3; ++i) {
    base.traffic.push_back({i + 1, "v", "ferry", {{0.0, {0, 0}}, {100.0, {100, 0}}}});
  }
  ExecutorConfig a = base, b = base, c = base;
  PerturbConfig(7, &a);
  PerturbConfig(7, &b);
  PerturbConfig(8, &c);
  bool differs = false;
  for (size_t v = 0; v < base.traffic.size(); ++v) {
    const double shift = a.traffic[v].track[0].time_s;
    EXPECT_LE(std::abs(shift), 60.0);
    // The whole track moves together.
    EXPECT_NEAR(a.traffic[v].track[1].time_s - shift, 100.0, 1e-9);
    EXPECT_EQ(shift, b.traffic[v].track[0].time_s);
    differs = differs || shift != c.traffic[v].track[0].time_s;
  }
  EXPECT_TRUE(differs) << "seeds 7 and 8 shift the traffic alike";
  EXPECT_GE(a.environment.wind_speed_mps, 8.0);
  EXPECT_LE(a.environment.wind_speed_mps, 12.0);
  EXPECT_LE(std::abs(a.environment.wind_direction_from_rad - 1.0), 20.0 * M_PI / 180 + 1e-12);
}

}  // namespace
}  // namespace seaplan::sim
