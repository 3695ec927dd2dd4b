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
      open_needers_(static_cast<std::size_t>(task.num_facts())) {
  stn_.Reset();
  is_action_node_.assign(1, 0);
  for (const auto& til : task_.tils()) {
    stn_.AddFixedNode(til.time_s);
    is_action_node_.push_back(0);
  }
  committed_mark_ = stn_.GetMark();
}

bool Timeline::Build(std::span<const Event> events) {
  std::size_t common = 0;
  const std::size_t shared = std::min(events.size(), path_.size());
  while (common < shared) {
    const Event& a = events[common];
    const Event& b = path_[common].event;
    if (a.snap != b.snap || a.min_duration_s != b.min_duration_s ||
        a.max_duration_s != b.max_duration_s) {
      break;
    }
    ++common;
  }
  return Build(common, events.subspan(common));
}

bool Timeline::Build(std::size_t keep, std::span<const Event> rest) {
  Rewind(keep);
  path_makespan_s_ = path_.empty() ? 0.0 : path_.back().makespan_s;
  for (const Event& event : rest) {
    const Stn::Mark mark = stn_.GetMark();
    const bool ok = AddToStn(event);  // keep going so tables stay coherent
    const bool consistent = ok && (path_.empty() || path_.back().consistent);
    // Times only rise: the new node and the raised ones are all that can
    // move the makespan (an inconsistent network's times mean nothing).
    path_makespan_s_ = consistent ? MakespanSince(mark, path_makespan_s_) : Current().makespan_s;
    Commit(event, mark, consistent);
  }
  return path_.empty() || path_.back().consistent;
}

void Timeline::Keep(const Event& event) {
  path_makespan_s_ = tentative_makespan_s_;
  Commit(event, mark_, path_.empty() || path_.back().consistent);
}

double Timeline::MakespanSince(const Stn::Mark& mark, double makespan_s) const {
  const int new_node = stn_.num_nodes() - 1;
  if (is_action_node_[new_node]) makespan_s = std::max(makespan_s, stn_.time(new_node));
  stn_.ForEachRaisedSince(mark, [&](int n) {
    if (is_action_node_[n]) makespan_s = std::max(makespan_s, stn_.time(n));
  });
  return makespan_s;
}

void Timeline::Rewind(std::size_t num_events) {
  if (num_events < path_.size()) {
    const PathEvent first = path_[num_events];
    while (path_.size() > num_events) Uncommit();
    committed_mark_ = first.mark;
    next_til_ = first.next_til;
  }
  // Also drops a tentative node left without Undo().
  stn_.Undo(committed_mark_);
  is_action_node_.resize(static_cast<std::size_t>(stn_.num_nodes()));
}

bool Timeline::AddToStn(const Event& event) {
  if (event.is_til()) {
    // Already a fixed node; its orderings were added when the earlier
    // events were (the pending-literal rule). Keep node numbering dense.
    const int node = stn_.BeginNode();
    is_action_node_.resize(static_cast<std::size_t>(node) + 1);
    is_action_node_[node] = 0;
    // Alias node: equal to the literal's fixed node.
    stn_.AddIncoming(TilNode(event.til()), 0.0);
    stn_.AddOutgoing(TilNode(event.til()), 0.0);
    return stn_.FinishNode();
  }
  const SnapAction& snap = task_.snap(event.snap);
  const int node = stn_.BeginNode();
  is_action_node_.resize(static_cast<std::size_t>(node) + 1);
  is_action_node_[node] = 1;
  const double eps = epsilon_s_;
  for (auto f : snap.reads) {
    if (last_writer_[f] >= 0) stn_.AddIncoming(last_writer_[f], eps);
  }
  for (auto f : snap.writes) {
    if (last_writer_[f] >= 0) stn_.AddIncoming(last_writer_[f], eps);
    for (auto r : Since(readers_[f], last_writer_[f])) stn_.AddIncoming(r, eps);
    for (auto r : Since(inv_readers_[f], last_writer_[f])) stn_.AddIncoming(r, 0.0);
  }
  for (auto v : snap.num_reads) {
    if (var_last_writer_[v] >= 0) stn_.AddIncoming(var_last_writer_[v], eps);
  }
  for (auto v : snap.num_writes) {
    if (var_last_writer_[v] >= 0) stn_.AddIncoming(var_last_writer_[v], eps);
    for (auto r : Since(var_readers_[v], var_last_writer_[v])) stn_.AddIncoming(r, eps);
    for (auto r : Since(var_inv_readers_[v], var_last_writer_[v])) stn_.AddIncoming(r, 0.0);
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

void Timeline::Commit(const Event& event, const Stn::Mark& mark, bool consistent) {
  const auto node = static_cast<std::int32_t>(EventNode(path_.size()));
  path_.push_back(
      PathEvent{event, mark, undo_log_.size(), next_til_, consistent, path_makespan_s_});
  committed_mark_ = stn_.GetMark();
  // A write keeps the reader lists (readers after it are told apart by
  // their node numbers, Since) and logs the writer it replaces.
  auto write_fact = [&](task::FactId f) {
    undo_log_.push_back(last_writer_[f]);
    last_writer_[f] = node;
  };
  auto write_var = [&](task::NumericVarId v) {
    undo_log_.push_back(var_last_writer_[v]);
    var_last_writer_[v] = node;
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
    readers_[f].push_back(node);
  }
  for (auto v : snap.num_reads) {
    if (std::binary_search(snap.num_writes.begin(), snap.num_writes.end(), v)) continue;
    var_readers_[v].push_back(node);
  }
  if (snap.is_end) {
    for (auto f : snap.inv_reads) inv_readers_[f].push_back(node);
    for (auto v : snap.inv_num_reads) var_inv_readers_[v].push_back(node);
  }
  for (auto f : snap.writes) write_fact(f);
  for (auto v : snap.num_writes) write_var(v);
  const InvariantEnvelopes& env = task_.envelopes();
  const task::ActionId a = snap.action;
  if (!snap.is_end) {
    if (task_.task().actions[a].is_durative) {
      open_start_[a] = node;
      open_min_duration_[a] = event.min_duration_s;
      open_max_duration_[a] = event.max_duration_s;
      open_actions_.push_back(a);
      for (auto f : env.EndDeletes(a)) open_deleters_[f].push_back(a);
      for (auto f : env.EnclosedNeeds(a)) open_needers_[f].push_back(a);
    }
    return;
  }
  // Erases `a` from `list`, logging where it was.
  auto erase = [&](std::vector<std::int32_t>& list) {
    const auto it = std::find(list.begin(), list.end(), a);
    undo_log_.push_back(static_cast<std::int32_t>(it - list.begin()));
    list.erase(it);
  };
  undo_log_.push_back(open_start_[a]);
  open_start_[a] = -1;
  if (bound_concurrency_) end_nodes_.push_back(node);
  erase(open_actions_);
  for (auto f : env.EndDeletes(a)) erase(open_deleters_[f]);
  for (auto f : env.EnclosedNeeds(a)) erase(open_needers_[f]);
}

void Timeline::Uncommit() {
  // Commit's steps in reverse order.
  const PathEvent& last = path_.back();
  const Event& event = last.event;
  auto pop_log = [&]() {
    const std::int32_t v = undo_log_.back();
    undo_log_.pop_back();
    return v;
  };
  auto unwrite_facts = [&](const std::vector<task::FactId>& facts) {
    for (auto it = facts.rbegin(); it != facts.rend(); ++it) last_writer_[*it] = pop_log();
  };
  auto unwrite_vars = [&](const std::vector<task::NumericVarId>& vars) {
    for (auto it = vars.rbegin(); it != vars.rend(); ++it) var_last_writer_[*it] = pop_log();
  };
  if (event.is_til()) {
    const TilEvent& til = task_.tils()[static_cast<std::size_t>(event.til())];
    unwrite_vars(til.num_writes);
    unwrite_facts(til.writes);
  } else {
    const SnapAction& snap = task_.snap(event.snap);
    const InvariantEnvelopes& env = task_.envelopes();
    const task::ActionId a = snap.action;
    if (!snap.is_end) {
      if (task_.task().actions[a].is_durative) {
        for (auto f : env.EnclosedNeeds(a)) open_needers_[f].pop_back();
        for (auto f : env.EndDeletes(a)) open_deleters_[f].pop_back();
        open_actions_.pop_back();
        open_start_[a] = -1;
      }
    } else {
      auto unerase = [&](std::vector<std::int32_t>& list) {
        list.insert(list.begin() + pop_log(), a);
      };
      const auto& needs = env.EnclosedNeeds(a);
      for (auto it = needs.rbegin(); it != needs.rend(); ++it) unerase(open_needers_[*it]);
      const auto& deletes = env.EndDeletes(a);
      for (auto it = deletes.rbegin(); it != deletes.rend(); ++it) unerase(open_deleters_[*it]);
      unerase(open_actions_);
      if (bound_concurrency_) end_nodes_.pop_back();
      open_start_[a] = pop_log();
    }
    unwrite_vars(snap.num_writes);
    unwrite_facts(snap.writes);
    if (snap.is_end) {
      for (auto v : snap.inv_num_reads) var_inv_readers_[v].pop_back();
      for (auto f : snap.inv_reads) inv_readers_[f].pop_back();
    }
    for (auto v : snap.num_reads) {
      if (!std::binary_search(snap.num_writes.begin(), snap.num_writes.end(), v))
        var_readers_[v].pop_back();
    }
    for (auto f : snap.reads) {
      if (!std::binary_search(snap.writes.begin(), snap.writes.end(), f)) readers_[f].pop_back();
    }
  }
  path_.pop_back();
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
  const double makespan = MakespanSince(mark_, path_makespan_s_);
  const int new_node = stn_.num_nodes() - 1;
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
