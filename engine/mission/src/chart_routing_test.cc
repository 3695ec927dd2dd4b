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

}  // namespace
}  // namespace seaplan::mission
