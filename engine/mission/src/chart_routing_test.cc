#include "seaplan/mission/chart_routing.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

namespace seaplan::mission {
namespace {

constexpr double kE0 = 500000.0, kN0 = 7000000.0;  // UTM33 near 63.1 N, 15 E

chart::Polygon Rect(double x0, double y0, double x1, double y1) {
  return {{{kE0 + x0, kN0 + y0}, {kE0 + x1, kN0 + y0}, {kE0 + x1, kN0 + y1}, {kE0 + x0, kN0 + y1}},
          {}};
}
EastNorth P(double x, double y) {
  return {kE0 + x, kN0 + y};
}
EastNorth M(double x, double y) {
  return {kE0 + x, kN0 + y};
}

// An island x, y in [-300, 300] (10 m safety buffer) in a 6 x 4 km chart.
std::shared_ptr<const chart::ObstacleMap> Island() {
  chart::ChartOptions co;
  co.safety_buffer_m = 10.0;
  auto map =
      chart::ObstacleMap::FromPolygons({Rect(-300, -300, 300, 300)}, chart::LocalFrame(), co,
                                       "test", chart::LocalBox{P(-3000, -2000), P(3000, 2000)});
  EXPECT_TRUE(map.ok()) << map.status();
  return std::make_shared<const chart::ObstacleMap>(std::move(map).value());
}

ChartRouteSettings FastSettings() {
  ChartRouteSettings s;
  s.options.level2.pso.particles = 12;
  s.options.level2.pso.iterations = 30;
  return s;
}

TEST(ChartRoutingTest, PrependWayOutAddsALegAtTheRoutesMeanSpeed) {
  Route r;
  r.length_m = 100;
  r.sailing_time_s = 50;
  r.waypoints = {{{0, 0}, MsoMode::kPti, 0, 0, 0, 0, 0, 4.0},
                 {{100, 0}, MsoMode::kMec, 50, 100, 0, 0, 0, 0}};
  PrependWayOut({-20, 0}, &r);
  ASSERT_EQ(r.waypoints.size(), 3u);
  EXPECT_EQ(r.waypoints[0].position, (EastNorth{-20, 0}));
  EXPECT_EQ(r.waypoints[0].mode, MsoMode::kPti);
  EXPECT_DOUBLE_EQ(r.waypoints[0].eta_s, 0);
  EXPECT_DOUBLE_EQ(r.waypoints[0].fuel_kg, 4.0 * 20 / 100);
  EXPECT_DOUBLE_EQ(r.waypoints[1].eta_s, 10);  // 20 m at 2 m/s
  EXPECT_DOUBLE_EQ(r.waypoints[2].distance_from_start_m, 120);
  EXPECT_DOUBLE_EQ(r.length_m, 120);
  EXPECT_DOUBLE_EQ(r.sailing_time_s, 60);
  Route empty;
  PrependWayOut({1, 1}, &empty);
  EXPECT_TRUE(empty.waypoints.empty());
}

TEST(ChartRoutingTest, RouteFromAlternativeAccumulatesEtaAndDistance) {
  route::RouteAlternative a;
  a.length_m = 300;
  a.sailing_time_s = 60;
  a.waypoints.resize(3);
  a.waypoints[0].local = {0, 0};
  a.waypoints[0].segment_length_m = 100;
  a.waypoints[0].segment_time_s = 20;
  a.waypoints[0].grounding_probability = 0.01;
  a.waypoints[0].mode = route::MsoMode::kPto;
  a.waypoints[1].local = {100, 0};
  a.waypoints[1].segment_length_m = 200;
  a.waypoints[1].segment_time_s = 40;
  a.waypoints[1].grounding_probability = 0.03;
  a.waypoints[2].local = {300, 0};
  Route r = RouteFromAlternative(a, 1);
  EXPECT_EQ(r.alternative_index, 1);
  ASSERT_EQ(r.waypoints.size(), 3u);
  EXPECT_EQ(r.waypoints[0].mode, MsoMode::kPto);
  EXPECT_DOUBLE_EQ(r.waypoints[1].eta_s, 20);
  EXPECT_DOUBLE_EQ(r.waypoints[2].eta_s, 60);
  EXPECT_DOUBLE_EQ(r.waypoints[2].distance_from_start_m, 300);
  EXPECT_DOUBLE_EQ(r.max_grounding_probability, 0.03);
}

TEST(ChartRoutingTest, CacheLoadsAChartOnceAndRoutesLeaveTheBufferFirst) {
  std::atomic<int> loads{0};
  ChartRoutingCache cache(
      [&](const std::string& id) -> StatusOr<std::shared_ptr<const chart::ObstacleMap>> {
        if (id != "island") return absl::NotFoundError("chart '" + id + "' not found");
        ++loads;
        return Island();
      });
  auto routing = cache.Get("island", "fast", FastSettings());
  ASSERT_TRUE(routing.ok()) << routing.status();
  auto again = cache.Get("island", "fast", FastSettings());
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(routing->get(), again->get());
  EXPECT_EQ(loads.load(), 1);
  EXPECT_TRUE(absl::IsFailedPrecondition(cache.Get("other", "fast", FastSettings()).status()));
  // Forgetting another chart keeps this one; forgetting it loads it again.
  cache.Forget("isl");
  EXPECT_EQ(cache.Get("island", "fast", FastSettings())->get(), routing->get());
  EXPECT_EQ(loads.load(), 1);
  cache.Forget("island");
  auto reloaded = cache.Get("island", "fast", FastSettings());
  ASSERT_TRUE(reloaded.ok());
  EXPECT_NE(reloaded->get(), routing->get());
  EXPECT_EQ(loads.load(), 2);

  // (0, 305) is in the buffer (island edge at 300, buffer 10 m): the route
  // starts there and leaves northwards first.
  RouteRequest req;
  req.from_position = M(0, 305);
  req.to_position = M(0, 1500);
  auto r = (*routing)->Plan(req, StopToken());
  ASSERT_TRUE(r.ok()) << r.status();
  ASSERT_GE(r->waypoints.size(), 3u);
  EXPECT_EQ(r->waypoints.front().position, M(0, 305));
  EXPECT_GT(r->waypoints[1].position.north_m, kN0 + 310);
  EXPECT_NEAR(r->waypoints.back().position.north_m, kN0 + 1500, 1e-6);
  // Asked again: the cached route.
  auto cached = (*routing)->Plan(req, StopToken());
  ASSERT_TRUE(cached.ok());
  EXPECT_DOUBLE_EQ(cached->length_m, r->length_m);

  // The island's centre is 310 m from free water: still a way out.
  ASSERT_TRUE((*routing)->Plan({"move", "a", "b", M(0, 0), M(0, 1500), 0}, StopToken()).ok());
  // A goal inside the island cannot be sailed to.
  auto inside = (*routing)->Plan({"move", "a", "b", M(0, 1500), M(0, 0), 0}, StopToken());
  EXPECT_TRUE(absl::IsFailedPrecondition(inside.status())) << inside.status();
  // In the user's latitude/longitude, with the nearest navigable point.
  const std::string message(inside.status().message());
  EXPECT_NE(message.find(chart::FormatLatLon((*routing)->frame().ToLatLon(M(0, 0)))),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("nearest navigable point is"), std::string::npos) << message;
  EXPECT_EQ(message.find("7000000"), std::string::npos) << message;
}

TEST(ChartRoutingTest, ShortestWayOutFindsTheNearestFreeWater) {
  auto planner =
      route::RoutePlanner::Create(Island(), route::ShipParticulars{}, FastSettings().options);
  ASSERT_TRUE(planner.ok()) << planner.status();
  const route::ObstacleField& field = planner->field();
  auto out = ShortestWayOut(field, P(0, 280));
  ASSERT_TRUE(out.has_value());
  EXPECT_FALSE(field.Inside({out->east_m, out->north_m}));
  EXPECT_GT(out->north_m, kN0 + 300);
  EXPECT_LT(std::hypot(out->east_m - kE0, out->north_m - kN0 - 280), 60);
}

TEST(ChartRoutingTest, LeadInsGoStraightOnOrTurnOnTheHullsCircle) {
  LeadInOptions o;  // 20 s reaction, 400 m radius
  const std::vector<LeadIn> c = LeadInCandidates({0, 0}, {0.0, 10.0}, M_PI, o);
  ASSERT_EQ(c.size(), 6u);
  // Straight on: 200 m (10 m/s for 20 s), then 1, 2 and 4 radii further.
  EXPECT_EQ(c[0].points.back(), (EastNorth{0, 200}));
  EXPECT_NEAR(c[3].points.back().north_m, 1800, 1e-9);
  EXPECT_DOUBLE_EQ(c[3].end_course_rad, 0.0);
  // Turned round to starboard (east) and to port (west) after 200 m.
  const LeadIn& starboard = c[4];
  EXPECT_NEAR(starboard.points.back().east_m, 800, 1e-6);
  EXPECT_NEAR(starboard.points.back().north_m, 200, 1e-6);
  EXPECT_NEAR(starboard.length_m, 200 + 400 * M_PI, 1e-6);
  for (const EastNorth& p : starboard.points) EXPECT_GE(p.east_m, -1e-9);
  const LeadIn& port = c[5];
  EXPECT_NEAR(port.points.back().east_m, -800, 1e-6);
  EXPECT_DOUBLE_EQ(port.end_course_rad, M_PI);
  for (size_t i = 2; i < port.points.size(); ++i) {
    EXPECT_NEAR(Distance(port.points[i], {-400, 200}), 400, 1e-6);
  }
}

// A ship under way north at 9 m/s, 200 m west of an island, is sent to a
// goal behind it. From rest the route would start southwards; under way it
// starts on the ship's course and turns round on the side away from the
// island (a starboard turn on a 400 m circle would cross it).
TEST(ChartRoutingTest, AShipUnderWayGetsARouteThatStartsOnItsCourse) {
  auto map = Island();
  auto planner = route::RoutePlanner::Create(map, route::ShipParticulars{}, FastSettings().options);
  ASSERT_TRUE(planner.ok()) << planner.status();
  auto shared = std::make_shared<const route::RoutePlanner>(std::move(*planner));
  ChartRouting routing(map->frame(), shared, route::Environment{});
  RouteRequest req;
  req.from_position = M(-500, 0);
  req.to_position = M(0, -1500);
  auto from_rest = routing.Plan(req, StopToken());
  ASSERT_TRUE(from_rest.ok()) << from_rest.status();
  const EastNorth first_leg = from_rest->waypoints[1].position - from_rest->waypoints[0].position;
  EXPECT_LT(first_leg.north_m, 0) << "from rest the route leads off behind the ship";

  req.start_motion = ShipMotion{0.0, 9.0};
  auto under_way = routing.Plan(req, StopToken());
  ASSERT_TRUE(under_way.ok()) << under_way.status();
  const std::vector<RouteWaypoint>& w = under_way->waypoints;
  ASSERT_GE(w.size(), 3u);
  EXPECT_EQ(w.front().position, M(-500, 0));
  const EastNorth lead = w[1].position - w[0].position;
  EXPECT_NEAR(std::atan2(lead.east_m, lead.north_m), 0.0, 1e-6) << "straight on first";
  EXPECT_GE(lead.Norm(), 9.0 * 20 - 1e-6) << "for the reaction time";
  for (const RouteWaypoint& p : w) {
    if (p.position.north_m > kN0) {
      EXPECT_LT(p.position.east_m, kE0 - 500 + 1e-6) << "turned to port";
    }
  }
  EXPECT_NEAR(w.back().position.north_m, kN0 - 1500, 1e-6);
  double length = 0;
  for (size_t i = 0; i + 1 < w.size(); ++i) {
    EXPECT_FALSE(shared->field().SegmentHits(w[i].position, w[i + 1].position)) << "leg " << i;
    length += Distance(w[i].position, w[i + 1].position);
  }
  EXPECT_NEAR(under_way->length_m, length, 1e-6);
  // A ship at rest is routed as before.
  req.start_motion = ShipMotion{0.0, 0.0};
  auto rest_again = routing.Plan(req, StopToken());
  ASSERT_TRUE(rest_again.ok());
  EXPECT_DOUBLE_EQ(rest_again->length_m, from_rest->length_m);
}

}  // namespace
}  // namespace seaplan::mission
