#include "temporal_reachability.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>

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
  leaves_out_numbers_ = !gt.goal.numeric.empty();
  for (const auto& a : actions) {
    leaves_out_numbers_ = leaves_out_numbers_ || !a.at_start.numeric.empty() ||
                          !a.over_all.numeric.empty() || !a.at_end.numeric.empty();
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
  pair_base_ = num_facts_ + task.num_actions();
  fact_pairs_begin_.assign(static_cast<std::size_t>(num_facts_) + 1, 0);
  op_pairs_begin_.assign(static_cast<std::size_t>(num_ops_) + 1, 0);
  IndexConditions(pair_base_);
  windows_.resize(static_cast<std::size_t>(num_facts_));
  fact_times_.resize(static_cast<std::size_t>(num_facts_));
  schedule_begin_.assign(1, 0);
  for (int op = 0; op < num_ops_; ++op) {
    const SnapAction& snap = task_.snap(op);
    for (auto f : snap.reads) schedule_facts_.push_back(2 * f);
    for (auto f : snap.writes) schedule_facts_.push_back(2 * f + 1);
    if (!snap.is_end) {
      for (auto f : snap.inv_reads) schedule_facts_.push_back(2 * f);
    }
    schedule_begin_.push_back(static_cast<std::int32_t>(schedule_facts_.size()));
  }
  fact_times_stamp_.assign(static_cast<std::size_t>(num_facts_), 0);
  open_since_.assign(static_cast<std::size_t>(num_facts_), kInfinity);
  op_marked_.assign(static_cast<std::size_t>(num_ops_), 0);
  missing_.resize(static_cast<std::size_t>(num_ops_));
  usable_.resize(static_cast<std::size_t>(num_ops_));
  min_d_ = static_min_d_;
  max_d_ = static_max_d_;
  running_.assign(num_actions, 0);
}

void TemporalReachability::IndexConditions(int total_facts) {
  // fact -> snaps needing it.
  std::vector<std::int32_t> count(static_cast<std::size_t>(total_facts) + 1, 0);
  for (auto f : pre_) ++count[static_cast<std::size_t>(f) + 1];
  for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
  fact_ops_begin_ = count;
  fact_ops_.resize(pre_.size());
  std::vector<std::int32_t> fill(count.begin(), count.end() - 1);
  for (int op = 0; op < num_ops_; ++op) {
    for (int i = pre_begin_[op]; i < pre_begin_[op + 1]; ++i) fact_ops_[fill[pre_[i]]++] = op;
  }
  earliest_.resize(static_cast<std::size_t>(total_facts));
  achiever_.resize(static_cast<std::size_t>(total_facts));
  fact_marked_.assign(static_cast<std::size_t>(total_facts), 0);
}

void TemporalReachability::UseMutexGroups(const MutexGroups& mutex) {
  if (!active_ || num_pair_facts() > 0) return;
  const auto& actions = task_.task().actions;
  const auto& groups = mutex.groups();
  std::size_t members = 0;
  for (const auto& g : groups) members += g.size();
  if (groups.empty() || members > kMaxGroupMembers) return;

  // The facts a snap needs when it happens: the context it adds facts in.
  // With `conditions`, also its conditional effects' conditions, which may
  // be false: sources of group transitions only (an extra edge can only
  // shorten a way), never a context.
  auto needs = [&](int op, bool conditions, std::vector<GroupMember>* out) {
    out->clear();
    const task::Action& action = actions[static_cast<std::size_t>(op / 2)];
    const bool is_end = op % 2 == 1;
    if (!is_end) {
      out->insert(out->end(), action.at_start.positive.begin(), action.at_start.positive.end());
    } else {
      out->insert(out->end(), action.over_all.positive.begin(), action.over_all.positive.end());
      out->insert(out->end(), action.at_end.positive.begin(), action.at_end.positive.end());
    }
    if (!conditions) return;
    const task::Effects& eff = is_end ? action.end_effects : action.start_effects;
    for (const auto& ce : eff.conditional) {
      out->insert(out->end(), ce.condition.positive.begin(), ce.condition.positive.end());
    }
  };
  // Transitions of each group: a snap moves its token from a member it
  // needs to a member it adds (the invariant: every snap adding a member
  // deletes one it requires). Leaving a running marker takes the action's
  // minimum duration; every other step takes no time.
  struct Edge {
    std::int32_t from, to;  // indices into the group
    double s;
  };
  std::vector<std::vector<Edge>> edges(groups.size());
  auto index_in = [&](std::size_t g, GroupMember m) {
    const auto& members_of = groups[g];
    return static_cast<std::int32_t>(std::lower_bound(members_of.begin(), members_of.end(), m) -
                                     members_of.begin());
  };
  // Calls visit(g) for each group `a` and `b` are both in.
  auto for_each_shared_group = [&](GroupMember a, GroupMember b, auto&& visit) {
    const auto of_b = mutex.GroupsOf(b);
    for (auto g : mutex.GroupsOf(a)) {
      if (std::find(of_b.begin(), of_b.end(), g) != of_b.end()) visit(static_cast<std::size_t>(g));
    }
  };
  std::vector<GroupMember> from, to;
  for (int op = 0; op < num_ops_; ++op) {
    if (missing_init_[op] >= (1 << 30)) continue;  // an instantaneous action's end
    const auto a = static_cast<task::ActionId>(op / 2);
    const bool is_end = op % 2 == 1;
    needs(op, true, &from);
    if (is_end) from.push_back(RunningMember(a));
    to.assign(add_.begin() + add_begin_[op], add_.begin() + add_begin_[op + 1]);
    for (auto& m : to) {
      if (m >= num_facts_) m = RunningMember(m - num_facts_);  // started(a)
    }
    for (GroupMember f : from) {
      for (GroupMember t : to) {
        if (t == f) continue;
        const double s = is_end && f == RunningMember(a) ? static_min_d_[a] : 0.0;
        for_each_shared_group(f, t, [&](std::size_t g) {
          edges[g].push_back({index_in(g, f), index_in(g, t), s});
        });
      }
    }
  }
  // Each group's edges by source member, found by binary search.
  auto by_from = [](const Edge& x, const Edge& y) { return x.from < y.from; };
  for (auto& list : edges) std::sort(list.begin(), list.end(), by_from);
  // Shortest times from one member of a group to the others (a Dijkstra
  // per source, cached). Past a budget of edges relaxed, a way counts as
  // taking no time: a lower bound still.
  std::vector<std::vector<std::vector<double>>> from_member(groups.size());
  std::size_t edges_relaxed = 0;
  std::vector<std::pair<double, std::int32_t>> queue;
  auto shortest = [&](std::size_t g, GroupMember source, GroupMember target) {
    auto& rows = from_member[g];
    if (rows.empty()) rows.resize(groups[g].size());
    auto& row = rows[static_cast<std::size_t>(index_in(g, source))];
    if (row.empty()) {
      if (edges_relaxed > kMaxEdgesRelaxed) return 0.0;
      row.assign(groups[g].size(), kInfinity);
      row[static_cast<std::size_t>(index_in(g, source))] = 0.0;
      queue.assign(1, {0.0, index_in(g, source)});
      while (!queue.empty()) {
        std::pop_heap(queue.begin(), queue.end(), std::greater<>());
        const auto [d, at] = queue.back();
        queue.pop_back();
        if (d > row[static_cast<std::size_t>(at)]) continue;
        const auto [first, last] =
            std::equal_range(edges[g].begin(), edges[g].end(), Edge{at, 0, 0.0}, by_from);
        for (auto edge = first; edge != last; ++edge) {
          ++edges_relaxed;
          auto& best = row[static_cast<std::size_t>(edge->to)];
          if (d + edge->s < best) {
            best = d + edge->s;
            queue.emplace_back(best, edge->to);
            std::push_heap(queue.begin(), queue.end(), std::greater<>());
          }
        }
      }
    }
    return row[static_cast<std::size_t>(index_in(g, target))];
  };

  // The snaps adding each fact.
  std::vector<std::vector<std::int32_t>> adders(static_cast<std::size_t>(num_facts_));
  for (int op = 0; op < num_ops_; ++op) {
    for (int i = add_begin_[op]; i < add_begin_[op + 1]; ++i) {
      if (add_[i] < num_facts_) adders[static_cast<std::size_t>(add_[i])].push_back(op);
    }
  }
  // How long after `op` adds a fact the member q can hold: the longest of
  // the ways from the members of q's groups that op needs (0 when none; an
  // unreachable q is left to the rest of the exploration).
  auto delay = [&](int op, task::FactId q) {
    needs(op, false, &from);
    double longest = 0.0;
    for (GroupMember m : from) {
      if (m == q) continue;
      for_each_shared_group(m, q, [&](std::size_t g) {
        const double d = shortest(g, m, q);
        if (d < kInfinity) longest = std::max(longest, d);
      });
    }
    return longest;
  };

  // Pair facts for the starts' conditions.
  std::map<std::pair<task::FactId, task::FactId>, std::int32_t> pair_of;
  std::vector<std::vector<std::int32_t>> extra_pre(static_cast<std::size_t>(num_ops_));
  std::vector<std::vector<std::pair<std::int32_t, double>>> reached_by(
      static_cast<std::size_t>(num_ops_));
  std::vector<std::vector<std::int32_t>> pairs_of_fact(static_cast<std::size_t>(num_facts_));
  int next_pair = pair_base_;
  std::size_t pair_reaches = 0;
  const std::size_t max_pair_reaches = kPairReachesPerSnap * static_cast<std::size_t>(num_ops_);
  for (int op = 0; op < num_ops_; op += 2) {
    for (int i = pre_begin_[op]; i < pre_begin_[op + 1]; ++i) {
      const task::FactId q = pre_[i];
      if (q >= num_facts_ || mutex.GroupsOf(q).empty()) continue;
      for (int j = pre_begin_[op]; j < pre_begin_[op + 1]; ++j) {
        const task::FactId p = pre_[j];
        if (p == q || p >= num_facts_ || mutex.Mutex(p, q)) continue;
        auto [it, fresh] = pair_of.try_emplace({p, q}, -1);
        const auto& achievers = adders[static_cast<std::size_t>(p)];
        if (fresh && pair_reaches + achievers.size() <= max_pair_reaches) {
          std::vector<std::pair<std::int32_t, double>> delays;
          bool later = false;
          for (auto adder : achievers) {
            delays.emplace_back(adder, delay(adder, q));
            later = later || delays.back().second > 0.0;
          }
          // it->second stays -1 when there is nothing to wait for, or when
          // the pair would add more work per evaluation than the budget
          // (any subset of the pairs keeps the bound).
          if (!later) continue;
          pair_reaches += delays.size();
          it->second = next_pair++;
          for (const auto& [adder, d] : delays) {
            reached_by[static_cast<std::size_t>(adder)].emplace_back(it->second, d);
          }
          pairs_of_fact[static_cast<std::size_t>(p)].push_back(it->second);
        }
        if (it->second >= 0) extra_pre[static_cast<std::size_t>(op)].push_back(it->second);
      }
    }
  }
  if (next_pair == pair_base_) return;

  // Rebuild the condition table with the pairs (a start keeps p and q too).
  std::vector<std::int32_t> pre_begin{0}, pre;
  for (int op = 0; op < num_ops_; ++op) {
    pre.insert(pre.end(), pre_.begin() + pre_begin_[op], pre_.begin() + pre_begin_[op + 1]);
    const auto& extra = extra_pre[static_cast<std::size_t>(op)];
    pre.insert(pre.end(), extra.begin(), extra.end());
    if (missing_init_[op] < (1 << 30)) missing_init_[op] += static_cast<std::int32_t>(extra.size());
    pre_begin.push_back(static_cast<std::int32_t>(pre.size()));
  }
  pre_ = std::move(pre);
  pre_begin_ = std::move(pre_begin);
  op_pairs_begin_.assign(1, 0);
  for (int op = 0; op < num_ops_; ++op) {
    for (const auto& [pair, d] : reached_by[static_cast<std::size_t>(op)]) {
      op_pairs_.push_back(pair);
      op_pair_delay_s_.push_back(d);
    }
    op_pairs_begin_.push_back(static_cast<std::int32_t>(op_pairs_.size()));
  }
  fact_pairs_begin_.assign(1, 0);
  for (const auto& pairs : pairs_of_fact) {
    fact_pairs_.insert(fact_pairs_.end(), pairs.begin(), pairs.end());
    fact_pairs_begin_.push_back(static_cast<std::int32_t>(fact_pairs_.size()));
  }
  IndexConditions(next_pair);
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

const TemporalReachability::FactTimes& TemporalReachability::ScheduleTimes(
    task::FactId f, const Timeline& timeline) {
  FactTimes& times = fact_times_[static_cast<std::size_t>(f)];
  std::uint32_t& stamp = fact_times_stamp_[static_cast<std::size_t>(f)];
  if (stamp != evaluation_) {
    stamp = evaluation_;
    times = {timeline.FactWrittenAt(f), timeline.FactReadUntil(f)};
  }
  return times;
}

double TemporalReachability::ScheduleBound(int op, const Timeline& timeline) {
  double t = 0.0;
  for (int i = schedule_begin_[op]; i < schedule_begin_[op + 1]; ++i) {
    const std::int32_t entry = schedule_facts_[static_cast<std::size_t>(i)];
    const FactTimes& times = ScheduleTimes(entry >> 1, timeline);
    t = std::max(t, (entry & 1) != 0 ? times.read_until_s : times.written_s);
  }
  return t;
}

void TemporalReachability::ReachFromState(int fact, double time_s) {
  Reach(fact, time_s, -1);
  for (int i = fact_pairs_begin_[fact]; i < fact_pairs_begin_[fact + 1]; ++i) {
    Reach(fact_pairs_[i], time_s, -1);
  }
}

void TemporalReachability::Reach(int fact, double time_s, int achiever) {
  if (!(time_s < earliest_[fact])) return;
  earliest_[fact] = time_s;
  achiever_[fact] = achiever;
  if (time_s <= now_s_) {
    now_.push_back({time_s, fact});  // a snap at the time being popped
  } else {
    later_.Push(time_s, fact);
  }
}

bool TemporalReachability::PopEarliest(Entry* next) {
  if (next_now_ < now_.size()) {
    *next = now_[next_now_++];
    return true;
  }
  now_.clear();
  next_now_ = 0;
  if (later_.empty()) return false;
  *next = later_.Pop();
  now_s_ = next->time_s;
  return true;
}

bool TemporalReachability::Evaluate(const StateData& state, const Timeline& timeline) {
  if (++evaluation_ == 0) {  // wrapped: no stamp may look current
    std::fill(fact_times_stamp_.begin(), fact_times_stamp_.end(), 0);
    evaluation_ = 1;
  }
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
  later_.Clear();
  now_.clear();
  next_now_ = 0;
  now_s_ = -kInfinity;  // the state's facts all go to later_
  for (std::size_t w = 0; w < state.facts.size(); ++w) {
    std::uint64_t bits = state.facts[w];
    while (bits) {
      const int f = static_cast<int>(w * 64) + __builtin_ctzll(bits);
      bits &= bits - 1;
      if (!window_fact_[f]) ReachFromState(f, timeline.FactWrittenAt(f));
    }
  }
  for (std::size_t k = static_cast<std::size_t>(state.next_til); k < tils.size(); ++k) {
    for (auto f : tils[k].add) {
      if (!window_fact_[f]) ReachFromState(f, tils[k].time_s);
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
    for (int i = op_pairs_begin_[op]; i < op_pairs_begin_[op + 1]; ++i) {
      Reach(op_pairs_[i], t + op_pair_delay_s_[i], op);
    }
  };
  for (auto op : no_pre_ops_) fire(op, 0.0);
  Entry next;
  while (PopEarliest(&next)) {
    const double t = next.time_s;
    const int f = next.id;
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
    for (int i = pre_begin_[op]; i < pre_begin_[op + 1]; ++i) {
      if (pre_[i] < pair_base_) mark_fact(pre_[i]);
    }
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
        from_state = pre_[i] >= pair_base_ || achiever_[pre_[i]] < 0;
      }
      if (from_state) preferred->push_back(op);
    }
    std::sort(preferred->begin(), preferred->end());
  }
  return h;
}

}  // namespace seaplan::search
