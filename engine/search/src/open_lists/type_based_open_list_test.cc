#include "type_based_open_list.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <vector>

namespace seaplan::search {
namespace {

std::vector<std::int32_t> PopAll(TypeBasedOpenList& list) {
  std::vector<std::int32_t> ids;
  while (!list.empty()) ids.push_back(list.Pop());
  return ids;
}

TEST(TypeBasedOpenListTest, PopsEveryEntryOnceAndDropsEmptiedTypes) {
  TypeBasedOpenList list(1);
  // Three types: (5, 1) with ids 0-2, (5, 2) with 3, (7, 1) with 4-5.
  list.Insert(5, 1, 0);
  list.Insert(5, 1, 1);
  list.Insert(5, 2, 3);
  list.Insert(7, 1, 4);
  list.Insert(5, 1, 2);
  list.Insert(7, 1, 5);
  EXPECT_EQ(list.size(), 6u);
  EXPECT_EQ(list.num_types(), 3u);
  EXPECT_GT(list.MemoryBytes(), 6 * sizeof(std::int32_t));
  std::vector<std::int32_t> ids = PopAll(list);
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(ids, (std::vector<std::int32_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(list.num_types(), 0u);
  // Usable again after being emptied.
  list.Insert(-1, 0, 9);
  EXPECT_EQ(list.num_types(), 1u);
  EXPECT_EQ(list.Pop(), 9);
  EXPECT_TRUE(list.empty());
}

TEST(TypeBasedOpenListTest, SameSeedSamePopsOtherSeedOtherPops) {
  const auto pops = [](std::uint64_t seed) {
    TypeBasedOpenList list(seed);
    for (std::int32_t id = 0; id < 200; ++id) list.Insert(id % 7, id % 3, id);
    return PopAll(list);
  };
  EXPECT_EQ(pops(3), pops(3));
  EXPECT_NE(pops(3), pops(4));
}

// The type is chosen uniformly, not the entry: one entry alone in its type
// comes out first about as often as any one of the other type's 99 entries
// together, where a uniform pick among entries would take it first 1 time
// in 100.
TEST(TypeBasedOpenListTest, ChoosesTheTypeUniformlyThenTheEntry) {
  int lone_first = 0;
  std::map<std::int32_t, int> crowd_first;
  const int runs = 2000;
  for (int run = 0; run < runs; ++run) {
    TypeBasedOpenList list(static_cast<std::uint64_t>(run) + 1);
    for (std::int32_t id = 0; id < 99; ++id) list.Insert(10, 4, id);
    list.Insert(30, 1, 99);
    const std::int32_t first = list.Pop();
    if (first == 99) {
      ++lone_first;
    } else {
      ++crowd_first[first];
    }
  }
  // Binomial(2000, 1/2): mean 1000, standard deviation about 22.
  EXPECT_GT(lone_first, 850);
  EXPECT_LT(lone_first, 1150);
  // Within the crowd, no entry is favoured: each was first about
  // 1000 / 99 times, and most of them at least once.
  EXPECT_GT(crowd_first.size(), 80u);
  for (const auto& [id, count] : crowd_first) EXPECT_LT(count, 40) << id;
}

// MemoryBytes keeps a running sum of the buckets' capacities: the ids'
// bytes are counted while held and given back when their types empty.
TEST(TypeBasedOpenListTest, MemoryBytesCountsTheIdsHeld) {
  TypeBasedOpenList list(7);
  const std::size_t empty_bytes = list.MemoryBytes();
  for (std::int32_t id = 0; id < 3000; ++id) list.Insert(id % 50, id % 7, id);
  const std::size_t full_bytes = list.MemoryBytes();
  EXPECT_GE(full_bytes, empty_bytes + 3000 * sizeof(std::int32_t));
  PopAll(list);
  EXPECT_EQ(list.num_types(), 0u);
  // The bucket table and hash map keep their capacity; the ids' slots go.
  EXPECT_LE(list.MemoryBytes() + 3000 * sizeof(std::int32_t), full_bytes);
  for (std::int32_t id = 0; id < 100; ++id) list.Insert(1, 1, id);
  EXPECT_GE(list.MemoryBytes(), 100 * sizeof(std::int32_t));
}

}  // namespace
}  // namespace seaplan::search
