#include "search_engine.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iterator>

namespace seaplan::search {

LazySearch::LazySearch(const SnapTask& task, StateRegistry& registry,
                       RelaxedPlanHeuristic& heuristic, const Transitions& transitions,
                       Timeline& timeline, const SearchParams& params)
    : task_(task),
      registry_(registry),
      heuristic_(heuristic),
      transitions_(transitions),
      timeline_(timeline),
      params_(params),
      rng_(params.seed),
      open_all_(KeyOrder(params)),
      open_preferred_(KeyOrder(params)),
      // Its own stream, so that the successors' shuffle is the same with
      // and without it.
      open_typed_(params.seed ^ 0x9e3779b97f4a7c15ULL),
      open_landmark_all_(KeyOrder(params)),
      open_landmark_preferred_(KeyOrder(params)) {
  paths_.push_back(SchedulePath{&timeline_, {}, -1});
  if (params.symmetry != nullptr && params.symmetry->active()) {
    canonical_registry_ =
        std::make_unique<StateRegistry>(registry.num_facts(), registry.num_vars());
  }
  if (TypeBased()) {
    const auto wanted = static_cast<std::size_t>(
        std::clamp(params.schedule_paths, 1, static_cast<int>(kMaxSchedulePaths)));
    while (paths_.size() < wanted) {
      explore_timelines_.push_back(
          std::make_unique<Timeline>(task, timeline.epsilon_s(), timeline.bound_concurrency()));
      paths_.push_back(SchedulePath{explore_timelines_.back().get(), {}, -1});
    }
  }
  if (params.landmarks != nullptr && params.landmarks->size() > 0 && params.weight < 0) {
    landmark_counter_.emplace(*params.landmarks);
  }
}

TieBreakingOpenList::KeyOrder LazySearch::KeyOrder(const SearchParams& params) {
  // Greedy: (h, makespan so far); weighted A*: (f, h). See Push.
  return params.weight < 0 ? TieBreakingOpenList::KeyOrder::kIntegerFirst
                           : TieBreakingOpenList::KeyOrder::kRealFirst;
}

LazySearch::NodeInfo& LazySearch::Info(StateId id) {
  const auto i = static_cast<std::size_t>(id.value());
  if (i >= info_.size()) info_.resize(std::max(i + 1, info_.size() * 3 / 2 + 16));
  return info_[i];
}

std::size_t LazySearch::MemoryBytes() const {
  return info_.capacity() * sizeof(NodeInfo) + slack_pool_.capacity() * sizeof(double) +
         pending_.capacity() * sizeof(Pending) + open_all_.MemoryBytes() +
         open_preferred_.MemoryBytes() + open_typed_.MemoryBytes() +
         depth_.capacity() * sizeof(std::int32_t) + path_.capacity() * sizeof(Event) +
         ExploreMemoryBytes() + open_landmark_all_.MemoryBytes() +
         open_landmark_preferred_.MemoryBytes() +
         landmark_accepted_.capacity() * sizeof(std::uint64_t) +
         (canonical_registry_ ? canonical_registry_->MemoryBytes() : 0) +
         canonical_owner_.capacity() * sizeof(std::int32_t);
}

std::pair<std::int32_t, std::int32_t> LazySearch::CanonicalOwner(const StateData& state) {
  if (!canonical_registry_) return {-1, -1};
  params_.symmetry->Canonicalize(state, &canonical_);
  canonical_.variant = 0;
  bool is_new = false;
  const std::int32_t id = canonical_registry_->Insert(canonical_, &is_new).value();
  if (is_new) canonical_owner_.push_back(-1);
  return {id, canonical_owner_[static_cast<std::size_t>(id)]};
}

std::size_t LazySearch::ExploreMemoryBytes() const {
  std::size_t bytes = 0;
  for (const auto& t : explore_timelines_) bytes += t->MemoryBytes();
  for (const SchedulePath& p : paths_) bytes += p.states.capacity() * sizeof(std::int32_t);
  return bytes;
}

void LazySearch::Initialize(const StateData& initial) {
  bool is_new = false;
  StateData copy = initial;
  copy.variant = 0;
  const StateId id = registry_.Insert(copy, &is_new);
  NodeInfo& n = Info(id);
  n = NodeInfo{};
  n.status = kOpen;
  initial_ = id.value();
  if (TypeBased()) Depth(initial_) = 0;
  // The initial state is a pending record without a parent.
  pending_.push_back(Pending{-1, 0, 0.0});
  open_all_.Insert(0, 0, 0);
  prefix_pending_ = params_.prefix.empty() ? -1 : 0;
  prefix_taken_ = 0;
}

void LazySearch::ExtractPath(std::int32_t state, std::vector<Event>* out) const {
  out->clear();
  for (std::int32_t s = state; info_[static_cast<std::size_t>(s)].parent >= 0;
       s = info_[static_cast<std::size_t>(s)].parent) {
    out->push_back(info_[static_cast<std::size_t>(s)].event);
  }
  std::reverse(out->begin(), out->end());
}

bool LazySearch::SlackAtLeast(const NodeInfo& n, const std::vector<double>& slack) const {
  // Same logical state, so the same window actions in the same order.
  for (int i = 0; i < n.slack_count; ++i) {
    if (slack_pool_[static_cast<std::size_t>(n.slack_begin) + static_cast<std::size_t>(i)] <
        slack[static_cast<std::size_t>(i)] - 1e-9)
      return false;
  }
  return true;
}

bool LazySearch::SlackAtMost(const NodeInfo& n, const std::vector<double>& slack) const {
  for (int i = 0; i < n.slack_count; ++i) {
    if (slack_pool_[static_cast<std::size_t>(n.slack_begin) + static_cast<std::size_t>(i)] >
        slack[static_cast<std::size_t>(i)] + 1e-9)
      return false;
  }
  return true;
}

bool LazySearch::IsAncestor(std::int32_t maybe_ancestor, std::int32_t state) const {
  for (std::int32_t x = state; x >= 0; x = info_[static_cast<std::size_t>(x)].parent) {
    if (x == maybe_ancestor) return true;
  }
  return false;
}

void LazySearch::Push(std::int32_t parent, const Event& event, double g_s, double lb_s,
                      bool preferred, std::int32_t parent_h, std::int32_t parent_lm_h) {
  const auto index = static_cast<std::int32_t>(pending_.size());
  pending_.push_back(Pending{parent, event.snap, lb_s});
  // Greedy: parent's h, then the makespan so far (or the newest record
  // first); weighted A*: makespan lower bound + weight * scale * h, then h.
  double real_key = lb_s + params_.weight * params_.scale_s * parent_h;
  if (params_.weight < 0) {
    real_key = params_.plateau_order == SearchParams::PlateauOrder::kNewestFirst
                   ? -static_cast<double>(index)
                   : g_s;
  }
  open_all_.Insert(parent_h, real_key, index);
  if (preferred) open_preferred_.Insert(parent_h, real_key, index);
  if (TypeBased()) open_typed_.Insert(parent_h, Depth(parent) + 1, index);
  if (landmark_counter_) {
    open_landmark_all_.Insert(parent_lm_h, real_key, index);
    if (preferred) open_landmark_preferred_.Insert(parent_lm_h, real_key, index);
  }
}

std::int32_t& LazySearch::Depth(std::int32_t state) {
  const auto i = static_cast<std::size_t>(state);
  if (i >= depth_.size()) depth_.resize(std::max(i + 1, depth_.size() * 3 / 2 + 16), 0);
  return depth_[i];
}

bool LazySearch::Pop(std::int32_t* state) {
  // Round robin by priority (the lowest goes next, ties in the order
  // preferred, landmark preferred, all, landmark all, typed), as Fast
  // Downward's alternation: a boost lowers the preferred lists' priorities,
  // so they then have that many turns in a row.
  enum List { kPreferred, kLandmarkPreferred, kAll, kLandmarkAll, kTyped, kLists };
  int* const priority[kLists] = {&priority_preferred_, &priority_landmark_preferred_,
                                 &priority_all_, &priority_landmark_all_, &priority_typed_};
  const int lm = params_.landmark_pop_cost;
  const int pop_cost[kLists] = {1, lm, 1, lm, 1};
  while (true) {
    const bool empty[kLists] = {open_preferred_.empty(), open_landmark_preferred_.empty(),
                                open_all_.empty(), open_landmark_all_.empty(), open_typed_.empty()};
    int next = -1;
    for (int l = 0; l < kLists; ++l) {
      if (!empty[l] && (next < 0 || *priority[l] < *priority[next])) next = l;
    }
    if (next < 0) return false;
    std::int32_t index;
    switch (next) {
      case kPreferred:
        index = open_preferred_.Pop().state;
        break;
      case kLandmarkPreferred:
        index = open_landmark_preferred_.Pop().state;
        break;
      case kAll:
        index = open_all_.Pop().state;
        break;
      case kLandmarkAll:
        index = open_landmark_all_.Pop().state;
        break;
      default:
        index = open_typed_.Pop();
        break;
    }
    *priority[next] += pop_cost[next];
    const Pending& p = pending_[static_cast<std::size_t>(index)];
    if (p.parent == kConsumed || OverBound(p.lb_s)) continue;
    *state = index;
    return true;
  }
}

bool LazySearch::OnPath(std::size_t k, std::int32_t state) const {
  if (k == 0) return info_[static_cast<std::size_t>(state)].path_index >= 0;
  const std::vector<std::int32_t>& states = paths_[k].states;
  const auto d = static_cast<std::size_t>(depth_[static_cast<std::size_t>(state)]);
  return d < states.size() && states[d] == state;
}

std::size_t LazySearch::PathPosition(std::size_t k, std::int32_t state) const {
  return static_cast<std::size_t>(k == 0 ? info_[static_cast<std::size_t>(state)].path_index
                                         : depth_[static_cast<std::size_t>(state)]);
}

void LazySearch::EnsureTimeline(std::int32_t state) {
  for (std::size_t k = 0; k < paths_.size(); ++k) {
    if (paths_[k].path_of == state) {  // usually the state just expanded
      active_ = k;
      return;
    }
  }
  // Up the tree from `state` to the deepest state each path shares with
  // its path (none before this search's first build of that path: then up
  // past the initial state). Parents change only in Materialize, for a
  // state that is then appended to the active path, so the paths' states
  // keep the parents they were built with. A path costs the events it
  // must undo plus those it must add; the walk stops once no path found
  // further up could cost less.
  branch_.clear();
  std::array<bool, kMaxSchedulePaths> found{};
  std::size_t num_found = 0, best = 0, best_keep = 0, best_add = 0;
  std::size_t best_cost = static_cast<std::size_t>(-1);
  for (std::int32_t x = state;; x = info_[static_cast<std::size_t>(x)].parent) {
    for (std::size_t k = 0; k < paths_.size(); ++k) {
      if (found[k] || (x >= 0 && !OnPath(k, x))) continue;
      found[k] = true;
      ++num_found;
      const std::size_t keep = x >= 0 ? PathPosition(k, x) + 1 : 0;
      const std::size_t cost = paths_[k].states.size() - keep + branch_.size();
      if (cost < best_cost) {
        best = k;
        best_cost = cost;
        best_keep = keep;
        best_add = branch_.size();
      }
    }
    if (x < 0 || num_found == paths_.size() || branch_.size() >= best_cost) break;
    branch_.push_back(x);
  }
  schedule_events_rebuilt_ += best_cost;
  SchedulePath& p = paths_[best];
  if (best == 0) {
    for (std::size_t i = best_keep; i < p.states.size(); ++i) {
      info_[static_cast<std::size_t>(p.states[i])].path_index = -1;
    }
  }
  p.states.resize(best_keep);
  path_.clear();
  for (std::size_t i = best_add; i-- > 0;) {
    NodeInfo& n = info_[static_cast<std::size_t>(branch_[i])];
    if (n.parent >= 0) path_.push_back(n.event);
    if (best == 0) n.path_index = static_cast<std::int32_t>(p.states.size());
    p.states.push_back(branch_[i]);
  }
  p.timeline->Build(best_keep > 0 ? best_keep - 1 : 0, path_);
  p.path_of = state;
  active_ = best;
}

void LazySearch::AppendToTimelinePath(std::int32_t state) {
  SchedulePath& p = paths_[active_];
  if (active_ == 0) {
    info_[static_cast<std::size_t>(state)].path_index = static_cast<std::int32_t>(p.states.size());
  }
  p.states.push_back(state);
  p.path_of = state;
}

std::int32_t LazySearch::Materialize(std::int32_t pending_index) {
  const Pending rec = pending_[static_cast<std::size_t>(pending_index)];
  pending_[static_cast<std::size_t>(pending_index)].parent = kConsumed;
  if (rec.parent < 0) {
    // The initial state.
    NodeInfo& n = info_[static_cast<std::size_t>(initial_)];
    if (n.status == kClosed) return -1;
    n.status = kClosed;
    registry_.Unpack(StateId(initial_), &current_);
    if (const auto [image, owner] = CanonicalOwner(current_); image >= 0 && owner < 0) {
      canonical_owner_[static_cast<std::size_t>(image)] = initial_;
    }
    return initial_;
  }
  registry_.Unpack(StateId(rec.parent), &parent_state_);
  Event ev{rec.snap, 0.0, 0.0};
  if (!transitions_.Apply(parent_state_, &ev, &next_)) return -1;  // cannot happen: deterministic
  EnsureTimeline(rec.parent);
  Timeline::Outcome out;
  const auto reject = [this]() {
    ActiveTimeline().Undo();
    return std::int32_t{-1};
  };
  // A state dropped for another copy's schedule: with running actions or
  // timed literals the times of single facts also matter (a deadline met on
  // one path, missed on the other), so exhaustion is no proof then.
  const auto reject_merged = [&]() {
    if (!next_.running.empty() || !task_.tils().empty()) merged_timed_ = true;
    return reject();
  };
  // Only deferred successors can fail here: theirs was not checked at generation.
  Timeline& timeline = ActiveTimeline();
  if (!timeline.TryAdd(ev, &out)) {
    stn_pruned_ = true;
    return reject();
  }
  if (OverBound(out.lower_bound_s)) return reject();
  slack_scratch_.clear();
  for (const auto& r : next_.running) {
    if (task_.IsWindowAction(r.action))
      slack_scratch_.push_back(timeline.WindowSlack(r.action, out.makespan_s));
  }
  const bool greedy = params_.weight < 0;
  const auto [image, owner] = CanonicalOwner(next_);
  bool owner_is_copy = false;
  // Find the copy of this state to use: an unvisited one, one we improve
  // on, or a new variant when no visited copy dominates this schedule.
  std::int32_t chosen = -1;
  for (int v = 0; v < params_.max_variants; ++v) {
    next_.variant = v;
    bool is_new = false;
    const StateId id = registry_.Insert(next_, &is_new);
    if (id.value() == owner) owner_is_copy = true;
    NodeInfo& n = Info(id);
    if (n.status == kNew) {
      chosen = id.value();
      break;
    }
    merged_any_ = true;
    if (BoundCovers(n, out.lower_bound_s) && SlackAtLeast(n, slack_scratch_))
      return reject_merged();  // dominated
    const bool new_dominates = out.lower_bound_s <= n.lb_s + 1e-9 && SlackAtMost(n, slack_scratch_);
    if (new_dominates) {
      if (greedy && n.status == kClosed) return reject_merged();  // the better schedule is dropped
      // Stored bounds of descendants can be stale after an ancestor
      // improved; never let a state become its own ancestor.
      if (IsAncestor(id.value(), rec.parent)) return reject();
      chosen = id.value();
      break;
    }
  }
  if (chosen < 0) return reject_merged();
  if (owner >= 0 && owner != chosen && !owner_is_copy) {
    // A symmetric state (another permutation of interchangeable objects)
    // was expanded: its future is this one's, renamed. Dropped like a
    // dominated copy when its bound is no later (window actions' slack is
    // not compared, so not with those running).
    const NodeInfo& o = info_[static_cast<std::size_t>(owner)];
    if (o.status == kClosed && BoundCovers(o, out.lower_bound_s) && o.slack_count == 0 &&
        slack_scratch_.empty()) {
      ++counters_.symmetric_drops;
      merged_any_ = true;  // the schedules were not compared: no proof of optimality
      return reject_merged();
    }
  }
  // The image's owner is the expanded state that drops the most: one with
  // no window slack (the drop compares no slack) and the earliest bound.
  if (image >= 0) {
    const auto o = static_cast<std::size_t>(owner);
    const bool replace =
        owner < 0 || (slack_scratch_.empty() &&
                      (info_[o].slack_count != 0 || out.lower_bound_s < info_[o].lb_s - 1e-9));
    if (replace) canonical_owner_[static_cast<std::size_t>(image)] = chosen;
  }
  // The chosen state's schedule is the parent's plus this event: keep it
  // for the expansion that follows.
  timeline.Keep(ev);
  if (TypeBased()) {
    const std::int32_t depth = Depth(rec.parent) + 1;
    Depth(chosen) = depth;
  }
  NodeInfo& n = info_[static_cast<std::size_t>(chosen)];
  AppendToTimelinePath(chosen);
  n.parent = rec.parent;
  n.event = ev;
  n.g_s = out.makespan_s;
  n.lb_s = out.lower_bound_s;
  n.status = kClosed;
  n.slack_begin = static_cast<std::int32_t>(slack_pool_.size());
  n.slack_count = static_cast<std::int32_t>(slack_scratch_.size());
  slack_pool_.insert(slack_pool_.end(), slack_scratch_.begin(), slack_scratch_.end());
  std::swap(current_, next_);
  return chosen;
}

bool LazySearch::TakeEagerEnd(Timeline& timeline) {
  for (const Event& candidate : candidates_) {
    if (candidate.is_til() || (candidate.snap & 1) == 0 ||
        !task_.EagerEnd(task_.snap(candidate.snap).action))
      continue;
    Event ev = candidate;
    if (!transitions_.Apply(current_, &ev, &next_)) continue;
    Timeline::Outcome out;
    const bool consistent = timeline.TryAdd(ev, &out);
    timeline.Undo();
    if (!consistent) continue;
    candidates_.assign(1, candidate);
    ++counters_.eager_ends;
    return true;
  }
  return false;
}

LazySearch::Status LazySearch::Step() {
  std::int32_t pending_index;
  if (!Pop(&pending_index)) return Status::kExhausted;
  const std::int32_t s = Materialize(pending_index);
  if (s < 0) return Status::kInProgress;
  // On the prefix: its next event is the only successor.
  const bool on_prefix = pending_index == prefix_pending_;
  if (on_prefix) prefix_pending_ = -1;
  if (transitions_.IsGoal(current_)) {
    ExtractPath(s, &plan_);
    plan_makespan_s_ = info_[static_cast<std::size_t>(s)].g_s;
    return Status::kSolved;
  }
  const NodeInfo& cur = info_[static_cast<std::size_t>(s)];
  std::span<const std::uint8_t> usable;
  const bool timed_check = reachability_ != nullptr && reachability_->active();
  if (timed_check) {
    EnsureTimeline(s);
    if (!reachability_->Evaluate(current_, ActiveTimeline())) {
      // Like an inconsistent schedule, this depends on the path's times.
      stn_pruned_ = true;
      return Status::kInProgress;
    }
    usable = reachability_->usable_snaps();
  }
  EnsureTimeline(s);
  candidates_.clear();
  transitions_.Candidates(current_, &candidates_);
  const std::int32_t parent = info_[static_cast<std::size_t>(s)].parent;
  if (on_prefix) {
    const SnapId due = params_.prefix[prefix_taken_].snap;
    std::erase_if(candidates_, [due](const Event& e) { return e.snap != due; });
  }
  // A state whose only successor is an eager end is not evaluated: its
  // successor goes on with the parent's h, as this state did.
  const bool eager = !on_prefix && params_.eager_ends && parent >= 0 && candidates_.size() > 1 &&
                     TakeEagerEnd(ActiveTimeline());
  int h = 0;
  if (eager) {
    h = info_[static_cast<std::size_t>(parent)].h;
  } else {
    // The heuristic reads when each agent is free on the path's schedule.
    // With deadlines its helpful events are only wanted beside the timed
    // plan's when that plan leaves numbers out (below).
    const bool timed_helpful_only = timed_check && !reachability_->leaves_out_numbers();
    h = heuristic_.Evaluate(current_, timed_helpful_only ? nullptr : &preferred_,
                            std::span<const double>(slack_pool_.data() + cur.slack_begin,
                                                    static_cast<std::size_t>(cur.slack_count)),
                            usable, &ActiveTimeline());
    if (timed_check && h < RelaxedPlanHeuristic::kDeadEnd) {
      // The untimed relaxed plan counts a fact of the state as free even
      // when the state got it too late for a window (an image taken after
      // its antenna's window closed); the plan along the earliest achievers
      // takes it again. The longer of the two estimates guides the search.
      // Its helpful events replace the untimed plan's: FF's first achievers
      // give every image to the first satellite, which then works alone
      // past the windows; the earliest achievers spread the work the way
      // deadlines need it (bench/planner/README.md, "Helpful events on
      // time"). That plan leaves numbers out: with numeric conditions,
      // FF's events (a refuel) stay helpful too.
      if (timed_helpful_only) {
        h = std::max(h, reachability_->RelaxedPlanLength(current_, &preferred_));
      } else {
        h = std::max(h, reachability_->RelaxedPlanLength(current_, &timed_preferred_));
        merged_preferred_.clear();
        std::set_union(preferred_.begin(), preferred_.end(), timed_preferred_.begin(),
                       timed_preferred_.end(), std::back_inserter(merged_preferred_));
        preferred_.swap(merged_preferred_);
      }
    }
    ++counters_.evaluated;
    if (h < RelaxedPlanHeuristic::kDeadEnd && params_.goal_order != nullptr &&
        params_.goal_order->DeadEnd(current_)) {
      ++counters_.goal_order_dead_ends;
      info_[static_cast<std::size_t>(s)].h = RelaxedPlanHeuristic::kDeadEnd;
      return Status::kInProgress;  // proven: not an unsafe dead end
    }
  }
  info_[static_cast<std::size_t>(s)].h = h;
  // (Not for an eager end's state: its parent's h may have been
  // overwritten since, by a re-expansion in weighted A*.)
  if (!eager && h >= RelaxedPlanHeuristic::kDeadEnd) {
    if (!heuristic_.last_dead_end_proven()) unsafe_dead_end_ = true;
    return Status::kInProgress;
  }
  std::int32_t landmark_h = 0;
  if (landmark_counter_) {
    // Path-dependent: what the parent had accepted, plus what holds now
    // and had its ordering parents accepted there.
    const std::size_t need =
        (static_cast<std::size_t>(std::max(s, parent)) + 1) * landmark_counter_->words();
    if (landmark_accepted_.size() < need) {
      landmark_accepted_.resize(std::max(need, landmark_accepted_.size() * 3 / 2), 0);
    }
    landmark_h =
        landmark_counter_->Update(parent >= 0 ? std::span<const std::uint64_t>(Accepted(parent))
                                              : std::span<const std::uint64_t>(),
                                  current_, Accepted(s));
  }
  // Progress in either estimate boosts the preferred lists (LAMA).
  bool progress = false;
  if (h < best_h_) {
    best_h_ = h;
    progress = true;
  }
  if (landmark_counter_ && landmark_h < best_landmark_h_) {
    best_landmark_h_ = landmark_h;
    progress = true;
  }
  if (progress) {
    priority_preferred_ -= 1000;
    priority_landmark_preferred_ -= 1000;
  }
  ++counters_.expanded;
  Timeline& timeline = ActiveTimeline();
  std::shuffle(candidates_.begin(), candidates_.end(), rng_);
  // Helpful events first, so FIFO ties favour them. With landmarks, an
  // event adding one that could be accepted next is helpful too.
  std::span<const std::uint64_t> accepted;
  if (landmark_counter_) accepted = Accepted(s);
  // An eager end, the only successor, counts as helpful: the relaxed plan
  // rarely names it (its facts often hold in the relaxation already), and
  // left to the lists of all successors it would stall the preferred ones.
  const std::size_t num_helpful =
      eager ? 1
            : static_cast<std::size_t>(
                  std::stable_partition(
                      candidates_.begin(), candidates_.end(),
                      [&](const Event& e) {
                        if (e.is_til()) return false;
                        if (std::binary_search(preferred_.begin(), preferred_.end(), e.snap))
                          return true;
                        return landmark_counter_ &&
                               landmark_counter_->AddsNextLandmark(accepted, current_, e.snap);
                      }) -
                  candidates_.begin());
  std::size_t tried = 0;
  const bool greedy = params_.weight < 0;
  const double parent_g_s = info_[static_cast<std::size_t>(s)].g_s;
  const double parent_lb_s = info_[static_cast<std::size_t>(s)].lb_s;
  // The due event's record is the next one pushed (if it applies, fits the
  // schedule and the bound; else the search runs out of states).
  if (on_prefix && !candidates_.empty() && prefix_taken_ + 1 < params_.prefix.size()) {
    prefix_pending_ = static_cast<std::int32_t>(pending_.size());
    ++prefix_taken_;
  }
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    Event ev = candidates_[i];
    if (stop_ != nullptr && (++tried & 255) == 0 && stop_->StopRequested())
      return Status::kInProgress;
    const bool helpful =
        i < num_helpful;  // of the relaxed plan or adding a next landmark (never a TIL)
    // Starts are even SnapIds (snap_task.h); reading the SnapAction would
    // cost a cache miss per candidate.
    if (greedy && !ev.is_til() && (ev.snap & 1) == 0 && !helpful) {
      // Deferred: applied and scheduled only if popped (Materialize), with
      // the parent's makespan and bound, both valid lower bounds.
      ++counters_.generated;
      Push(s, ev, parent_g_s, parent_lb_s, false, h, landmark_h);
      continue;
    }
    if (!transitions_.Apply(current_, &ev, &next_)) continue;
    Timeline::Outcome out;
    const bool consistent = timeline.TryAdd(ev, &out);
    timeline.Undo();
    if (!consistent) {
      stn_pruned_ = true;
      continue;
    }
    if (OverBound(out.lower_bound_s)) continue;
    ++counters_.generated;
    bool preferred = false;
    if (ev.is_til()) {
      preferred = !task_.tils()[static_cast<std::size_t>(ev.til())].add.empty();
    } else {
      preferred = helpful;
    }
    // A goal reached is taken at once (best first among goals is the
    // anytime phase's job): put it first in both lists.
    if (transitions_.IsGoal(next_)) {
      Push(s, ev, out.makespan_s, out.lower_bound_s, true, kGoalFirst, kGoalFirst);
      continue;
    }
    Push(s, ev, out.makespan_s, out.lower_bound_s, preferred, h, landmark_h);
  }
  return Status::kInProgress;
}

}  // namespace seaplan::search
