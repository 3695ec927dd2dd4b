// A server process killed while a mission was REPLANNING leaves it so in the
// database with no replan running anywhere: the next coordinator over that
// database (the restarted server) must run the replan, or the ship waits
// for a plan version forever.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "server/core/mission_coordinator.h"
#include "server/core/work_pool.h"
#include "test_support.h"

namespace seaplan::server::testing {
namespace {

TEST(ReplanResumeTest, MissionLeftReplanningByADeadProcessIsReplannedAtStart) {
  auto engine = std::make_shared<FakeMissionEngine>();
  InProcessServer s(engine);
  auto missions = v1::MissionService::NewStub(s.channel());
  v1::CreateMissionRequest create;
  *create.mutable_spec() = SampleSpec();
  v1::Mission m;
  {
    grpc::ClientContext ctx;
    SetDeadline(&ctx, 30000);
    grpc::Status st = missions->CreateMission(&ctx, create, &m);
    ASSERT_TRUE(st.ok()) << st.error_message();
  }
  ASSERT_EQ(m.current_version(), 1);
  // What a process killed after a report triggered a replan leaves behind.
  storage::MissionUpdate replanning;
  replanning.state = v1::MISSION_STATE_REPLANNING;
  ASSERT_TRUE(s.store().missions().Update(m.mission_id(), replanning, {}).ok());
  EXPECT_EQ(engine->replan_calls.load(), 0);

  WorkPool pool(1);
  MissionCoordinator restarted(s.store().missions(), pool, StopToken(), engine);
  storage::MissionRecord record;
  for (int i = 0; i < 1000; ++i) {
    auto r = s.store().missions().Get(m.mission_id());
    ASSERT_TRUE(r.ok()) << r.status();
    record = *r;
    if (record.current_version == 2) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_EQ(record.current_version, 2);
  EXPECT_EQ(record.state, v1::MISSION_STATE_ACTIVE);
  EXPECT_EQ(engine->replan_calls.load(), 1);
  auto v2 = s.store().missions().GetVersion(m.mission_id(), 2);
  ASSERT_TRUE(v2.ok()) << v2.status();
  EXPECT_EQ(v2->reason, "replan resumed after a server restart");
  restarted.Shutdown();
}

}  // namespace
}  // namespace seaplan::server::testing
