#include "timeline.h"

#include <algorithm>
#include <cmath>

namespace seaplan::search {

Timeline::Timeline(const SnapTask& task, double epsilon_s, bool bound_concurrency)
    : task_(task),
      epsilon_s_(epsilon_s),
      last_writer_(static_cast<std::size_t>(task.num_facts()), -1),
      readers_(static_cast<std::size_t>(task.num_facts())),
      var_last_writer_(static_cast<std::size_t>(task.num_vars()), -1),
      var_readers_(static_cast<std::size_t>(task.num_vars())),
      inv_readers_(static_cast<std::size_t>(task.num_facts())),
      var_inv_readers_(static_cast<std::size_t>(task.num_vars())),
      open_start_(static_cast<std::size_t>(task.num_actions()), -1),
      open_min_duration_(static_cast<std::size_t>(task.num_actions()), 0.0),
      open_max_duration_(static_cast<std::size_t>(task.num_actions()), 0.0),
      bound_concurrency_(bound_concurrency),
      open_deleters_(static_cast<std::size_t>(task.num_facts())),
      open_needers_(static_cast<std::size_t>(task.num_facts())) {}

void Timeline::ResetTables() {
  for (auto f : touched_facts_) {
    last_writer_[f] = -1;
    readers_[f].clear();
    inv_readers_[f].clear();
  }
  for (auto v : touched_vars_) {
    var_last_writer_[v] = -1;
    var_readers_[v].clear();
    var_inv_readers_[v].clear();
  }
  touched_facts_.clear();
  touched_vars_.clear();
  for (auto a : open_actions_) open_start_[a] = -1;
  open_actions_.clear();
  for (auto f : envelope_touched_) {
    open_deleters_[f].clear();
    open_needers_[f].clear();
  }
  envelope_touched_.clear();
  end_nodes_.clear();
}

bool Timeline::Build(std::span<const Event> events) {
  ResetTables();
  stn_.Reset();
  is_action_node_.assign(1, false);
  for (const auto& til : task_.tils()) {
    stn_.AddFixedNode(til.time_s);
    is_action_node_.push_back(false);
  }
  num_events_ = 0;
  next_til_ = 0;
  bool ok = true;
  for (const Event& e : events) {
    if (!AddToStn(e)) ok = false;  // keep going so tables stay coherent
    Commit(e, EventNode(num_events_));
    ++num_events_;
  }
  path_makespan_s_ = Current().makespan_s;
  return ok;
}

void Timeline::Keep(const Event& event) {
  Commit(event, EventNode(num_events_));
  ++num_events_;
  path_makespan_s_ = tentative_makespan_s_;
}

bool Timeline::AddToStn(const Event& event) {
  if (event.is_til()) {
    // Already a fixed node; its orderings were added when the earlier
    // events were (the pending-literal rule). Keep node numbering dense.
    const int node = stn_.BeginNode();
    is_action_node_.resize(static_cast<std::size_t>(node) + 1);
    is_action_node_[node] = false;
    // Alias node: equal to the literal's fixed node.
    stn_.AddIncoming(TilNode(event.til()), 0.0);
    stn_.AddOutgoing(TilNode(event.til()), 0.0);
    return stn_.FinishNode();
  }
  const SnapAction& snap = task_.snap(event.snap);
  const int node = stn_.BeginNode();
  is_action_node_.resize(static_cast<std::size_t>(node) + 1);
  is_action_node_[node] = true;
  const double eps = epsilon_s_;
  for (auto f : snap.reads) {
    if (last_writer_[f] >= 0) stn_.AddIncoming(last_writer_[f], eps);
  }
  for (auto f : snap.writes) {
    if (last_writer_[f] >= 0) stn_.AddIncoming(last_writer_[f], eps);
    for (auto r : readers_[f]) stn_.AddIncoming(r, eps);
    for (auto r : inv_readers_[f]) stn_.AddIncoming(r, 0.0);
  }
  for (auto v : snap.num_reads) {
    if (var_last_writer_[v] >= 0) stn_.AddIncoming(var_last_writer_[v], eps);
  }
  for (auto v : snap.num_writes) {
    if (var_last_writer_[v] >= 0) stn_.AddIncoming(var_last_writer_[v], eps);
    for (auto r : var_readers_[v]) stn_.AddIncoming(r, eps);
    for (auto r : var_inv_readers_[v]) stn_.AddIncoming(r, 0.0);
  }
  if (!snap.is_end) {
    // The invariant must hold right after the start's happening: its
    // achiever may share that happening (the start does not read it).
    for (auto f : snap.inv_reads) {
      if (last_writer_[f] >= 0) stn_.AddIncoming(last_writer_[f], 0.0);
    }
    for (auto v : snap.inv_num_reads) {
      if (var_last_writer_[v] >= 0) stn_.AddIncoming(var_last_writer_[v], 0.0);
    }
  }
  // Literals not yet applied come after this event when they interfere.
  const auto& tils = task_.tils();
  if (!tils.empty()) {
    auto pending = [&](const std::vector<int>& list) {
      for (auto k : list) {
        if (k >= next_til_) stn_.AddOutgoing(TilNode(k), eps);
      }
    };
    for (auto f : snap.reads) pending(task_.TilsWritingFact(f));
    for (auto f : snap.writes) pending(task_.TilsWritingFact(f));
    for (auto v : snap.num_reads) pending(task_.TilsWritingVar(v));
    for (auto v : snap.num_writes) pending(task_.TilsWritingVar(v));
    if (snap.is_end) {
      // A literal still to come may change the invariant only from the end on.
      auto pending_inv = [&](const std::vector<int>& list) {
        for (auto k : list) {
          if (k >= next_til_) stn_.AddOutgoing(TilNode(k), 0.0);
        }
      };
      for (auto f : snap.inv_reads) pending_inv(task_.TilsWritingFact(f));
      for (auto v : snap.inv_num_reads) pending_inv(task_.TilsWritingVar(v));
    }
  }
  if (bound_concurrency_ && !snap.is_end) {
    for (auto n : end_nodes_) stn_.AddIncoming(n, eps);
  }
  AddEnvelopeEdges(event, snap);
  if (snap.is_end) {
    const int start = open_start_[snap.action];
    if (start >= 0) {
      // The start's bounds were recorded with the start event.
      stn_.AddIncoming(start, open_min_duration_[snap.action]);
      const double max_d = event.max_duration_s;
      if (max_d < kInfinity) stn_.AddOutgoing(start, -max_d);
    }
  }
  return stn_.FinishNode();
}

void Timeline::AddEnvelopeEdges(const Event& event, const SnapAction& snap) {
  const InvariantEnvelopes& env = task_.envelopes();
  const task::ActionId x = snap.action;
  if (!task_.task().actions[x].is_durative) return;
  // x inside a running y: end(x) <= end(y) <= start(y) + max_dur(y); at the
  // start of x, through start(x) + min_dur(x) <= end(x).
  const double x_min = snap.is_end ? 0.0 : event.min_duration_s;
  for (auto f : env.EnclosedNeeds(x)) {
    for (auto y : open_deleters_[f]) {
      if (y == x || !(open_max_duration_[y] < kInfinity)) continue;
      stn_.AddOutgoing(open_start_[y], x_min - open_max_duration_[y]);
    }
  }
  if (snap.is_end || !(event.max_duration_s < kInfinity)) return;
  // A running y inside x, which starts now: start(y) + min_dur(y) <= end(y) <= end(x).
  for (auto f : env.EndDeletes(x)) {
    for (auto y : open_needers_[f]) {
      if (y == x) continue;
      stn_.AddIncoming(open_start_[y], open_min_duration_[y] - event.max_duration_s);
    }
  }
}

void Timeline::TrackEnvelopes(task::ActionId a, bool started) {
  const InvariantEnvelopes& env = task_.envelopes();
  auto update = [&](std::vector<std::vector<task::ActionId>>& lists,
                    const std::vector<task::FactId>& facts) {
    for (auto f : facts) {
      auto& list = lists[f];
      if (started) {
        if (open_deleters_[f].empty() && open_needers_[f].empty()) envelope_touched_.push_back(f);
        list.push_back(a);
      } else {
        list.erase(std::find(list.begin(), list.end(), a));
      }
    }
  };
  update(open_deleters_, env.EndDeletes(a));
  update(open_needers_, env.EnclosedNeeds(a));
}

void Timeline::Commit(const Event& event, int node) {
  auto fact_fresh = [&](task::FactId f) {
    return last_writer_[f] < 0 && readers_[f].empty() && inv_readers_[f].empty();
  };
  auto var_fresh = [&](task::NumericVarId v) {
    return var_last_writer_[v] < 0 && var_readers_[v].empty() && var_inv_readers_[v].empty();
  };
  auto write_fact = [&](task::FactId f) {
    if (fact_fresh(f)) touched_facts_.push_back(f);
    last_writer_[f] = node;
    readers_[f].clear();
    inv_readers_[f].clear();
  };
  auto write_var = [&](task::NumericVarId v) {
    if (var_fresh(v)) touched_vars_.push_back(v);
    var_last_writer_[v] = node;
    var_readers_[v].clear();
    var_inv_readers_[v].clear();
  };
  if (event.is_til()) {
    const TilEvent& til = task_.tils()[static_cast<std::size_t>(event.til())];
    for (auto f : til.writes) write_fact(f);
    for (auto v : til.num_writes) write_var(v);
    next_til_ = event.til() + 1;
    return;
  }
  const SnapAction& snap = task_.snap(event.snap);
  for (auto f : snap.reads) {
    if (std::binary_search(snap.writes.begin(), snap.writes.end(), f)) continue;
    if (fact_fresh(f)) touched_facts_.push_back(f);
    readers_[f].push_back(node);
  }
  for (auto v : snap.num_reads) {
    if (std::binary_search(snap.num_writes.begin(), snap.num_writes.end(), v)) continue;
    if (var_fresh(v)) touched_vars_.push_back(v);
    var_readers_[v].push_back(node);
  }
  if (snap.is_end) {
    for (auto f : snap.inv_reads) {
      if (fact_fresh(f)) touched_facts_.push_back(f);
      inv_readers_[f].push_back(node);
    }
    for (auto v : snap.inv_num_reads) {
      if (var_fresh(v)) touched_vars_.push_back(v);
      var_inv_readers_[v].push_back(node);
    }
  }
  for (auto f : snap.writes) write_fact(f);
  for (auto v : snap.num_writes) write_var(v);
  if (!snap.is_end) {
    if (task_.task().actions[snap.action].is_durative) {
      open_start_[snap.action] = node;
      open_min_duration_[snap.action] = event.min_duration_s;
      open_max_duration_[snap.action] = event.max_duration_s;
      open_actions_.push_back(snap.action);
      TrackEnvelopes(snap.action, true);
    }
  } else {
    open_start_[snap.action] = -1;
    if (bound_concurrency_) end_nodes_.push_back(node);
    open_actions_.erase(std::find(open_actions_.begin(), open_actions_.end(), snap.action));
    TrackEnvelopes(snap.action, false);
  }
}

Timeline::Outcome Timeline::Current() const {
  Outcome out;
  for (int n = 0; n < stn_.num_nodes(); ++n) {
    if (is_action_node_[n]) out.makespan_s = std::max(out.makespan_s, stn_.time(n));
  }
  out.lower_bound_s = LowerBound(out.makespan_s, task::ActionId{-1});
  return out;
}

double Timeline::LowerBound(double makespan_s, task::ActionId skip) const {
  double bound = makespan_s;
  for (auto a : open_actions_) {
    if (a == skip) continue;
    bound = std::max(bound, stn_.time(open_start_[a]) + open_min_duration_[a]);
  }
  return bound;
}

bool Timeline::TryAdd(const Event& event, Outcome* outcome) {
  mark_ = stn_.GetMark();
  if (!AddToStn(event)) return false;
  // Current() without its scan over every node of the path.
  double makespan = path_makespan_s_;
  const int new_node = stn_.num_nodes() - 1;
  if (is_action_node_[new_node]) makespan = std::max(makespan, stn_.time(new_node));
  stn_.ForEachRaisedSince(mark_, [&](int n) {
    if (is_action_node_[n]) makespan = std::max(makespan, stn_.time(n));
  });
  tentative_makespan_s_ = makespan;
  outcome->makespan_s = makespan;
  // An ending action no longer bounds from below beyond its end node; a
  // durative start bounds it by its minimum duration.
  const SnapAction* snap = event.is_til() ? nullptr : &task_.snap(event.snap);
  outcome->lower_bound_s =
      LowerBound(makespan, snap != nullptr && snap->is_end ? snap->action : task::ActionId{-1});
  if (snap != nullptr && !snap->is_end && task_.task().actions[snap->action].is_durative) {
    outcome->lower_bound_s =
        std::max(outcome->lower_bound_s, stn_.time(new_node) + event.min_duration_s);
  }
  return true;
}

double Timeline::WindowSlack(task::ActionId a, double makespan_s) const {
  const int start = open_start_[a];
  const double max_d = open_max_duration_[a];
  if (start < 0 || !(max_d < kInfinity)) return kInfinity;
  // Latest start allowed by the events already ordered after it (earliest
  // times; a cheap, sound-enough signature, not a full latest schedule).
  double latest = kInfinity;
  for (const auto& e : stn_.OutEdges(start)) latest = std::min(latest, stn_.time(e.to) - e.weight);
  if (!(latest < kInfinity)) return kInfinity;
  return std::round((latest + max_d - makespan_s) / epsilon_s_) * epsilon_s_;
}

void Timeline::Undo() {
  stn_.Undo(mark_);
  is_action_node_.resize(static_cast<std::size_t>(stn_.num_nodes()));
}

}  // namespace seaplan::search
