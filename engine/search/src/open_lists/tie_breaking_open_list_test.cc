#include "tie_breaking_open_list.h"

#include <gtest/gtest.h>

#include <vector>

namespace seaplan::search {
namespace {

struct Item {
  std::int32_t int_key;
  double real_key;
  std::int32_t id;
};

// Inserts `items` in order, then pops everything.
std::vector<std::int32_t> PopAllOf(TieBreakingOpenList::KeyOrder order,
                                   const std::vector<Item>& items) {
  TieBreakingOpenList list(order);
  for (const Item& i : items) list.Insert(i.int_key, i.real_key, i.id);
  EXPECT_EQ(list.size(), items.size());
  std::vector<std::int32_t> ids;
  while (!list.empty()) ids.push_back(list.Pop().state);
  return ids;
}

std::vector<std::int32_t> PopAll(TieBreakingOpenList& list) {
  std::vector<std::int32_t> ids;
  while (!list.empty()) ids.push_back(list.Pop().state);
  return ids;
}

TEST(TieBreakingOpenListTest, IntegerKeyFirstThenRealThenId) {
  EXPECT_EQ(
      PopAllOf(TieBreakingOpenList::KeyOrder::kIntegerFirst,
               {{2, 0.5, 0}, {1, 9.0, 1}, {1, 3.0, 2}, {1, 3.0, 3}, {-1'000'000'000, 100.0, 4}}),
      (std::vector<std::int32_t>{4, 2, 3, 1, 0}));
}

TEST(TieBreakingOpenListTest, RealKeyFirstThenIntegerThenId) {
  EXPECT_EQ(PopAllOf(TieBreakingOpenList::KeyOrder::kRealFirst,
                     {{2, 0.5, 0}, {1, 9.0, 1}, {7, 3.0, 2}, {5, 3.0, 3}, {5, 3.0, 4}}),
            (std::vector<std::int32_t>{0, 3, 4, 2, 1}));
}

TEST(TieBreakingOpenListTest, TiesComeOutInIdOrderWhateverTheInsertionOrder) {
  TieBreakingOpenList list;
  for (std::int32_t id : {5, 1, 4, 2, 3}) list.Insert(0, 0.0, id);
  EXPECT_EQ(PopAll(list), (std::vector<std::int32_t>{1, 2, 3, 4, 5}));
  EXPECT_EQ(list.MemoryBytes() % sizeof(OpenEntry), 0u);
  EXPECT_GE(list.MemoryBytes(), 5 * sizeof(OpenEntry));
}

}  // namespace
}  // namespace seaplan::search
