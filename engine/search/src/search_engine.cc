#include "search_engine.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

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
      rng_(params.seed) {}

LazySearch::NodeInfo& LazySearch::Info(StateId id) {
  const auto i = static_cast<std::size_t>(id.value());
  if (i >= info_.size()) info_.resize(std::max(i + 1, info_.size() * 3 / 2 + 16));
  return info_[i];
}

std::size_t LazySearch::MemoryBytes() const {
  return info_.capacity() * sizeof(NodeInfo) + slack_pool_.capacity() * sizeof(double) +
         open_all_.MemoryBytes() +
         open_preferred_.MemoryBytes() + path_.capacity() * sizeof(Event);
}

void LazySearch::Initialize(const StateData& initial) {
  bool is_new = false;
  const StateId id = registry_.Insert(initial, &is_new);
  NodeInfo& n = Info(id);
  n = NodeInfo{};
  n.status = kOpen;
  if (transitions_.IsGoal(initial)) {
    plan_.clear();
    plan_makespan_s_ = 0;
  }
  open_all_.Insert(0, 0, id.value());
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
    if (slack_pool_[static_cast<std::size_t>(n.slack_begin + i)] < slack[static_cast<std::size_t>(i)] - 1e-9) return false;
  }
  return true;
}

bool LazySearch::SlackAtMost(const NodeInfo& n, const std::vector<double>& slack) const {
  for (int i = 0; i < n.slack_count; ++i) {
    if (slack_pool_[static_cast<std::size_t>(n.slack_begin + i)] > slack[static_cast<std::size_t>(i)] + 1e-9) return false;
  }
  return true;
}

bool LazySearch::IsAncestor(std::int32_t maybe_ancestor, std::int32_t state) const {
  for (std::int32_t x = state; x >= 0; x = info_[static_cast<std::size_t>(x)].parent) {
    if (x == maybe_ancestor) return true;
  }
  return false;
}

void LazySearch::Push(std::int32_t state, bool preferred, double parent_h) {
  const NodeInfo& n = info_[static_cast<std::size_t>(state)];
  double primary, secondary;
  if (params_.weight < 0) {
    primary = parent_h;
    secondary = getenv("H3_FIFO") ? 0.0 : n.g_s;
  } else {
    primary = n.lb_s + params_.weight * params_.scale_s * parent_h;
    secondary = parent_h;
  }
  open_all_.Insert(primary, secondary, state);
  if (preferred) open_preferred_.Insert(primary, secondary, state);
}

bool LazySearch::Pop(std::int32_t* state) {
  while (!open_all_.empty() || !open_preferred_.empty()) {
    TieBreakingOpenList* list;
    if (!open_preferred_.empty() && (open_all_.empty() || priority_preferred_ <= priority_all_)) {
      list = &open_preferred_;
      ++priority_preferred_;
    } else {
      list = &open_all_;
      ++priority_all_;
    }
    const OpenEntry e = list->Pop();
    const NodeInfo& n = info_[static_cast<std::size_t>(e.state)];
    if (n.status == kClosed) continue;
    if (n.lb_s >= params_.bound_s - params_.epsilon_s / 2) continue;
    *state = e.state;
    return true;
  }
  return false;
}

LazySearch::Status LazySearch::Step() {
  std::int32_t s;
  if (!Pop(&s)) return Status::kExhausted;
  info_[static_cast<std::size_t>(s)].status = kClosed;
  registry_.Unpack(StateId(s), &current_);
  if (s == 0 && transitions_.IsGoal(current_) && info_[0].parent < 0) {
    plan_.clear();
    plan_makespan_s_ = 0;
    return Status::kSolved;
  }
  const NodeInfo& cur = info_[static_cast<std::size_t>(s)];
  const int h = heuristic_.Evaluate(
      current_, &preferred_,
      std::span<const double>(slack_pool_.data() + cur.slack_begin, static_cast<std::size_t>(cur.slack_count)));
  ++counters_.evaluated;
  info_[static_cast<std::size_t>(s)].h = h;
  if (h >= RelaxedPlanHeuristic::kDeadEnd) {
    if (!heuristic_.last_dead_end_proven()) unsafe_dead_end_ = true;
    return Status::kInProgress;
  }
  if (h < best_h_) {
    best_h_ = h;
    priority_preferred_ -= 1000;
  }
  ++counters_.expanded;
  ExtractPath(s, &path_);
  timeline_.Build(path_);

  candidates_.clear();
  transitions_.Candidates(current_, &candidates_);
  std::shuffle(candidates_.begin(), candidates_.end(), rng_);
  // Helpful events first, so FIFO ties favour them.
  std::stable_partition(candidates_.begin(), candidates_.end(), [&](const Event& e) {
    return !e.is_til() && std::binary_search(preferred_.begin(), preferred_.end(), e.snap);
  });
  const bool greedy = params_.weight < 0;
  for (Event ev : candidates_) {
    if (!transitions_.Apply(current_, &ev, &next_)) continue;
    Timeline::Outcome out;
    const bool consistent = timeline_.TryAdd(ev, &out);
    if (!consistent) {
      timeline_.Undo();
      stn_pruned_ = true;
      continue;
    }
    slack_scratch_.clear();
    for (const auto& r : next_.running) {
      if (task_.IsWindowAction(r.action)) {
        slack_scratch_.push_back(timeline_.WindowSlack(r.action, out.makespan_s));
      }
    }
    timeline_.Undo();
    if (out.lower_bound_s >= params_.bound_s - params_.epsilon_s / 2) continue;
    ++counters_.generated;
    // Find the copy of this state to use: an unvisited one, one we improve
    // on, or a new variant when no visited copy dominates this schedule.
    std::int32_t chosen = -1;
    bool dominated = false;
    for (int v = 0; v < params_.max_variants; ++v) {
      next_.variant = v;
      bool is_new = false;
      const StateId id = registry_.Insert(next_, &is_new);
      NodeInfo& n = Info(id);
      if (n.status == kNew) {
        chosen = id.value();
        break;
      }
      merged_any_ = true;
      const bool bound_ok = params_.bound_dominance ? n.lb_s <= out.lower_bound_s + 1e-9
                                                    : std::abs(n.lb_s - out.lower_bound_s) <= 1e-9;
      const bool old_dominates = bound_ok && SlackAtLeast(n, slack_scratch_);
      if (old_dominates) {
        dominated = true;
        break;
      }
      const bool new_dominates = out.lower_bound_s <= n.lb_s + 1e-9 && SlackAtMost(n, slack_scratch_);
      if (new_dominates) {
        if (greedy && n.status == kClosed) {
          dominated = true;
          break;
        }
        // Stored bounds of descendants can be stale after an ancestor
        // improved; never let a state become its own ancestor.
        if (IsAncestor(id.value(), s)) {
          dominated = true;
          break;
        }
        chosen = id.value();
        break;
      }
    }
    if (chosen < 0) {
      if (!next_.running.empty() || !task_.tils().empty()) merged_timed_ = true;
      (void)dominated;
      continue;
    }
    NodeInfo& n = info_[static_cast<std::size_t>(chosen)];
    const bool was_new = n.status == kNew;
    n.parent = s;
    n.event = ev;
    n.g_s = out.makespan_s;
    n.lb_s = out.lower_bound_s;
    n.status = kOpen;
    n.slack_begin = static_cast<std::int32_t>(slack_pool_.size());
    n.slack_count = static_cast<std::int32_t>(slack_scratch_.size());
    slack_pool_.insert(slack_pool_.end(), slack_scratch_.begin(), slack_scratch_.end());
    if (transitions_.IsGoal(next_)) {
      ExtractPath(chosen, &plan_);
      plan_makespan_s_ = out.makespan_s;
      n.status = kClosed;
      return Status::kSolved;
    }
    if (!was_new && greedy) continue;  // better schedule recorded; already queued
    bool preferred = false;
    if (ev.is_til()) {
      preferred = !task_.tils()[static_cast<std::size_t>(ev.til())].add.empty();
    } else {
      preferred = std::binary_search(preferred_.begin(), preferred_.end(), ev.snap);
    }
    Push(chosen, preferred, h);
  }
  return Status::kInProgress;
}

}  // namespace seaplan::search
