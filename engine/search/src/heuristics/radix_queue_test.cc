#include "radix_queue.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <random>
#include <vector>

namespace seaplan::search {
namespace {

TEST(RadixTimeQueueTest, PopsInTimeOrder) {
  RadixTimeQueue queue;
  const std::vector<double> times = {7.5, 0.0, 1e-9, 3.0, 1e6, 0.001, 3.0, 2.9999999};
  for (std::size_t i = 0; i < times.size(); ++i) queue.Push(times[i], static_cast<int>(i));
  EXPECT_EQ(queue.size(), times.size());
  std::vector<double> popped;
  while (!queue.empty()) popped.push_back(queue.Pop().time_s);
  std::vector<double> sorted = times;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(popped, sorted);
}

TEST(RadixTimeQueueTest, KeepsEachIdWithItsTime) {
  RadixTimeQueue queue;
  queue.Push(2.0, 20);
  queue.Push(1.0, 10);
  queue.Push(3.0, 30);
  for (int expected : {10, 20, 30}) {
    const RadixTimeQueue::Entry e = queue.Pop();
    EXPECT_EQ(e.id, expected);
    EXPECT_EQ(e.time_s, expected / 10.0);
  }
}

// A Dijkstra-like use: pushes between pops, never before the last popped
// time. Checked against a sorted multiset of the same times.
TEST(RadixTimeQueueTest, MonotonePushesBetweenPopsMatchASortedReference) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> step(0.0, 50.0);
  std::uniform_int_distribution<int> count(0, 4);
  RadixTimeQueue queue;
  for (int round = 0; round < 3; ++round) {
    queue.Clear();
    std::vector<double> reference;  // the queue's times
    for (int i = 0; i < 20; ++i) {
      const double t = step(rng);
      queue.Push(t, i);
      reference.push_back(t);
    }
    double now = 0.0;
    int next_id = 100;
    while (!queue.empty()) {
      std::sort(reference.begin(), reference.end(), std::greater<>());
      const RadixTimeQueue::Entry e = queue.Pop();
      ASSERT_EQ(e.time_s, reference.back());
      reference.pop_back();
      ASSERT_GE(e.time_s, now);
      now = e.time_s;
      for (int k = count(rng); k > 0 && next_id < 2000; --k) {
        // Some at the popped time itself, most later.
        const double t = (next_id % 5 == 0) ? now : now + step(rng);
        queue.Push(t, next_id++);
        reference.push_back(t);
      }
      ASSERT_EQ(queue.size(), reference.size());
    }
    EXPECT_TRUE(reference.empty());
    EXPECT_GT(next_id, 1000);  // the pushes between pops did happen
  }
}

TEST(RadixTimeQueueTest, ClearStartsAgainFromTimeZero) {
  RadixTimeQueue queue;
  queue.Push(100.0, 1);
  queue.Push(200.0, 2);
  EXPECT_EQ(queue.Pop().id, 1);
  queue.Clear();
  EXPECT_TRUE(queue.empty());
  // Earlier than anything popped before the Clear.
  queue.Push(5.0, 3);
  queue.Push(0.5, 4);
  EXPECT_EQ(queue.Pop().id, 4);
  EXPECT_EQ(queue.Pop().id, 3);
  EXPECT_TRUE(queue.empty());
}

}  // namespace
}  // namespace seaplan::search
