#include "temporal_reachability.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace seaplan::search {
namespace {

constexpr double kTol = 1e-9;
// Rounds of window adjustment per snap before settling for the (earlier,
// hence still relaxed) time reached so far.
constexpr int kMaxWindowRounds = 32;

void AddEffectAdds(const task::Effects& e, std::vector<std::uint8_t>& added) {
  for (auto f : e.add) added[f] = 1;
  for (const auto& ce : e.conditional) {
    for (auto f : ce.add) added[f] = 1;
  }
}

void AddWrittenVars(const task::Effects& e, std::vector<std::uint8_t>& written) {
  for (const auto& n : e.numeric) written[n.var] = 1;
  for (const auto& ce : e.conditional) {
    for (const auto& n : ce.numeric) written[n.var] = 1;
  }
}

bool ReadsOnly(const task::NumericExpr& expr, const std::vector<std::uint8_t>& written) {
  for (const auto& n : expr.nodes) {
    if (n.op == task::NumericExpr::Op::kVariable && written[n.var]) return false;
    if (n.op == task::NumericExpr::Op::kDuration || n.op == task::NumericExpr::Op::kTotalTime)
      return false;
  }
  return true;
}

}  // namespace

TemporalReachability::TemporalReachability(const SnapTask& task)
    : task_(task), num_facts_(task.num_facts()), num_ops_(2 * task.num_actions()) {
  const auto& gt = task.task();
  const auto& actions = gt.actions;
  const std::size_t num_actions = actions.size();
  std::vector<std::uint8_t> added(static_cast<std::size_t>(num_facts_), 0);
  std::vector<std::uint8_t> written(static_cast<std::size_t>(task.num_vars()), 0);
  for (const auto& a : actions) {
    AddEffectAdds(a.start_effects, added);
    AddEffectAdds(a.end_effects, added);
    AddWrittenVars(a.start_effects, written);
    AddWrittenVars(a.end_effects, written);
  }
  for (const auto& tif : gt.timed_fluents) written[tif.var] = 1;
  window_fact_.assign(static_cast<std::size_t>(num_facts_), 0);
  for (int f = 0; f < num_facts_; ++f) {
    window_fact_[f] = !added[f] && !task.TilsWritingFact(f).empty();
  }
  for (const auto& til : task.tils()) {
    for (auto f : til.del) active_ = active_ || window_fact_[f];
  }
  // Inactive: Evaluate is never called, so no tables (large tasks without
  // deadlines pay nothing).
  if (!active_) return;

  // Static duration bounds: constraints over fluents no effect changes.
  static_min_d_.assign(num_actions, 0.0);
  static_max_d_.assign(num_actions, kInfinity);
  for (std::size_t a = 0; a < num_actions; ++a) {
    const auto& action = actions[a];
    if (!action.is_durative) {
      static_max_d_[a] = 0.0;
      continue;
    }
    double lo = 0.0, hi = kInfinity;
    for (const auto& c : action.duration) {
      if (!ReadsOnly(c.value, written)) continue;
      const auto v = c.value.Evaluate(gt.initial_values);
      if (!v || std::isnan(*v)) continue;
      switch (c.comparator) {
        case task::Comparator::kEqual:
          lo = std::max(lo, *v);
          hi = std::min(hi, *v);
          break;
        case task::Comparator::kGreaterEqual:
        case task::Comparator::kGreater:
          lo = std::max(lo, *v);
          break;
        case task::Comparator::kLessEqual:
        case task::Comparator::kLess:
          hi = std::min(hi, *v);
          break;
      }
    }
    if (hi < lo) hi = lo;  // the successor generator rejects such starts anyway
    static_min_d_[a] = lo;
    static_max_d_[a] = hi;
  }

  // Per-snap tables.
  std::vector<std::uint8_t> needed_window(static_cast<std::size_t>(num_facts_), 0);
  pre_begin_.push_back(0);
  win_begin_.push_back(0);
  add_begin_.push_back(0);
  missing_init_.resize(static_cast<std::size_t>(num_ops_));
  std::vector<std::int32_t> tmp;
  for (int op = 0; op < num_ops_; ++op) {
    const auto a = static_cast<std::size_t>(op / 2);
    const bool is_end = op % 2 == 1;
    const task::Action& action = actions[a];
    const bool exists = !is_end || action.is_durative;
    tmp.clear();
    auto condition = [&](const std::vector<task::FactId>& facts, Kind kind) {
      for (auto f : facts) {
        if (window_fact_[f]) {
          win_.push_back({f, kind});
          needed_window[f] = 1;
        } else {
          tmp.push_back(f);
        }
      }
    };
    if (exists) {
      if (!is_end) {
        condition(action.at_start.positive, Kind::kAt);
        if (action.is_durative) {
          condition(action.over_all.positive, Kind::kSpan);
          // At-end window facts constrain the start; their facts are
          // preconditions of the end snap only.
          for (auto f : action.at_end.positive) {
            if (window_fact_[f]) {
              win_.push_back({f, Kind::kRange});
              needed_window[f] = 1;
            }
          }
        }
      } else {
        condition(action.at_end.positive, Kind::kAt);
        condition(action.over_all.positive, Kind::kAt);
        tmp.push_back(num_facts_ + static_cast<int>(a));
      }
      std::sort(tmp.begin(), tmp.end());
      tmp.erase(std::unique(tmp.begin(), tmp.end()), tmp.end());
    }
    pre_.insert(pre_.end(), tmp.begin(), tmp.end());
    pre_begin_.push_back(static_cast<std::int32_t>(pre_.size()));
    win_begin_.push_back(static_cast<std::int32_t>(win_.size()));
    missing_init_[op] = exists ? static_cast<std::int32_t>(tmp.size()) : (1 << 30);
    if (exists && tmp.empty()) no_pre_ops_.push_back(op);
    tmp.clear();
    if (exists) {
      const task::Effects& eff = is_end ? action.end_effects : action.start_effects;
      tmp.insert(tmp.end(), eff.add.begin(), eff.add.end());
      for (const auto& ce : eff.conditional) tmp.insert(tmp.end(), ce.add.begin(), ce.add.end());
      if (!is_end && action.is_durative) tmp.push_back(num_facts_ + static_cast<int>(a));
      std::sort(tmp.begin(), tmp.end());
      tmp.erase(std::unique(tmp.begin(), tmp.end()), tmp.end());
    }
    add_.insert(add_.end(), tmp.begin(), tmp.end());
    add_begin_.push_back(static_cast<std::int32_t>(add_.size()));
  }
  for (int f = 0; f < num_facts_; ++f) {
    if (needed_window[f]) window_facts_.push_back(f);
  }
  // fact -> snaps needing it.
  const int total_facts = num_facts_ + task.num_actions();
  std::vector<std::int32_t> count(static_cast<std::size_t>(total_facts) + 1, 0);
  for (auto f : pre_) ++count[f + 1];
  for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
  fact_ops_begin_ = count;
  fact_ops_.resize(pre_.size());
  std::vector<std::int32_t> fill(count.begin(), count.end() - 1);
  for (int op = 0; op < num_ops_; ++op) {
    for (int i = pre_begin_[op]; i < pre_begin_[op + 1]; ++i) fact_ops_[fill[pre_[i]]++] = op;
  }

  windows_.resize(static_cast<std::size_t>(num_facts_));
  open_since_.assign(static_cast<std::size_t>(num_facts_), kInfinity);
  earliest_.resize(static_cast<std::size_t>(total_facts));
  achiever_.resize(static_cast<std::size_t>(total_facts));
  fact_marked_.assign(static_cast<std::size_t>(total_facts), 0);
  op_marked_.assign(static_cast<std::size_t>(num_ops_), 0);
  missing_.resize(static_cast<std::size_t>(num_ops_));
  usable_.resize(static_cast<std::size_t>(num_ops_));
  min_d_ = static_min_d_;
  max_d_ = static_max_d_;
  running_.assign(num_actions, 0);
}

double TemporalReachability::NextAllowed(const WindowCondition& c, double t,
                                         task::ActionId a) const {
  const double min_d = min_d_[static_cast<std::size_t>(a)];
  const double max_d = max_d_[static_cast<std::size_t>(a)];
  for (const Interval& w : windows_[c.fact]) {
    switch (c.kind) {
      case Kind::kAt:
        if (w.close_s >= t - kTol) return std::max(t, w.open_s);
        break;
      case Kind::kSpan: {
        const double s = std::max(t, w.open_s);
        if (w.close_s >= s + min_d - kTol) return s;
        break;
      }
      case Kind::kRange:
        if (w.close_s >= t + min_d - kTol) {
          return w.open_s <= t + max_d + kTol ? t : w.open_s - max_d;
        }
        break;
    }
  }
  return kInfinity;
}

double TemporalReachability::OpTime(int op, double t0) const {
  const auto a = static_cast<task::ActionId>(op / 2);
  const bool is_end = op % 2 == 1;
  double t = t0;
  if (is_end) {
    t = std::max(t, earliest_[static_cast<std::size_t>(num_facts_) + static_cast<std::size_t>(a)] +
                        min_d_[a]);
  }
  const int first = win_begin_[op];
  const int last = win_begin_[op + 1];
  if (first == last) return t;
  if (is_end && running_[a]) {
    // The over-all window facts of a running action hold now: its end must
    // come before their current windows close.
    for (auto f : task_.task().actions[a].over_all.positive) {
      if (!window_fact_[f]) continue;
      const auto& ws = windows_[f];
      if (ws.empty() || ws.front().close_s < t - kTol) return kInfinity;
    }
  }
  for (int round = 0; round < kMaxWindowRounds; ++round) {
    bool moved = false;
    for (int i = first; i < last; ++i) {
      const double next = NextAllowed(win_[i], t, a);
      if (!(next < kInfinity)) return kInfinity;
      if (next > t + kTol) {
        t = next;
        moved = true;
      }
    }
    if (!moved) break;
  }
  return t;
}

double TemporalReachability::ScheduleBound(int op, const Timeline& timeline) const {
  const SnapAction& snap = task_.snap(op);
  double t = 0.0;
  for (auto f : snap.reads) t = std::max(t, timeline.FactWrittenAt(f));
  for (auto f : snap.writes) t = std::max(t, timeline.FactReadUntil(f));
  if (!snap.is_end) {
    for (auto f : snap.inv_reads) t = std::max(t, timeline.FactWrittenAt(f));
  }
  return t;
}

void TemporalReachability::Reach(int fact, double time_s, int achiever) {
  if (!(time_s < earliest_[fact])) return;
  earliest_[fact] = time_s;
  achiever_[fact] = achiever;
  heap_.emplace_back(time_s, fact);
  std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
}

bool TemporalReachability::Evaluate(const StateData& state, const Timeline& timeline) {
  // Windows of the window facts from the state and the pending literals.
  for (auto f : window_facts_) {
    windows_[f].clear();
    open_since_[f] = state.Holds(f) ? timeline.FactWrittenAt(f) : kInfinity;
  }
  const auto& tils = task_.tils();
  for (std::size_t k = static_cast<std::size_t>(state.next_til); k < tils.size(); ++k) {
    const TilEvent& til = tils[k];
    for (auto f : til.del) {
      if (!window_fact_[f] || !(open_since_[f] < kInfinity)) continue;
      windows_[f].push_back({open_since_[f], til.time_s});
      open_since_[f] = kInfinity;
    }
    for (auto f : til.add) {
      if (window_fact_[f] && !(open_since_[f] < kInfinity)) open_since_[f] = til.time_s;
    }
  }
  for (auto f : window_facts_) {
    if (open_since_[f] < kInfinity) windows_[f].push_back({open_since_[f], kInfinity});
  }

  std::fill(earliest_.begin(), earliest_.end(), kInfinity);
  std::copy(missing_init_.begin(), missing_init_.end(), missing_.begin());
  std::fill(usable_.begin(), usable_.end(), 0);
  heap_.clear();
  for (std::size_t w = 0; w < state.facts.size(); ++w) {
    std::uint64_t bits = state.facts[w];
    while (bits) {
      const int f = static_cast<int>(w * 64) + __builtin_ctzll(bits);
      bits &= bits - 1;
      if (!window_fact_[f]) Reach(f, timeline.FactWrittenAt(f), -1);
    }
  }
  for (std::size_t k = static_cast<std::size_t>(state.next_til); k < tils.size(); ++k) {
    for (auto f : tils[k].add) {
      if (!window_fact_[f]) Reach(f, tils[k].time_s, -1);
    }
  }
  for (const auto& r : state.running) {
    running_[r.action] = 1;
    min_d_[r.action] = r.min_duration_s;
    max_d_[r.action] = r.max_duration_s;
    Reach(num_facts_ + r.action, timeline.StartedAt(r.action), -1);
  }
  auto fire = [&](int op, double t0) {
    const double t = OpTime(op, std::max(t0, ScheduleBound(op, timeline)));
    if (!(t < kInfinity)) return;
    usable_[op] = 1;
    for (int i = add_begin_[op]; i < add_begin_[op + 1]; ++i) Reach(add_[i], t, op);
  };
  for (auto op : no_pre_ops_) fire(op, 0.0);
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), std::greater<>());
    const auto [t, f] = heap_.back();
    heap_.pop_back();
    if (t > earliest_[f]) continue;  // stale entry
    for (int i = fact_ops_begin_[f]; i < fact_ops_begin_[f + 1]; ++i) {
      const int op = fact_ops_[i];
      // Facts pop in time order: the last precondition sets the time.
      if (--missing_[op] == 0) fire(op, t);
    }
  }

  bool alive = true;
  for (const auto& r : state.running) {
    if (!usable_[2 * r.action + 1]) alive = false;
    running_[r.action] = 0;
    min_d_[r.action] = static_min_d_[r.action];
    max_d_[r.action] = static_max_d_[r.action];
  }
  for (auto f : task_.task().goal.positive) {
    if (!window_fact_[f] && !(earliest_[f] < kInfinity)) alive = false;
  }
  return alive;
}

int TemporalReachability::RelaxedPlanLength(const StateData& state,
                                            std::vector<SnapId>* preferred) {
  for (auto op : marked_ops_) op_marked_[op] = 0;
  for (auto f : marked_facts_) fact_marked_[f] = 0;
  marked_ops_.clear();
  marked_facts_.clear();
  stack_.clear();
  auto mark_fact = [&](int f) {
    if (fact_marked_[f]) return;
    fact_marked_[f] = 1;
    marked_facts_.push_back(f);
    const int op = achiever_[f];
    if (op < 0 || op_marked_[op]) return;
    op_marked_[op] = 1;
    marked_ops_.push_back(op);
    stack_.push_back(op);
  };
  for (auto f : task_.task().goal.positive) {
    if (!window_fact_[f]) mark_fact(f);
  }
  while (!stack_.empty()) {
    const int op = stack_.back();
    stack_.pop_back();
    for (int i = pre_begin_[op]; i < pre_begin_[op + 1]; ++i) mark_fact(pre_[i]);
  }
  int h = static_cast<int>(marked_ops_.size());
  for (const auto& r : state.running) {
    if (!op_marked_[2 * r.action + 1]) ++h;
  }
  if (preferred != nullptr) {
    preferred->clear();
    for (auto op : marked_ops_) {
      bool from_state = true;
      for (int i = pre_begin_[op]; i < pre_begin_[op + 1] && from_state; ++i) {
        from_state = achiever_[pre_[i]] < 0;
      }
      if (from_state) preferred->push_back(op);
    }
    std::sort(preferred->begin(), preferred->end());
  }
  return h;
}

}  // namespace seaplan::search
