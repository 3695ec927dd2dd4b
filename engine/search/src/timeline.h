// The partial-order schedule of a search path (POPF style).
//
// Built from the path's event sequence (snap actions and applied timed
// initial literals). Each event becomes an STN node ordered epsilon after
// every earlier event it interferes with: after the last writer of anything
// it reads or writes, and after the readers (since that writer) of anything
// it writes. Over-all conditions follow the validator instead (no mutex):
// the start comes at or after the last writer of an invariant's fact or
// variable, and a later writer at or after the end (gap 0). Start and end of an action are tied by
// [min, max] duration edges; timed literals are nodes fixed at their time, and an event that
// interferes with a literal not yet applied must precede it by epsilon. The
// earliest STN solution is the schedule; an inconsistent network prunes the
// path (a deadline passed, or a duration window cannot be met).
//
// Usage per expansion: Build(path), then for each candidate successor
// TryAdd(event) + Undo(). One Timeline is reused across the whole search
// (no allocation per expansion once warmed up).
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "snap_task.h"
#include "stn.h"

namespace seaplan::search {

struct Event {
  // >= 0: a SnapId; < 0: timed initial literal event ~snap.
  SnapId snap = 0;
  double min_duration_s = 0.0;  // starts of durative actions only
  double max_duration_s = 0.0;
  bool is_til() const { return snap < 0; }
  int til() const { return ~snap; }
};

class Timeline {
 public:
  // With `bound_concurrency`, every start is ordered after every earlier end
  // of the path, so the schedule never runs more actions at once than the
  // search had running (max_concurrent_actions).
  Timeline(const SnapTask& task, double epsilon_s, bool bound_concurrency = false);

  // Rebuilds the network for `events`; false when it is inconsistent.
  bool Build(std::span<const Event> events);

  struct Outcome {
    double makespan_s = 0.0;     // latest action event time
    double lower_bound_s = 0.0;  // makespan, or later when running actions must still end
  };
  // After a successful TryAdd: slack (latest end - makespan, epsilon grid) of
  // the running window action `a` (see SnapTask::IsWindowAction).
  double WindowSlack(task::ActionId a, double makespan_s) const;
  // Adds `event` on top of the built path tentatively. Returns false when
  // inconsistent. Always call Undo() afterwards.
  bool TryAdd(const Event& event, Outcome* outcome);
  void Undo();
  // Instead of Undo() after a successful TryAdd: keeps `event` (the same
  // one) as the path's next event, exactly as Build(path + event) would.
  void Keep(const Event& event);

  bool bound_concurrency() const { return bound_concurrency_; }

  // After Build: time of event i of the path.
  double EventTime(std::size_t i) const { return stn_.time(EventNode(i)); }
  // After Build: earliest time of the path's last event that wrote fact `f`
  // (0 when none did); nothing after the path reads f before it.
  double FactWrittenAt(task::FactId f) const {
    return last_writer_[f] >= 0 ? stn_.time(last_writer_[f]) : 0.0;
  }
  // After Build: the latest of FactWrittenAt(f) and the times of the events
  // that read f since (over-all readers at their end); any later writer of
  // f comes no earlier.
  double FactReadUntil(task::FactId f) const {
    double t = FactWrittenAt(f);
    for (auto n : readers_[f]) t = std::max(t, stn_.time(n));
    for (auto n : inv_readers_[f]) t = std::max(t, stn_.time(n));
    return t;
  }
  // After Build: earliest time of the start of running action `a` (0 when
  // it is not running).
  double StartedAt(task::ActionId a) const {
    return open_start_[a] >= 0 ? stn_.time(open_start_[a]) : 0.0;
  }
  Outcome Current() const;

 private:
  // max(makespan, start + minimum duration of every open action but `skip`).
  double LowerBound(double makespan_s, task::ActionId skip) const;
  int EventNode(std::size_t i) const {
    return 1 + static_cast<int>(task_.tils().size()) + static_cast<int>(i);
  }
  int TilNode(int k) const { return 1 + k; }
  bool AddToStn(const Event& event);
  void Commit(const Event& event, int node);
  // Orders implied by over-all envelopes (invariant_envelopes.h) between
  // `event` and the actions running when it happens.
  void AddEnvelopeEdges(const Event& event, const SnapAction& snap);
  // Keeps open_deleters_ / open_needers_ in step with the running actions.
  void TrackEnvelopes(task::ActionId a, bool started);
  void ResetTables();

  const SnapTask& task_;
  double epsilon_s_;
  Stn stn_;
  Stn::Mark mark_{};
  std::size_t num_events_ = 0;
  // Latest action event time of the built path: TryAdd only needs the new
  // node and the nodes propagation raised (times never decrease).
  double path_makespan_s_ = 0.0;
  double tentative_makespan_s_ = 0.0;  // of the last TryAdd, for Keep
  int next_til_ = 0;
  std::vector<std::int32_t> last_writer_;           // per fact, STN node or -1
  std::vector<std::vector<std::int32_t>> readers_;  // per fact, since last writer
  std::vector<std::int32_t> var_last_writer_;
  std::vector<std::vector<std::int32_t>> var_readers_;
  // Ends of actions whose invariant reads the fact / variable, since its
  // last writer: a later writer comes at or after them (gap 0, not epsilon).
  std::vector<std::vector<std::int32_t>> inv_readers_;
  std::vector<std::vector<std::int32_t>> var_inv_readers_;
  std::vector<std::int32_t> touched_facts_, touched_vars_;
  std::vector<std::int32_t> open_start_;  // per action: STN node of the running start, or -1
  std::vector<std::int32_t> open_actions_;
  std::vector<double> open_min_duration_;  // per action
  std::vector<double> open_max_duration_;  // per action
  std::vector<std::int32_t> scratch_preds_;
  std::vector<bool> is_action_node_;
  bool bound_concurrency_ = false;
  std::vector<std::int32_t> end_nodes_;
  // Per fact: running actions whose end deletes it / that need it over all
  // (InvariantEnvelopes::EndDeletes / EnclosedNeeds), for AddEnvelopeEdges.
  std::vector<std::vector<task::ActionId>> open_deleters_, open_needers_;
  std::vector<task::FactId> envelope_touched_;
};

}  // namespace seaplan::search
