#include "tie_breaking_open_list.h"

#include <gtest/gtest.h>

#include <vector>

namespace seaplan::search {
namespace {

std::vector<std::int32_t> PopAll(TieBreakingOpenList& list) {
  std::vector<std::int32_t> ids;
  while (!list.empty()) ids.push_back(list.Pop().state);
  return ids;
}

TEST(TieBreakingOpenListTest, IntegerKeyFirstThenRealThenId) {
  TieBreakingOpenList list(TieBreakingOpenList::KeyOrder::kIntegerFirst);
  list.Insert(2, 0.5, 0);
  list.Insert(1, 9.0, 1);
  list.Insert(1, 3.0, 2);
  list.Insert(1, 3.0, 3);
  list.Insert(-1'000'000'000, 100.0, 4);
  EXPECT_EQ(list.size(), 5u);
  EXPECT_EQ(PopAll(list), (std::vector<std::int32_t>{4, 2, 3, 1, 0}));
}

TEST(TieBreakingOpenListTest, RealKeyFirstThenIntegerThenId) {
  TieBreakingOpenList list(TieBreakingOpenList::KeyOrder::kRealFirst);
  list.Insert(2, 0.5, 0);
  list.Insert(1, 9.0, 1);
  list.Insert(7, 3.0, 2);
  list.Insert(5, 3.0, 3);
  list.Insert(5, 3.0, 4);
  EXPECT_EQ(PopAll(list), (std::vector<std::int32_t>{0, 3, 4, 2, 1}));
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
