#include "executor.h"

#include <gtest/gtest.h>

namespace seaplan::sim {
namespace {

mission::Task MoveTask(const std::string& id, mission::Point from, mission::Point to, double start,
                       double speed) {
  mission::Task t;
  t.id = id;
  t.kind = mission::TaskKind::kMove;
  t.start_s = start;
  mission::Route r;
  mission::RouteWaypoint a, b;
  a.position = from;
  b.position = to;
  r.length_m = mission::Distance(from, to);
  r.sailing_time_s = r.length_m / speed;
  b.eta_s = r.sailing_time_s;
  r.waypoints = {a, b};
  t.route = r;
  t.duration_s = r.sailing_time_s;
  t.action.name = "move-ship";
  return t;
}

TEST(FuelTankTest, PaperPercentages) {
  FuelTank tank(FuelOptions{}, 0.30);
  tank.OnTaskCompleted(mission::TaskKind::kMove);
  EXPECT_NEAR(tank.fraction(), 0.15, 1e-12);
  tank.OnTaskCompleted(mission::TaskKind::kLoad);
  EXPECT_NEAR(tank.fraction(), 0.05, 1e-12);
  tank.OnTaskCompleted(mission::TaskKind::kRefuel);
  EXPECT_NEAR(tank.fraction(), 1.0, 1e-12);
  tank.OnTaskCompleted(mission::TaskKind::kRepair);
  EXPECT_NEAR(tank.fraction(), 0.90, 1e-12);
  tank.OnTaskCompleted(mission::TaskKind::kUnload);
  EXPECT_NEAR(tank.fraction(), 0.80, 1e-12);
  tank.OnTaskCompleted(mission::TaskKind::kOther);
  EXPECT_NEAR(tank.fraction(), 0.80, 1e-12);
  EXPECT_FALSE(tank.ran_dry());
  for (int i = 0; i < 6; ++i) tank.OnTaskCompleted(mission::TaskKind::kMove);
  EXPECT_TRUE(tank.ran_dry());
  EXPECT_EQ(tank.fraction(), 0.0);
  FuelOptions machinery;
  machinery.kind = FuelModelKind::kMachinery;
  machinery.tank_capacity_kg = 100;
  FuelTank m(machinery, 1.0);
  m.OnTaskCompleted(mission::TaskKind::kMove);  // no percentage charge
  m.Burn(25);
  EXPECT_NEAR(m.fraction(), 0.75, 1e-12);
}

TEST(ExecutorTest, RunsAMoveAndAPortOperation) {
  ExecutorConfig c;
  c.start = {0, 0};
  c.start_heading_rad = M_PI / 2;
  auto ex = Executor::Create(c);
  ASSERT_TRUE(ex.ok()) << ex.status();
  mission::PlanVersion v;
  v.version = 1;
  v.tasks.push_back(MoveTask("v1-t1", {0, 0}, {1500, 0}, 0, 4.0));
  mission::Task load;
  load.id = "v1-t2";
  load.kind = mission::TaskKind::kLoad;
  load.start_s = v.tasks[0].end_s() + 0.001;
  load.duration_s = 60;
  load.action.name = "load-cont";
  v.tasks.push_back(load);
  ex->SetPlan(v);
  std::vector<FeedbackOut> out;
  for (int i = 0; i < 10000 && !ex->Finished(); ++i) ex->Step(&out);
  ASSERT_TRUE(ex->Finished());
  EXPECT_EQ(ex->completed_task_ids().size(), 2u);
  EXPECT_NEAR(ex->position().x, 1500, 80);
  EXPECT_NEAR(ex->fuel_fraction(), 1.0 - 0.15 - 0.10, 1e-9);
  int started = 0, completed = 0;
  for (const FeedbackOut& f : out) {
    started += f.kind == mission::FeedbackKind::kTaskStarted;
    completed += f.kind == mission::FeedbackKind::kTaskCompleted;
  }
  EXPECT_EQ(started, 2);
  EXPECT_EQ(completed, 2);
  EXPECT_GE(ex->report().log.Find("load task started"), 0);
  // The move takes longer than planned (the ship accelerates from rest) but not absurdly.
  EXPECT_LT(ex->time_s(), v.tasks[1].end_s() + 400);
}

TEST(ExecutorTest, GnssJumpFailsTheMoveAtTheScriptedTime) {
  ExecutorConfig c;
  c.start = {0, 0};
  c.start_heading_rad = M_PI / 2;
  c.grid = {{0, 0}, 25.0};
  c.gnss_jumps.push_back({100, 170, {2, 0}, {30, 50}});
  auto ex = Executor::Create(c);
  ASSERT_TRUE(ex.ok());
  mission::PlanVersion v;
  v.version = 1;
  v.tasks.push_back(MoveTask("v1-t1", {0, 0}, {3000, 0}, 0, 4.0));
  ex->SetPlan(v);
  std::vector<FeedbackOut> out;
  while (ex->time_s() < 99.9) ex->Step(&out);
  for (const FeedbackOut& f : out) EXPECT_NE(f.kind, mission::FeedbackKind::kTaskFailed);
  out.clear();
  for (int i = 0; i < 4 && !ex->WaitingForPlan(); ++i) ex->Step(&out);
  ASSERT_TRUE(ex->WaitingForPlan());
  ASSERT_FALSE(out.empty());
  const FeedbackOut& failed = out.back();
  EXPECT_EQ(failed.kind, mission::FeedbackKind::kTaskFailed);
  EXPECT_EQ(failed.task_id, "v1-t1");
  EXPECT_NEAR(failed.position.x, 750, 1e-6);
  EXPECT_NEAR(failed.position.y, 1250, 1e-6);
  EXPECT_NEAR(failed.mission_time_s, 100, 0.6);
  // Nothing advances until a new plan arrives.
  double t = ex->time_s();
  ex->Step(&out);
  EXPECT_EQ(ex->time_s(), t);
}

}  // namespace
}  // namespace seaplan::sim
