#include "stn.h"

#include <algorithm>

namespace seaplan::search {
namespace {
constexpr double kTolerance = 1e-9;
}

void Stn::Reset() {
  time_.assign(1, 0.0);
  fixed_.assign(1, true);
  edges_.clear();
  sources_.clear();
  trail_.clear();
  if (head_.empty()) head_.resize(1);
  head_[0] = Head{};
}

int Stn::AddFixedNode(double time_s) {
  const int v = num_nodes();
  time_.push_back(time_s);
  fixed_.push_back(true);
  if (head_.size() <= static_cast<std::size_t>(v)) head_.resize(static_cast<std::size_t>(v) + 1);
  head_[v] = Head{};
  return v;
}

int Stn::BeginNode() {
  const int v = num_nodes();
  time_.push_back(0.0);
  fixed_.push_back(false);
  if (head_.size() <= static_cast<std::size_t>(v)) head_.resize(static_cast<std::size_t>(v) + 1);
  head_[v] = Head{};
  return v;
}

std::size_t Stn::MemoryBytes() const {
  return edges_.capacity() * sizeof(Edge) + sources_.capacity() * sizeof(EdgeSource) +
         head_.capacity() * sizeof(Head) + time_.capacity() * sizeof(double) +
         trail_.capacity() * sizeof(TrailEntry) + queue_.capacity() * sizeof(std::int32_t);
}

void Stn::PushEdge(std::int32_t from, std::int32_t to, double weight) {
  Head& head = head_[static_cast<std::size_t>(from)];
  sources_.push_back({from, head.first_to});
  edges_.push_back({to, head.first, weight});
  head.first = static_cast<std::int32_t>(edges_.size() - 1);
  head.first_to = to;
}

void Stn::AddIncoming(int from, double weight) {
  const int v = num_nodes() - 1;
  // Every edge `from` got since v began goes to v, so a second one is its
  // newest: keep the stronger weight in it (the same least solution, one
  // edge fewer to scan). Undo drops it with v.
  const Head& head = head_[static_cast<std::size_t>(from)];
  if (head.first_to == v) {
    double& w = edges_[static_cast<std::size_t>(head.first)].weight;
    w = std::max(w, weight);
  } else {
    PushEdge(from, v, weight);
  }
  if (time_[from] + weight > time_[v]) time_[v] = time_[from] + weight;
}

void Stn::AddOutgoing(int to, double weight) {
  PushEdge(num_nodes() - 1, to, weight);
}

bool Stn::FinishNode() {
  const int v = num_nodes() - 1;
  // time_[v] already holds the max over incoming edges (and >= 0).
  queue_.clear();
  queue_.push_back(v);
  // A label-correcting pass; a positive cycle must run through v, so any
  // attempt to raise v, time zero or a fixed node is a contradiction. The
  // relaxation budget guards against pathological float drift.
  std::size_t budget =
      64 + 4 * static_cast<std::size_t>(num_nodes()) * static_cast<std::size_t>(num_nodes());
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    const int u = queue_[head];
    const double tu = time_[u];
    for (std::int32_t i = head_[u].first; i >= 0; i = edges_[i].next) {
      const Edge& e = edges_[i];
      const double candidate = tu + e.weight;
      if (candidate > time_[e.to] + kTolerance) {
        if (e.to == v || fixed_[e.to]) return false;
        if (--budget == 0) return false;
        trail_.push_back({e.to, time_[e.to]});
        time_[e.to] = candidate;
        queue_.push_back(e.to);
      }
    }
    if (queue_.size() > 1'000'000) return false;
  }
  return true;
}

void Stn::Undo(const Mark& mark) {
  while (trail_.size() > mark.trail) {
    time_[trail_.back().node] = trail_.back().old_time;
    trail_.pop_back();
  }
  while (edges_.size() > mark.edges) {
    Head& head = head_[static_cast<std::size_t>(sources_.back().from)];
    head.first = edges_.back().next;
    head.first_to = sources_.back().next_to;
    edges_.pop_back();
    sources_.pop_back();
  }
  time_.resize(mark.nodes);
  fixed_.resize(mark.nodes);
}

}  // namespace seaplan::search
