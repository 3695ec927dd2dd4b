#include "stn.h"

#include <algorithm>

namespace seaplan::search {
namespace {
constexpr double kTolerance = 1e-9;
}

void Stn::Reset() {
  // Keep the per-node edge vectors (and their capacity) for reuse.
  time_.assign(1, 0.0);
  fixed_.assign(1, true);
  if (out_.empty()) out_.resize(1);
  out_[0].clear();
  trail_.clear();
  edge_log_.clear();
}

int Stn::AddFixedNode(double time_s) {
  const int v = num_nodes();
  time_.push_back(time_s);
  fixed_.push_back(true);
  if (out_.size() <= static_cast<std::size_t>(v)) out_.emplace_back();
  out_[v].clear();
  return v;
}

int Stn::BeginNode() {
  const int v = num_nodes();
  time_.push_back(0.0);
  fixed_.push_back(false);
  if (out_.size() <= static_cast<std::size_t>(v)) out_.emplace_back();
  out_[v].clear();
  return v;
}

void Stn::Push(std::vector<Edge>& list, Edge edge) {
  const std::size_t before = list.capacity();
  list.push_back(edge);
  edge_capacity_ += list.capacity() - before;
}

std::size_t Stn::MemoryBytes() const {
  return edge_capacity_ * sizeof(Edge) + out_.capacity() * sizeof(std::vector<Edge>) +
         time_.capacity() * sizeof(double) + trail_.capacity() * sizeof(TrailEntry) +
         (edge_log_.capacity() + queue_.capacity() + touches_.capacity()) * sizeof(std::int32_t);
}

void Stn::AddIncoming(int from, double weight) {
  const int v = num_nodes() - 1;
  // Every edge `from` got since v began goes to v, so a second one is the
  // list's last: keep the stronger weight in it (the same least solution,
  // one edge fewer to scan). Undo drops it with v.
  std::vector<Edge>& list = out_[from];
  if (!list.empty() && list.back().to == v) {
    list.back().weight = std::max(list.back().weight, weight);
  } else {
    Push(list, {v, weight});
    edge_log_.push_back(from);
  }
  if (time_[from] + weight > time_[v]) time_[v] = time_[from] + weight;
}

void Stn::AddOutgoing(int to, double weight) {
  const int v = num_nodes() - 1;
  Push(out_[v], {to, weight});
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
    for (const Edge& e : out_[u]) {
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
  while (edge_log_.size() > mark.edge_log) {
    out_[static_cast<std::size_t>(edge_log_.back())].pop_back();
    edge_log_.pop_back();
  }
  time_.resize(mark.nodes);
  fixed_.resize(mark.nodes);
}

}  // namespace seaplan::search
