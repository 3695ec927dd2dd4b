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
  // Clears to a single node 0 (time zero).
  void Reset();
  int num_nodes() const { return static_cast<int>(time_.size()); }
  double time(int node) const { return time_[node]; }
  // Calls f(to, weight) for every edge t[to] >= t[node] + weight.
  template <typename F>
  void ForEachOutEdge(int node, F&& f) const {
    for (std::int32_t e = head_[node].first; e >= 0; e = edges_[e].next) {
      f(edges_[e].to, edges_[e].weight);
    }
  }

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
    std::size_t trail, edges, nodes;
  };
  // Nodes whose time propagation raised since `mark` (possibly repeated);
  // times only ever increase, so their current times are the new maxima.
  template <typename F>
  void ForEachRaisedSince(const Mark& mark, F&& f) const {
    for (std::size_t i = mark.trail; i < trail_.size(); ++i) f(trail_[i].node);
  }
  Mark GetMark() const { return {trail_.size(), edges_.size(), time_.size()}; }
  void Undo(const Mark& mark);

  // Heap bytes held (capacity, which Undo and Reset keep for reuse).
  std::size_t MemoryBytes() const;

 private:
  void PushEdge(std::int32_t from, std::int32_t to, double weight);

  std::vector<double> time_;
  std::vector<bool> fixed_;
  // Edges are added and undone last in, first out, so they live on one
  // stack, each node's outgoing ones linked from its newest. Adding an edge
  // touches the stack's top and the source's head, not a list per node:
  // an event waiting for hundreds of earlier ones (each the end of an
  // action that needed a fact over all) costs no cache miss per edge, and
  // memory is what the network holds now, not the most each node position
  // ever held.
  struct Edge {
    std::int32_t to;
    std::int32_t next;  // the source's next older edge, or -1
    double weight;
  };
  std::vector<Edge> edges_;
  // Per edge, what Undo restores: its source and the source's head target.
  struct EdgeSource {
    std::int32_t from;
    std::int32_t next_to;  // target of `next`, or -1
  };
  std::vector<EdgeSource> sources_;
  // Per node: its newest outgoing edge (-1: none) and that edge's target,
  // which tells a second edge to the node being added without reading the
  // stack.
  struct Head {
    std::int32_t first = -1;
    std::int32_t first_to = -1;
  };
  std::vector<Head> head_;
  struct TrailEntry {
    std::int32_t node;
    double old_time;
  };
  std::vector<TrailEntry> trail_;
  std::vector<std::int32_t> queue_;
};

}  // namespace seaplan::search
