#include "server/core/work_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <future>
#include <vector>

#include "server/core/status_details.h"

namespace seaplan::server {
namespace {

// Occupies every worker of `pool` until `release` is set.
std::vector<std::future<absl::Status>> Occupy(WorkPool& pool, int count,
                                              const std::shared_future<void>& released) {
  std::atomic<int> started{0};
  std::vector<std::future<absl::Status>> blockers;
  blockers.reserve(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    blockers.push_back(std::async(std::launch::async, [&pool, &started, released] {
      return pool.Run(
          [&started, released] {
            ++started;
            released.wait();
          },
          StopToken());
    }));
  }
  while (started.load() < count) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return blockers;
}

TEST(WorkPoolTest, RunsWorkAndRefusesWhenFullWithoutQueue) {
  WorkPool pool(1);
  std::promise<void> release;
  auto blockers = Occupy(pool, 1, release.get_future().share());
  EXPECT_EQ(pool.busy(), 1);
  // Full and no queue: refused at once, the work never runs.
  bool ran = false;
  absl::Status st = pool.Run([&] { ran = true; }, StopToken());
  EXPECT_EQ(st.code(), absl::StatusCode::kResourceExhausted) << st;
  EXPECT_TRUE(GetRetryAfter(st).has_value());
  EXPECT_FALSE(ran);
  release.set_value();
  EXPECT_TRUE(blockers[0].get().ok());
  // Free again.
  EXPECT_TRUE(pool.Run([&] { ran = true; }, StopToken()).ok());
  EXPECT_TRUE(ran);
}

TEST(WorkPoolTest, QueuedCallsWaitInOrderAndBeyondTheBoundAreRefused) {
  WorkPool pool(1, /*max_waiting=*/2);
  std::promise<void> release;
  auto blockers = Occupy(pool, 1, release.get_future().share());
  std::mutex order_mu;
  std::vector<int> order;
  std::vector<std::future<absl::Status>> queued;
  for (int i = 0; i < 2; ++i) {
    queued.push_back(std::async(std::launch::async, [&, i] {
      return pool.Run(
          [&, i] {
            std::lock_guard lock(order_mu);
            order.push_back(i);
          },
          StopToken());
    }));
    // The next one queues behind this one.
    while (pool.waiting() < i + 1) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  // The queue is full: the third is refused at once.
  const absl::Status refused = pool.Run([] {}, StopToken());
  EXPECT_EQ(refused.code(), absl::StatusCode::kResourceExhausted) << refused;
  EXPECT_NE(refused.message().find("waiting"), std::string_view::npos) << refused;
  release.set_value();
  EXPECT_TRUE(blockers[0].get().ok());
  for (auto& q : queued) EXPECT_TRUE(q.get().ok());
  EXPECT_EQ(order, (std::vector<int>{0, 1}));
  EXPECT_EQ(pool.waiting(), 0);
}

TEST(WorkPoolTest, AWaitingCallGivesUpWhenItsTokenStopsAndTicksMeanwhile) {
  WorkPool pool(1, /*max_waiting=*/4);
  std::promise<void> release;
  auto blockers = Occupy(pool, 1, release.get_future().share());
  StopToken stop;
  std::atomic<int> ticks{0};
  bool ran = false;
  auto waiter = std::async(std::launch::async, [&] {
    return pool.Run([&] { ran = true; }, stop, [&] { ++ticks; }, std::chrono::milliseconds(2));
  });
  while (ticks.load() < 3) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  stop.Cancel();
  EXPECT_EQ(waiter.get().code(), absl::StatusCode::kCancelled);
  EXPECT_FALSE(ran);
  EXPECT_EQ(pool.waiting(), 0);
  release.set_value();
  EXPECT_TRUE(blockers[0].get().ok());
}

TEST(WorkPoolTest, TicksWhileWorkingAndRefusesAfterShutdown) {
  WorkPool pool(2);
  int ticks = 0;
  ASSERT_TRUE(pool.Run([] { std::this_thread::sleep_for(std::chrono::milliseconds(60)); },
                       StopToken(), [&] { ++ticks; }, std::chrono::milliseconds(5))
                  .ok());
  EXPECT_GE(ticks, 3);
  pool.Shutdown();
  EXPECT_EQ(pool.Run([] {}, StopToken()).code(), absl::StatusCode::kUnavailable);
}

TEST(WorkPoolTest, RunWhenFreeWaitsForAWorkerOrItsStopTokenWhateverTheQueueBound) {
  WorkPool pool(1, /*max_waiting=*/0);
  std::promise<void> release;
  auto blockers = Occupy(pool, 1, release.get_future().share());
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
  EXPECT_TRUE(blockers[0].get().ok());
  EXPECT_TRUE(waiter.get().ok());
  EXPECT_TRUE(ran);
  EXPECT_EQ(busy_while_running.load(), 1);
  pool.Shutdown();
  EXPECT_EQ(pool.RunWhenFree([] {}, StopToken()).code(), absl::StatusCode::kUnavailable);
}

}  // namespace
}  // namespace seaplan::server
