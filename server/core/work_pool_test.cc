#include "server/core/work_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <future>

namespace seaplan::server {
namespace {

TEST(WorkPoolTest, RunsWorkAndRefusesWhenFull) {
  WorkPool pool(1);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> started{false};
  auto blocker = std::async(std::launch::async, [&] {
    return pool.Run([&] {
      started = true;
      released.wait();
    });
  });
  while (!started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  EXPECT_EQ(pool.busy(), 1);
  // Full: refused at once, the work never runs.
  bool ran = false;
  absl::Status st = pool.Run([&] { ran = true; });
  EXPECT_EQ(st.code(), absl::StatusCode::kResourceExhausted) << st;
  EXPECT_FALSE(ran);
  release.set_value();
  EXPECT_TRUE(blocker.get().ok());
  // Free again.
  EXPECT_TRUE(pool.Run([&] { ran = true; }).ok());
  EXPECT_TRUE(ran);
}

TEST(WorkPoolTest, TicksWhileWaitingAndRefusesAfterShutdown) {
  WorkPool pool(2);
  int ticks = 0;
  ASSERT_TRUE(pool.Run([] { std::this_thread::sleep_for(std::chrono::milliseconds(60)); },
                       [&] { ++ticks; }, std::chrono::milliseconds(5))
                  .ok());
  EXPECT_GE(ticks, 3);
  pool.Shutdown();
  EXPECT_EQ(pool.Run([] {}).code(), absl::StatusCode::kUnavailable);
}

TEST(WorkPoolTest, RunWhenFreeWaitsForAWorkerOrItsStopToken) {
  WorkPool pool(1);
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> started{false};
  auto blocker = std::async(std::launch::async, [&] {
    return pool.Run([&] {
      started = true;
      released.wait();
    });
  });
  while (!started) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  // Full and stopped: gives up without running the work.
  StopToken stopped;
  stopped.Cancel();
  bool ran = false;
  EXPECT_EQ(pool.RunWhenFree([&] { ran = true; }, stopped).code(), absl::StatusCode::kCancelled);
  EXPECT_FALSE(ran);
  // Full: waits, and runs once the blocker ended (alone on the one worker).
  std::atomic<int> busy_while_running{-1};
  auto waiter = std::async(std::launch::async, [&] {
    return pool.RunWhenFree(
        [&] {
          busy_while_running = pool.busy();
          ran = true;
        },
        StopToken());
  });
  release.set_value();
  EXPECT_TRUE(blocker.get().ok());
  EXPECT_TRUE(waiter.get().ok());
  EXPECT_TRUE(ran);
  EXPECT_EQ(busy_while_running.load(), 1);
  pool.Shutdown();
  EXPECT_EQ(pool.RunWhenFree([] {}, StopToken()).code(), absl::StatusCode::kUnavailable);
}

}  // namespace
}  // namespace seaplan::server
