#include "seaplan/route/route_planner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

namespace seaplan::route {
namespace {

constexpr double kE0 = 500000.0, kN0 = 7000000.0;  // UTM33 near 63.1 N, 15 E

chart::Polygon Rect(double x0, double y0, double x1, double y1) {
  return chart::Polygon{
      {{kE0 + x0, kN0 + y0}, {kE0 + x1, kN0 + y0}, {kE0 + x1, kN0 + y1}, {kE0 + x0, kN0 + y1}}, {}};
}
EastNorth P(double x, double y) {
  return {kE0 + x, kN0 + y};
}

// A long island x in [-800, 800], y in [-200, 200]; a square "harbour wall"
// ring far east encloses the point (3000, 0).
std::shared_ptr<const chart::ObstacleMap> Map() {
  std::vector<chart::Polygon> polys = {Rect(-800, -200, 800, 200)};
  chart::Polygon ring = Rect(2800, -200, 3200, 200);
  ring.holes.push_back({{kE0 + 2900, kN0 - 100},
                        {kE0 + 3100, kN0 - 100},
                        {kE0 + 3100, kN0 + 100},
                        {kE0 + 2900, kN0 + 100}});
  polys.push_back(ring);
  chart::ChartOptions co;
  co.safety_buffer_m = 10.0;
  auto map = chart::ObstacleMap::FromPolygons(polys, chart::LocalFrame(), co, "test",
                                              chart::LocalBox{P(-2500, -1500), P(3500, 1500)});
  EXPECT_TRUE(map.ok()) << map.status();
  return std::make_shared<const chart::ObstacleMap>(std::move(map).value());
}

Environment SouthWind() {
  Environment env;
  env.wind_speed_mps = 20.0;
  env.wind_from_deg = 180.0;
  env.current_speed_mps = 1.0;
  env.current_toward_deg = 0.0;
  return env;
}

RouteOptions FastOptions() {
  RouteOptions o;
  o.level2.pso.particles = 12;
  o.level2.pso.iterations = 30;
  return o;
}

TEST(RoutePlannerTest, PlansTwoAlternativesAndChoosesTheSaferOne) {
  auto map = Map();
  auto planner = RoutePlanner::Create(map, ShipParticulars{}, FastOptions());
  ASSERT_TRUE(planner.ok()) << planner.status();
  const chart::LatLon start = map->frame().ToLatLon(P(-2000, 0));
  const chart::LatLon goal = map->frame().ToLatLon(P(2000, 0));
  auto r = planner->Plan(start, goal, SouthWind());
  ASSERT_TRUE(r.ok()) << r.status();
  ASSERT_EQ(r->alternatives.size(), 2u);
  ASSERT_GE(r->chosen, 0);
  const RouteAlternative& chosen = r->alternatives[r->chosen];
  const RouteAlternative& other = r->alternatives[1 - r->chosen];
  EXPECT_LE(chosen.expected_cost, other.expected_cost);
  // The chosen route passes north of the island: drifting away from it.
  double mid_y = 0;
  for (const auto& w : chosen.waypoints) mid_y += (w.local.north_m - kN0) / chosen.waypoints.size();
  EXPECT_GT(mid_y, 0.0);
  // The south route's drift hits the island: higher P(G) somewhere.
  double max_other = 0, max_chosen = 0;
  for (const auto& w : other.waypoints) max_other = std::max(max_other, w.grounding_probability);
  for (const auto& w : chosen.waypoints) max_chosen = std::max(max_chosen, w.grounding_probability);
  EXPECT_GT(max_other, max_chosen);
  // Totals add up; lat/lon and local agree; times use per-mode speeds.
  double length = 0, time = 0, fuel = 0;
  for (size_t k = 0; k < chosen.waypoints.size(); ++k) {
    const auto& w = chosen.waypoints[k];
    const EastNorth back = map->frame().ToLocal(w.latlon);
    EXPECT_NEAR(back.east_m, w.local.east_m, 1e-3);
    EXPECT_NEAR(back.north_m, w.local.north_m, 1e-3);
    length += w.segment_length_m;
    time += w.segment_time_s;
    fuel += w.segment_fuel_kg;
    if (k + 1 < chosen.waypoints.size()) {
      EXPECT_GT(w.segment_time_s, w.segment_length_m / 12.0);
      EXPECT_LT(w.segment_time_s, w.segment_length_m / 4.0);
    }
  }
  EXPECT_NEAR(chosen.length_m, length, 1e-6);
  EXPECT_NEAR(chosen.sailing_time_s, time, 1e-6);
  EXPECT_NEAR(chosen.fuel_kg, fuel, 1e-9);
  EXPECT_GT(chosen.length_m, 4000.0);
}

TEST(RoutePlannerTest, BadEndpointsAndNoRoute) {
  auto map = Map();
  auto planner = RoutePlanner::Create(map, ShipParticulars{}, FastOptions());
  ASSERT_TRUE(planner.ok()) << planner.status();
  auto outside = planner->Plan(P(-2000, 0), P(9000, 0), SouthWind());
  EXPECT_EQ(outside.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(outside.status().message().find("goal"), std::string_view::npos) << outside.status();
  auto inside = planner->Plan(P(0, 0), P(2000, 0), SouthWind());
  EXPECT_EQ(inside.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(inside.status().message().find("start"), std::string_view::npos) << inside.status();
  // Goal inside the walled harbour: water, but unreachable.
  auto enclosed = planner->Plan(P(-2000, 0), P(3000, 0), SouthWind());
  EXPECT_EQ(enclosed.status().code(), absl::StatusCode::kFailedPrecondition) << enclosed.status();
  Environment bad = SouthWind();
  bad.wind_speed_mps = -1;
  EXPECT_EQ(planner->Plan(P(-2000, 0), P(2000, 0), bad).status().code(),
            absl::StatusCode::kInvalidArgument);
  RouteOptions deeper = FastOptions();
  deeper.min_depth_m = 50.0;  // the map was built for 5 m
  EXPECT_EQ(RoutePlanner::Create(map, ShipParticulars{}, deeper).status().code(),
            absl::StatusCode::kFailedPrecondition);
}

TEST(RoutePlannerTest, EndpointErrorsSpeakLatLonAndPointToNavigableWater) {
  auto map = Map();
  auto planner = RoutePlanner::Create(map, ShipParticulars{}, FastOptions());
  ASSERT_TRUE(planner.ok()) << planner.status();
  // 30 m inside the island's buffered north shore (y = 200 + growth).
  const double growth = chart::ObstacleGrowthM(map->summary().options);
  const chart::LatLon start = map->frame().ToLatLon(P(0, 200 + growth - 30));
  auto r = planner->Plan(start, map->frame().ToLatLon(P(2000, 0)), SouthWind());
  ASSERT_EQ(r.status().code(), absl::StatusCode::kInvalidArgument) << r.status();
  const std::string message(r.status().message());
  // The position as the user gave it, not projected metres.
  EXPECT_NE(message.find("start " + chart::FormatLatLon(start)), std::string::npos) << message;
  EXPECT_EQ(message.find(std::to_string(static_cast<int>(kE0))), std::string::npos) << message;
  // The nearest navigable point: straight north, 30 m + the 5 m step out.
  const chart::LatLon nearest = map->frame().ToLatLon(P(0, 200 + growth + 5));
  EXPECT_NE(message.find("nearest navigable point is " + chart::FormatLatLon(nearest) + ", 35 m"),
            std::string::npos)
      << message;
  // Outside the coverage: the same, with the box.
  auto outside = planner->Plan(map->frame().ToLatLon(P(-2000, 0)),
                               map->frame().ToLatLon(P(4500, 0)), SouthWind());
  ASSERT_EQ(outside.status().code(), absl::StatusCode::kInvalidArgument);
  const std::string outside_message(outside.status().message());
  EXPECT_NE(outside_message.find("outside the chart coverage"), std::string::npos);
  EXPECT_NE(outside_message.find("nearest navigable point"), std::string::npos);
}

TEST(RoutePlannerTest, RoutesKeepTheSafetyBufferFromTheChartedObstacles) {
  auto map = Map();
  RouteOptions options = FastOptions();
  options.level2.segments = 3;  // long chords that cut corners unless repaired
  auto planner = RoutePlanner::Create(map, ShipParticulars{}, options);
  ASSERT_TRUE(planner.ok()) << planner.status();
  auto r = planner->Plan(P(-2000, -50), P(2000, 50), SouthWind());
  ASSERT_TRUE(r.ok()) << r.status();
  ASSERT_GE(r->chosen, 0);
  for (const RouteAlternative& alt : r->alternatives) {
    EXPECT_TRUE(alt.safe);
    EXPECT_GE(alt.clearance_m, map->summary().options.safety_buffer_m);
    // The clearance is the distance to the island itself (x in [-800, 800],
    // |y| <= 200): no waypoint is closer than it.
    for (const RouteWaypoint& w : alt.waypoints) {
      const double dx = std::max(0.0, std::abs(w.local.east_m - kE0) - 800.0);
      const double dy = std::max(0.0, std::abs(w.local.north_m - kN0) - 200.0);
      EXPECT_GE(std::hypot(dx, dy), alt.clearance_m - 1e-6);
    }
  }
}

TEST(RoutePlannerTest, ServiceSpeedSetsEveryModesSpeedAndFuel) {
  auto map = Map();
  const chart::LatLon start = map->frame().ToLatLon(P(-2000, 0));
  const chart::LatLon goal = map->frame().ToLatLon(P(2000, 0));
  auto fast = RoutePlanner::Create(map, ShipParticulars{}, FastOptions());
  ASSERT_TRUE(fast.ok()) << fast.status();
  ShipParticulars slow_ship;
  slow_ship.service_speed_mps = 3.6;
  auto slow = RoutePlanner::Create(map, slow_ship, FastOptions());
  ASSERT_TRUE(slow.ok()) << slow.status();
  auto rf = fast->Plan(start, goal, Environment{});
  auto rs = slow->Plan(start, goal, Environment{});
  ASSERT_TRUE(rf.ok() && rs.ok());
  const RouteAlternative& s = rs->alternatives[rs->chosen];
  // Every mode can hold 3.6 m/s: each segment is sailed at it, whatever its mode.
  for (size_t k = 0; k + 1 < s.waypoints.size(); ++k) {
    EXPECT_NEAR(s.waypoints[k].segment_time_s, s.waypoints[k].segment_length_m / 3.6, 1e-6) << k;
  }
  const RouteAlternative& f = rf->alternatives[rf->chosen];
  EXPECT_GT(f.length_m / f.sailing_time_s, 4.5);  // service throttle 0.8: PTI 4.6, PTO 9.2 m/s
  // Slower through the water: less power, so a lower fuel rate (per metre
  // it can be more: the machinery's fixed loads run longer).
  EXPECT_LT(s.fuel_kg / s.sailing_time_s, f.fuel_kg / f.sailing_time_s);
  // Step 6 sails the route at the speed it is ordered for, else at 9 m/s.
  EXPECT_NEAR(rs->sail_speed_mps, 3.6, 1e-3);
  EXPECT_EQ(rf->sail_speed_mps, FastOptions().level2.sail_speed_mps);

  // Faster than a mode's top speed: that mode sails at its top speed, the route is still planned.
  ShipParticulars racer;
  racer.service_speed_mps = 30.0;
  auto top = RoutePlanner::Create(map, racer, FastOptions());
  ASSERT_TRUE(top.ok()) << top.status();
  auto rt = top->Plan(start, goal, Environment{});
  ASSERT_TRUE(rt.ok()) << rt.status();
  const RouteAlternative& t = rt->alternatives[rt->chosen];
  EXPECT_LT(t.sailing_time_s, f.sailing_time_s);
  EXPECT_GT(t.sailing_time_s, t.length_m / 30.0);
  int pto_segments = 0;  // sailed at PTO's top speed, as step 6 sailed them
  for (size_t k = 0; k + 1 < t.waypoints.size(); ++k) {
    if (t.waypoints[k].mode != MsoMode::kPto) continue;
    ++pto_segments;
    EXPECT_NEAR(rt->sail_speed_mps, t.waypoints[k].segment_length_m / t.waypoints[k].segment_time_s,
                1e-6);
  }
  EXPECT_GT(pto_segments, 0);
  EXPECT_LT(rt->sail_speed_mps, 30.0);

  ShipParticulars bad;
  bad.service_speed_mps = -1.0;
  EXPECT_EQ(RoutePlanner::Create(map, bad, FastOptions()).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(RoutePlannerTest, EstimateRiskHigherUpwindOfTheShore) {
  auto map = Map();
  auto planner = RoutePlanner::Create(map, ShipParticulars{}, FastOptions());
  ASSERT_TRUE(planner.ok()) << planner.status();
  const auto& f = map->frame();
  std::vector<TrackPoint> track = {
      {f.ToLatLon(P(0, -320)), 90.0, 2.0, MsoMode::kPto},  // south of the island, drifting onto it
      {f.ToLatLon(P(0, -320)), 90.0, 2.0, MsoMode::kMec},
      {f.ToLatLon(P(0, 320)), 90.0, 2.0, MsoMode::kPto},  // north: drifting away
  };
  auto risk = planner->EstimateRisk(track, SouthWind());
  ASSERT_TRUE(risk.ok()) << risk.status();
  ASSERT_EQ(risk->size(), 3u);
  EXPECT_LT((*risk)[0].ttg_s, 300.0);
  EXPECT_EQ((*risk)[2].ttg_s, 630.0);
  EXPECT_GT((*risk)[0].grounding_probability, 10 * (*risk)[2].grounding_probability);
  EXPECT_LT((*risk)[1].grounding_probability, (*risk)[0].grounding_probability);
  EXPECT_NEAR((*risk)[0].expected_cost, 5e6 * (*risk)[0].grounding_probability, 1e-12);
}

}  // namespace
}  // namespace seaplan::route
