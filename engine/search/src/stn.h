// A simple temporal network over event time points, kept at its earliest
// (least) solution. Edges say t[to] >= t[from] + weight. Node 0 is time
// zero. Nodes are added one at a time with their edges; AddNode propagates
// the increase (label-correcting, Bellman-Ford style, from the new node
// only, since every new edge touches it) and reports inconsistency when a
// positive cycle appears, i.e. when propagation would move time zero, a
// fixed node or the new node itself. Everything done since a Mark() can be
// undone, which the search uses to try successors on the parent's network.
//
// Why our own: the networks are small (one node per plan event), must be
// incremental and undoable per successor; no Debian library does that.
#pragma once

#include <cstdint>
#include <vector>

namespace seaplan::search {

class Stn {
 public:
  struct Edge {
    std::int32_t to;
    double weight;
  };

  // Clears to a single node 0 (time zero).
  void Reset();
  int num_nodes() const { return static_cast<int>(time_.size()); }
  double time(int node) const { return time_[node]; }
  const std::vector<Edge>& OutEdges(int node) const { return out_[node]; }

  // Adds a node fixed at `time_s` (timed initial literals). Only call
  // before any other node is added after Reset().
  int AddFixedNode(double time_s);

  // Tentative node: BeginNode(), then AddIncoming/AddOutgoing, then
  // FinishNode() which propagates; false means inconsistent (the caller
  // must Undo to the previous mark).
  int BeginNode();
  void AddIncoming(int from, double weight);  // t[new] >= t[from] + weight
  void AddOutgoing(int to, double weight);    // t[to] >= t[new] + weight
  bool FinishNode();

  struct Mark {
    std::size_t trail, edge_log, nodes;
  };
  // Nodes whose time propagation raised since `mark` (possibly repeated);
  // times only ever increase, so their current times are the new maxima.
  template <typename F>
  void ForEachRaisedSince(const Mark& mark, F&& f) const {
    for (std::size_t i = mark.trail; i < trail_.size(); ++i) f(trail_[i].node);
  }
  Mark GetMark() const { return {trail_.size(), edge_log_.size(), time_.size()}; }
  void Undo(const Mark& mark);

  // Heap bytes held, edge lists included: they keep their capacity through
  // Undo and Reset for reuse.
  std::size_t MemoryBytes() const;

 private:
  // push_back that keeps edge_capacity_ up to date.
  void Push(std::vector<Edge>& list, Edge edge);
  std::size_t edge_capacity_ = 0;  // sum of the edge lists' capacities
  std::vector<double> time_;
  std::vector<bool> fixed_;
  // Outgoing lists only: propagation reads nothing else (incoming lists,
  // kept at their largest size per node position, were most of a long
  // greedy search's memory).
  std::vector<std::vector<Edge>> out_;
  struct TrailEntry {
    std::int32_t node;
    double old_time;
  };
  std::vector<TrailEntry> trail_;
  // Nodes whose out_ got an edge to a newer node (AddIncoming). A node's
  // own edges (AddOutgoing) need no entry: its list is cleared when its
  // number is reused.
  std::vector<std::int32_t> edge_log_;
  std::vector<std::int32_t> queue_;
  std::vector<std::int32_t> touches_;
};

}  // namespace seaplan::search
