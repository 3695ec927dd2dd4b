#include "stn.h"

#include <gtest/gtest.h>

namespace seaplan::search {
namespace {

TEST(StnTest, EarliestTimesFollowLowerBounds) {
  Stn stn;
  stn.Reset();
  const int a = stn.BeginNode();
  ASSERT_TRUE(stn.FinishNode());
  const int b = stn.BeginNode();
  stn.AddIncoming(a, 5.0);
  ASSERT_TRUE(stn.FinishNode());
  EXPECT_DOUBLE_EQ(stn.time(a), 0.0);
  EXPECT_DOUBLE_EQ(stn.time(b), 5.0);
}

TEST(StnTest, UpperBoundPushesEarlierNodeLater) {
  // start s, another event x at >= 3, end e of s with duration exactly 2 must follow x.
  Stn stn;
  stn.Reset();
  const int s = stn.BeginNode();
  ASSERT_TRUE(stn.FinishNode());
  const int x = stn.BeginNode();
  stn.AddIncoming(0, 3.0);
  ASSERT_TRUE(stn.FinishNode());
  const int e = stn.BeginNode();
  stn.AddIncoming(s, 2.0);
  stn.AddIncoming(x, 0.5);
  stn.AddOutgoing(s, -2.0);
  ASSERT_TRUE(stn.FinishNode());
  EXPECT_DOUBLE_EQ(stn.time(e), 3.5);
  EXPECT_DOUBLE_EQ(stn.time(s), 1.5);
}

TEST(StnTest, PositiveCycleIsInconsistentAndUndoRestores) {
  Stn stn;
  stn.Reset();
  const int deadline = stn.AddFixedNode(4.0);
  const int s = stn.BeginNode();
  ASSERT_TRUE(stn.FinishNode());
  const auto mark = stn.GetMark();
  stn.BeginNode();
  stn.AddIncoming(s, 5.0);
  stn.AddOutgoing(deadline, 0.001);  // must happen before the fixed node at 4
  EXPECT_FALSE(stn.FinishNode());
  stn.Undo(mark);
  EXPECT_EQ(stn.num_nodes(), 3);
  EXPECT_DOUBLE_EQ(stn.time(s), 0.0);
  EXPECT_DOUBLE_EQ(stn.time(deadline), 4.0);
  // A feasible one still fits afterwards.
  stn.BeginNode();
  stn.AddIncoming(s, 3.0);
  stn.AddOutgoing(deadline, 0.001);
  EXPECT_TRUE(stn.FinishNode());
}

// The edge lists are counted at their capacity, which Undo and Reset keep.
// Each edge is stored once, in its source's list: a node waiting for 1,000
// earlier ones adds 1,000 edges (and their undo log), not twice that.
TEST(StnTest, MemoryBytesCountsEdgeListsAndKeepsThemAfterUndo) {
  Stn stn;
  stn.Reset();
  for (int i = 0; i < 1000; ++i) {
    stn.BeginNode();
    ASSERT_TRUE(stn.FinishNode());
  }
  const std::size_t nodes_only = stn.MemoryBytes();
  const auto mark = stn.GetMark();
  stn.BeginNode();
  for (int i = 1; i <= 1000; ++i) stn.AddIncoming(i, 1.0);
  ASSERT_TRUE(stn.FinishNode());
  const std::size_t with_edges = stn.MemoryBytes();
  EXPECT_GE(with_edges - nodes_only, 1000 * sizeof(Stn::Edge));
  EXPECT_LT(with_edges - nodes_only, 2000 * sizeof(Stn::Edge));
  stn.Undo(mark);
  EXPECT_EQ(stn.MemoryBytes(), with_edges);
  stn.Reset();
  EXPECT_EQ(stn.MemoryBytes(), with_edges);
}

// Two constraints between the same nodes are one edge with the larger
// weight: the same times, one edge to scan.
TEST(StnTest, ParallelEdgesKeepTheStrongerWeight) {
  Stn stn;
  stn.Reset();
  const int a = stn.BeginNode();
  ASSERT_TRUE(stn.FinishNode());
  const auto mark = stn.GetMark();
  const int b = stn.BeginNode();
  stn.AddIncoming(a, 2.0);
  stn.AddIncoming(a, 5.0);
  stn.AddIncoming(a, 1.0);
  ASSERT_TRUE(stn.FinishNode());
  EXPECT_DOUBLE_EQ(stn.time(b), 5.0);
  ASSERT_EQ(stn.OutEdges(a).size(), 1u);
  EXPECT_EQ(stn.OutEdges(a)[0].to, b);
  EXPECT_DOUBLE_EQ(stn.OutEdges(a)[0].weight, 5.0);
  // Raising a later propagates the stronger weight.
  const int c = stn.BeginNode();
  stn.AddOutgoing(a, 10.0);  // t[a] >= t[c] + 10
  stn.AddIncoming(0, 1.0);
  ASSERT_TRUE(stn.FinishNode());
  EXPECT_DOUBLE_EQ(stn.time(c), 1.0);
  EXPECT_DOUBLE_EQ(stn.time(a), 11.0);
  EXPECT_DOUBLE_EQ(stn.time(b), 16.0);
  stn.Undo(mark);
  EXPECT_TRUE(stn.OutEdges(a).empty());
  EXPECT_DOUBLE_EQ(stn.time(a), 0.0);
}

}  // namespace
}  // namespace seaplan::search
