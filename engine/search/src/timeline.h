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
// (no allocation per expansion once warmed up). Build keeps the events the
// new path shares with the one built before (their common prefix) and
// undoes and adds only the rest: a greedy search jumping between branches
// of its tree would otherwise schedule the whole path again at every pop.
// The result is the same as building from scratch (every table change is
// undone exactly, in reverse order).
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

  // Makes `events` the path (keeping the prefix it shares with the current
  // path); false when its network is inconsistent.
  bool Build(std::span<const Event> events);
  // The same when the caller knows that the first `keep` events of the
  // current path are those of the new one: keeps them and adds `rest`
  // (no comparison of the shared prefix).
  bool Build(std::size_t keep, std::span<const Event> rest);

  // Heap bytes of the schedule's network (the largest part of a timeline:
  // its edge lists, kept at their largest size for reuse).
  std::size_t MemoryBytes() const { return stn_.MemoryBytes(); }

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
  double epsilon_s() const { return epsilon_s_; }

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
    for (auto n : Since(readers_[f], last_writer_[f])) t = std::max(t, stn_.time(n));
    for (auto n : Since(inv_readers_[f], last_writer_[f])) t = std::max(t, stn_.time(n));
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
  // The makespan after the node added last (AddToStn since `mark`), given
  // the one before it.
  double MakespanSince(const Stn::Mark& mark, double makespan_s) const;
  // Adds `event` (whose node AddToStn made, from `mark` on) to the path's
  // tables; Uncommit undoes the last one.
  void Commit(const Event& event, const Stn::Mark& mark, bool consistent);
  void Uncommit();
  // Drops the path's events from `num_events` on.
  void Rewind(std::size_t num_events);
  // Orders implied by over-all envelopes (invariant_envelopes.h) between
  // `event` and the actions running when it happens.
  void AddEnvelopeEdges(const Event& event, const SnapAction& snap);
  // Entries of an append-only reader list after the last writer `writer`
  // (node numbers grow along the path).
  static std::span<const std::int32_t> Since(const std::vector<std::int32_t>& list,
                                             std::int32_t writer) {
    std::size_t i = list.size();
    while (i > 0 && list[i - 1] > writer) --i;
    return {list.data() + i, list.size() - i};
  }

  const SnapTask& task_;
  double epsilon_s_;
  Stn stn_;
  Stn::Mark mark_{};
  // The path: per event, what undoing it needs.
  struct PathEvent {
    Event event;
    Stn::Mark mark;          // before the event's node
    std::size_t undo_begin;  // its entries in undo_log_ start here
    std::int32_t next_til;   // next_til_ before it
    bool consistent;         // the network up to and including it
    double makespan_s;       // of the path up to and including it
  };
  std::vector<PathEvent> path_;
  Stn::Mark committed_mark_{};  // after the path's last event
  // Old values overwritten by Commit (last writers, the start node an end
  // closed, positions erased from lists), popped by Uncommit.
  std::vector<std::int32_t> undo_log_;
  // Latest action event time of the built path: TryAdd only needs the new
  // node and the nodes propagation raised (times never decrease).
  double path_makespan_s_ = 0.0;
  double tentative_makespan_s_ = 0.0;  // of the last TryAdd, for Keep
  int next_til_ = 0;
  std::vector<std::int32_t> last_writer_;  // per fact, STN node or -1
  // Per fact: every event of the path that read it, in path order (so
  // those after the last writer are a suffix, see Since).
  std::vector<std::vector<std::int32_t>> readers_;
  std::vector<std::int32_t> var_last_writer_;
  std::vector<std::vector<std::int32_t>> var_readers_;
  // Ends of actions whose invariant reads the fact / variable (those after
  // its last writer count): a later writer comes at or after them (gap 0,
  // not epsilon).
  std::vector<std::vector<std::int32_t>> inv_readers_;
  std::vector<std::vector<std::int32_t>> var_inv_readers_;
  std::vector<std::int32_t> open_start_;  // per action: STN node of the running start, or -1
  std::vector<std::int32_t> open_actions_;
  std::vector<double> open_min_duration_;     // per action
  std::vector<double> open_max_duration_;     // per action
  std::vector<std::uint8_t> is_action_node_;  // bytes: resized at every TryAdd and Undo
  bool bound_concurrency_ = false;
  std::vector<std::int32_t> end_nodes_;
  // Per fact: running actions whose end deletes it / that need it over all
  // (InvariantEnvelopes::EndDeletes / EnclosedNeeds), for AddEnvelopeEdges.
  std::vector<std::vector<task::ActionId>> open_deleters_, open_needers_;
};

}  // namespace seaplan::search
