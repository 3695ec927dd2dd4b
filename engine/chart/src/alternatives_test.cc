#include "seaplan/chart/alternatives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace seaplan::chart {
namespace {

constexpr double kCx = 500000.0, kCy = 6900000.0;
Polygon Rect(double x0, double y0, double x1, double y1) {
  return {{{kCx + x0, kCy + y0}, {kCx + x1, kCy + y0}, {kCx + x1, kCy + y1}, {kCx + x0, kCy + y1}},
          {}};
}
EastNorth P(double x, double y) {
  return {kCx + x, kCy + y};
}

ObstacleMap MakeMap(std::vector<Polygon> polygons, double buffer_m = 10.0) {
  ChartOptions o;
  o.safety_buffer_m = buffer_m;
  o.simplify_tolerance_m = 0.0;
  const LocalBox box{P(-3000, -3000), P(3000, 3000)};
  auto map =
      ObstacleMap::FromPolygons(std::move(polygons), *LocalFrame::FromEpsg(32633), o, "test", box);
  EXPECT_TRUE(map.ok()) << map.status();
  return std::move(map).value();
}

double MaxAbsY(const Alternative& a) {
  double m = 0;
  for (const EastNorth& p : a.waypoints) m = std::max(m, std::abs(p.north_m - kCy));
  return m;
}

TEST(Alternatives, SquareIslandGivesTwoSymmetricAlternatives) {
  // 100 m island, 10 m chart buffer, 50 m A1 margin: the hull reaches
  // |y| = 50 + 10 + 50 = 110 m. Start and goal 500 m either side.
  const ObstacleMap map = MakeMap({Rect(-50, -50, 50, 50)});
  AlternativesOptions options;
  options.margin_m = 50.0;
  auto result = PlanAlternatives(map, P(-500, 0), P(500, 0), options);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_FALSE(result->used_fallback);
  ASSERT_EQ(result->alternatives.size(), 2u);
  const Alternative& a = result->alternatives[0];
  const Alternative& b = result->alternatives[1];
  // One passes north (y > 0), the other south.
  auto side = [](const Alternative& alt) {
    double s = 0;
    for (const EastNorth& p : alt.waypoints) s += p.north_m - kCy;
    return s;
  };
  EXPECT_GT(side(a) * side(b) * -1.0, 0.0);
  // By hand: start -> (-50, +-110) -> (50, +-110) -> goal, corners of the
  // mitred hull lie a little outside: 2*sqrt(450^2+110^2) + 100 = 1026.5 m.
  EXPECT_NEAR(a.length_m, 1026.5, 0.03 * 1026.5);
  EXPECT_NEAR(a.length_m, b.length_m, 1e-6 * a.length_m);
  EXPECT_GE(MaxAbsY(a), 110.0 - 1e-6);
  EXPECT_LE(MaxAbsY(a), 140.0);
  for (const Alternative& alt : result->alternatives) {
    EXPECT_EQ(alt.waypoints.front(), P(-500, 0));
    EXPECT_EQ(alt.waypoints.back(), P(500, 0));
    ObstacleQuery q(map);
    EXPECT_FALSE(q.PolylineHits(alt.waypoints));
    // Clearance from the (buffered) obstacle is about the margin everywhere.
    for (size_t i = 1; i + 1 < alt.waypoints.size(); ++i)
      EXPECT_GE(q.DistanceM(alt.waypoints[i]), 45.0);
  }
}

TEST(Alternatives, FreeLineIsTheOnlyAlternative) {
  const ObstacleMap map = MakeMap({Rect(-50, 500, 50, 600)});
  auto result = PlanAlternatives(map, P(-500, 0), P(500, 0));
  ASSERT_TRUE(result.ok()) << result.status();
  ASSERT_EQ(result->alternatives.size(), 1u);
  EXPECT_EQ(result->alternatives[0].waypoints.size(), 2u);
  EXPECT_NEAR(result->alternatives[0].length_m, 1000.0, 1e-9);
}

TEST(Alternatives, TwoIslandsRecursion) {
  const ObstacleMap map = MakeMap({Rect(-250, -50, -150, 50), Rect(150, -80, 250, 20)});
  auto result = PlanAlternatives(map, P(-700, 0), P(700, 0));
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_GE(result->alternatives.size(), 2u);
  ObstacleQuery q(map);
  for (size_t i = 0; i < result->alternatives.size(); ++i) {
    const Alternative& alt = result->alternatives[i];
    EXPECT_FALSE(q.PolylineHits(alt.waypoints));
    if (i > 0) {
      EXPECT_GE(alt.length_m, result->alternatives[i - 1].length_m);  // sorted
    }
  }
}

TEST(Alternatives, StartOrGoalInsideObstacleIsNamed) {
  const ObstacleMap map = MakeMap({Rect(-50, -50, 50, 50)});
  auto start_in = PlanAlternatives(map, P(0, 0), P(500, 0));
  ASSERT_EQ(start_in.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(start_in.status().message().find("start"), absl::string_view::npos);
  EXPECT_NE(start_in.status().message().find("inside obstacle 0"), absl::string_view::npos);
  // Where, in latitude and longitude (the local frame is internal).
  EXPECT_NE(start_in.status().message().find(FormatLatLon(map.frame().ToLatLon(P(0, 0)))),
            absl::string_view::npos)
      << start_in.status().message();
  // Within the 10 m safety buffer counts as inside.
  auto goal_in = PlanAlternatives(map, P(-500, 0), P(55, 0));
  ASSERT_EQ(goal_in.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(goal_in.status().message().find("goal"), absl::string_view::npos);
  auto outside = PlanAlternatives(map, P(-500, 0), P(5000, 0));
  ASSERT_EQ(outside.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(outside.status().message().find("outside the chart coverage"), absl::string_view::npos);
}

TEST(Alternatives, StartInsideConcaveBayUsesFallbackAndAvoidsObstacles) {
  // A U-shaped harbour open to the north; start inside the bay, goal south.
  // The hull of the U swallows the start, so pure A1 cannot answer.
  const ObstacleMap map = MakeMap(
      {Rect(-500, -500, 500, -300), Rect(-500, -300, -300, 500), Rect(300, -300, 500, 500)});
  auto result = PlanAlternatives(map, P(0, 0), P(0, -1200));
  ASSERT_TRUE(result.ok()) << result.status();
  ASSERT_FALSE(result->alternatives.empty());
  EXPECT_FALSE(result->note.empty());
  ObstacleQuery q(map);
  for (const Alternative& alt : result->alternatives) {
    EXPECT_FALSE(q.PolylineHits(alt.waypoints));
    // It must leave the bay to the north (y > 500 + buffer) to get around.
    double max_y = -1e9;
    for (const EastNorth& p : alt.waypoints) max_y = std::max(max_y, p.north_m - kCy);
    EXPECT_GT(max_y, 510.0);
    // And is not absurdly long: out (~560) + around a side (~1000) + down.
    EXPECT_LT(alt.length_m, 4500.0);
  }
  // The fallback's second alternative goes round the other side of the U:
  // by symmetry both have the same length and mirrored x.
  ASSERT_EQ(result->alternatives.size(), 2u) << result->note;
  EXPECT_TRUE(result->used_fallback);
  EXPECT_NEAR(result->alternatives[0].length_m, result->alternatives[1].length_m, 1.0);
  auto east = [](const Alternative& alt) {
    double s = 0;
    for (const EastNorth& p : alt.waypoints) s += p.east_m - kCx;
    return s;
  };
  EXPECT_LT(east(result->alternatives[0]) * east(result->alternatives[1]), 0.0);
}

TEST(Alternatives, UnreachableGoalIsNotFound) {
  // The goal sits in a closed ring-shaped lagoon.
  Polygon ring = Rect(-400, -400, 400, 400);
  ring.holes.push_back(Rect(-200, -200, 200, 200).outer);
  const ObstacleMap map = MakeMap({ring});
  auto result = PlanAlternatives(map, P(-1000, 0), P(0, 0));
  EXPECT_EQ(result.status().code(), absl::StatusCode::kNotFound) << result.status();
}

TEST(Alternatives, StopTokenEndsTheSearch) {
  const ObstacleMap map = MakeMap({Rect(-50, -50, 50, 50)});
  AlternativesOptions options;
  options.stop = StopToken::WithTimeout(std::chrono::seconds(0));
  EXPECT_EQ(PlanAlternatives(map, P(-500, 0), P(500, 0), options).status().code(),
            absl::StatusCode::kDeadlineExceeded);
  options.stop = StopToken();
  options.stop.Cancel();
  EXPECT_EQ(PlanAlternatives(map, P(-500, 0), P(500, 0), options).status().code(),
            absl::StatusCode::kCancelled);
}

TEST(Alternatives, OptionsAreValidated) {
  const ObstacleMap map = MakeMap({Rect(-50, -50, 50, 50)});
  AlternativesOptions bad;
  bad.margin_m = -1;
  EXPECT_EQ(PlanAlternatives(map, P(-500, 0), P(500, 0), bad).status().code(),
            absl::StatusCode::kInvalidArgument);
  bad = {};
  bad.max_depth = 0;
  EXPECT_FALSE(bad.Validate().ok());
}

}  // namespace
}  // namespace seaplan::chart
