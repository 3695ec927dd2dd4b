#include "seaplan/mission/mission_state.h"

#include <gtest/gtest.h>

namespace seaplan::mission {
namespace {

TEST(MissionStateTest, ReplanRoundTrip) {
  auto replanning = NextState(MissionState::kActive, MissionEvent::kReplanStarted);
  ASSERT_TRUE(replanning.ok());
  EXPECT_EQ(*replanning, MissionState::kReplanning);
  EXPECT_EQ(*NextState(*replanning, MissionEvent::kNewVersion), MissionState::kActive);
  EXPECT_EQ(*NextState(*replanning, MissionEvent::kReplanEnded), MissionState::kActive);
  EXPECT_EQ(*NextState(MissionState::kActive, MissionEvent::kReplanEnded), MissionState::kActive);
}

TEST(MissionStateTest, FinalStatesAreFinal) {
  for (MissionState s :
       {MissionState::kCompleted, MissionState::kFailed, MissionState::kCancelled}) {
    EXPECT_TRUE(IsFinal(s));
    for (MissionEvent e : {MissionEvent::kReplanStarted, MissionEvent::kNewVersion,
                           MissionEvent::kCompleted, MissionEvent::kCancelled}) {
      auto next = NextState(s, e);
      EXPECT_TRUE(absl::IsFailedPrecondition(next.status())) << MissionStateName(s);
    }
  }
  EXPECT_FALSE(IsFinal(MissionState::kActive));
  EXPECT_FALSE(IsFinal(MissionState::kReplanning));
}

TEST(MissionStateTest, EndingsFromEitherRunningState) {
  for (MissionState s : {MissionState::kActive, MissionState::kReplanning}) {
    EXPECT_EQ(*NextState(s, MissionEvent::kCompleted), MissionState::kCompleted);
    EXPECT_EQ(*NextState(s, MissionEvent::kFailed), MissionState::kFailed);
    EXPECT_EQ(*NextState(s, MissionEvent::kCancelled), MissionState::kCancelled);
  }
  EXPECT_EQ(MissionStateName(MissionState::kReplanning), "REPLANNING");
}

}  // namespace
}  // namespace seaplan::mission
