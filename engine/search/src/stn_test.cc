#include "stn.h"

#include <gtest/gtest.h>

#include <vector>

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

struct OutEdge {
  int to;
  double weight;
};
std::vector<OutEdge> OutEdges(const Stn& stn, int node) {
  std::vector<OutEdge> out;
  stn.ForEachOutEdge(node, [&](int to, double weight) { out.push_back({to, weight}); });
  return out;
}

// Memory is counted at capacity, which Undo and Reset keep, and edges are
// stored once, on one stack: a node waiting for 1,000 earlier ones holds
// 1,000 edges, and after its Undo the same room serves the next such node
// wherever it comes, so trying one at many positions of a long path does
// not add up.
TEST(StnTest, MemoryBytesHoldsTheLargestNetworkNotOnePerPosition) {
  Stn stn;
  stn.Reset();
  for (int i = 0; i < 1000; ++i) {
    stn.BeginNode();
    ASSERT_TRUE(stn.FinishNode());
  }
  const std::size_t nodes_only = stn.MemoryBytes();
  const auto wait_for_all = [&stn]() {
    const auto mark = stn.GetMark();
    const int v = stn.BeginNode();
    for (int i = 1; i < v; ++i) stn.AddIncoming(i, 1.0);
    ASSERT_TRUE(stn.FinishNode());
    stn.Undo(mark);
  };
  wait_for_all();
  const std::size_t with_edges = stn.MemoryBytes();
  EXPECT_GE(with_edges - nodes_only, 1000 * (sizeof(double) + sizeof(std::int32_t)));
  for (int k = 0; k < 10; ++k) {
    stn.BeginNode();
    ASSERT_TRUE(stn.FinishNode());
    wait_for_all();
  }
  EXPECT_LT(stn.MemoryBytes() - with_edges, 1000 * sizeof(double));
  stn.Reset();
  EXPECT_GE(stn.MemoryBytes(), with_edges);
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
  const auto edges = OutEdges(stn, a);
  ASSERT_EQ(edges.size(), 1u);
  EXPECT_EQ(edges[0].to, b);
  EXPECT_DOUBLE_EQ(edges[0].weight, 5.0);
  // Raising a later propagates the stronger weight.
  const int c = stn.BeginNode();
  stn.AddOutgoing(a, 10.0);  // t[a] >= t[c] + 10
  stn.AddIncoming(0, 1.0);
  ASSERT_TRUE(stn.FinishNode());
  EXPECT_DOUBLE_EQ(stn.time(c), 1.0);
  EXPECT_DOUBLE_EQ(stn.time(a), 11.0);
  EXPECT_DOUBLE_EQ(stn.time(b), 16.0);
  stn.Undo(mark);
  EXPECT_TRUE(OutEdges(stn, a).empty());
  EXPECT_DOUBLE_EQ(stn.time(a), 0.0);
  // A new node reusing b's number starts without b's edges.
  const int d = stn.BeginNode();
  EXPECT_EQ(d, b);
  stn.AddIncoming(a, 1.0);
  ASSERT_TRUE(stn.FinishNode());
  EXPECT_TRUE(OutEdges(stn, d).empty());
  ASSERT_EQ(OutEdges(stn, a).size(), 1u);
  EXPECT_DOUBLE_EQ(stn.time(d), 1.0);
}

}  // namespace
}  // namespace seaplan::search
