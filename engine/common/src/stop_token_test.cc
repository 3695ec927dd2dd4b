#include "seaplan/common/stop_token.h"

#include <gtest/gtest.h>

#include <thread>

namespace seaplan {
namespace {

TEST(StopTokenTest, DefaultNeverStops) {
  StopToken token;
  EXPECT_EQ(token.Reason(), StopReason::kNone);
}

TEST(StopTokenTest, CancelIsSharedByCopies) {
  StopToken token;
  // NOLINTNEXTLINE(performance-unnecessary-copy-initialization): the copy is what is tested.
  StopToken copy = token;
  copy.Cancel();
  EXPECT_EQ(token.Reason(), StopReason::kCancelled);
}

TEST(StopTokenTest, DeadlinePasses) {
  auto token = StopToken::WithTimeout(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(token.Reason(), StopReason::kDeadline);
}

TEST(StopTokenTest, ChildSeesParentCancelButNotViceVersa) {
  StopToken parent;
  StopToken child = parent.Child(StopToken::Clock::time_point::max());
  child.Cancel();
  EXPECT_EQ(parent.Reason(), StopReason::kNone);
  StopToken child2 = parent.Child(StopToken::Clock::time_point::max());
  parent.Cancel();
  EXPECT_EQ(child2.Reason(), StopReason::kCancelled);
}

TEST(StopTokenTest, HugeTimeoutDoesNotOverflow) {
  auto token = StopToken::WithTimeout(std::chrono::duration<double>(1e30));
  EXPECT_EQ(token.Reason(), StopReason::kNone);
}

}  // namespace
}  // namespace seaplan
