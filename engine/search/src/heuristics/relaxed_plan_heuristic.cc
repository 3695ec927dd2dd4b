#include "relaxed_plan_heuristic.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

namespace seaplan::search {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Layers in which only numeric intervals widen before giving up: enough
// for counters that must be raised a few dozen times.
constexpr int kMaxStagnantLayers = 64;

void AddConditionFacts(const task::Condition& c, std::vector<std::int32_t>& out) {
  out.insert(out.end(), c.positive.begin(), c.positive.end());
}

bool ConditionHoldsNumeric(const task::NumericCondition& c, const StateData& state) {
  auto l = c.lhs.Evaluate(state.values);
  auto r = c.rhs.Evaluate(state.values);
  return l && r && !std::isnan(*l) && !std::isnan(*r) && task::Compare(*l, c.comparator, *r);
}

}  // namespace

RelaxedPlanHeuristic::RelaxedPlanHeuristic(const SnapTask& task, double epsilon_s)
    : task_(task),
      num_facts_(task.num_facts()),
      num_ops_(2 * task.num_actions()),
      epsilon_s_(epsilon_s),
      agents_(task) {
  const int total_facts = num_facts_ + task.num_actions();
  const auto& actions = task.task().actions;
  std::vector<std::int32_t> pre_begin{0}, pre;
  add_begin_.push_back(0);
  num_pre_.resize(static_cast<std::size_t>(num_ops_));
  num_eff_.resize(static_cast<std::size_t>(num_ops_));
  op_exists_.assign(static_cast<std::size_t>(num_ops_), false);
  std::vector<std::int32_t> tmp;
  for (int op = 0; op < num_ops_; ++op) {
    const int a = op / 2;
    const bool is_end = op % 2 == 1;
    const task::Action& action = actions[static_cast<std::size_t>(a)];
    op_exists_[op] = (!is_end || action.is_durative) && !task.Pruned(a);
    tmp.clear();
    if (op_exists_[op]) {
      AddConditionFacts(is_end ? action.at_end : action.at_start, tmp);
      if (action.is_durative) AddConditionFacts(action.over_all, tmp);
      if (is_end) tmp.push_back(num_facts_ + a);
      std::sort(tmp.begin(), tmp.end());
      tmp.erase(std::unique(tmp.begin(), tmp.end()), tmp.end());
    }
    pre.insert(pre.end(), tmp.begin(), tmp.end());
    pre_begin.push_back(static_cast<std::int32_t>(pre.size()));
    tmp.clear();
    if (op_exists_[op]) {
      const task::Effects& eff = is_end ? action.end_effects : action.start_effects;
      tmp.insert(tmp.end(), eff.add.begin(), eff.add.end());
      for (const auto& ce : eff.conditional) tmp.insert(tmp.end(), ce.add.begin(), ce.add.end());
      if (!is_end && action.is_durative) tmp.push_back(num_facts_ + a);
      std::sort(tmp.begin(), tmp.end());
      tmp.erase(std::unique(tmp.begin(), tmp.end()), tmp.end());
      for (const auto& c : (is_end ? action.at_end : action.at_start).numeric)
        num_pre_[op].push_back(&c);
      if (action.is_durative) {
        for (const auto& c : action.over_all.numeric) num_pre_[op].push_back(&c);
      }
      for (const auto& e : eff.numeric) num_eff_[op].push_back(&e);
      for (const auto& ce : eff.conditional) {
        for (const auto& e : ce.numeric) num_eff_[op].push_back(&e);
      }
    }
    add_.insert(add_.end(), tmp.begin(), tmp.end());
    add_begin_.push_back(static_cast<std::int32_t>(add_.size()));
  }
  has_num_pre_.resize(static_cast<std::size_t>(num_ops_));
  has_num_eff_.resize(static_cast<std::size_t>(num_ops_));
  for (int op = 0; op < num_ops_; ++op) {
    has_num_pre_[op] = !num_pre_[op].empty();
    has_num_eff_[op] = !num_eff_[op].empty();
  }
  window_facts_.resize(actions.size());
  min_invariant_duration_.assign(static_cast<std::size_t>(num_facts_), kInf);
  suppressed_.assign(static_cast<std::size_t>(num_facts_), 0);
  for (std::size_t a = 0; a < actions.size(); ++a) {
    const auto& action = actions[a];
    if (!action.is_durative) continue;
    if (task.IsWindowAction(static_cast<task::ActionId>(a))) {
      for (auto f : action.end_effects.del) {
        if (std::find(action.start_effects.add.begin(), action.start_effects.add.end(), f) !=
            action.start_effects.add.end()) {
          window_facts_[a].push_back(f);
        }
      }
    }
    const double d = action.ConstantDuration().value_or(0.0);
    for (auto f : action.over_all.positive) {
      min_invariant_duration_[f] = std::min(min_invariant_duration_[f], d);
    }
  }
  exact_ = BuildExploration(std::move(pre_begin), std::move(pre), op_exists_);
  fact_layer_.resize(static_cast<std::size_t>(total_facts));
  undoes_goal_.resize(static_cast<std::size_t>(total_facts));
  goal_undone_.resize(static_cast<std::size_t>(total_facts));
  fact_achiever_.resize(static_cast<std::size_t>(total_facts));
  fact_marked_.resize(static_cast<std::size_t>(total_facts));
  op_layer_.resize(static_cast<std::size_t>(num_ops_));
  op_missing_.resize(static_cast<std::size_t>(num_ops_));
  op_undo_stamp_.resize(static_cast<std::size_t>(num_ops_));
  op_marked_.resize(static_cast<std::size_t>(num_ops_));
  interval_.resize(static_cast<std::size_t>(task.num_vars()));
  next_interval_.resize(static_cast<std::size_t>(task.num_vars()));
  raiser_.resize(static_cast<std::size_t>(task.num_vars()));
  raise_layer_.resize(static_cast<std::size_t>(task.num_vars()));
  lowerer_.resize(static_cast<std::size_t>(task.num_vars()));
  lower_layer_.resize(static_cast<std::size_t>(task.num_vars()));
  til_fact_.resize(static_cast<std::size_t>(num_facts_));
  goal_fact_.assign(static_cast<std::size_t>(total_facts), 0);
  for (auto f : task.task().goal.positive) {
    if (!goal_fact_[f]) {
      goal_fact_[f] = 1;
      ++num_goal_facts_;
    }
  }
  goal_del_begin_.push_back(0);
  for (int op = 0; op < num_ops_; ++op) {
    if (op_exists_[op]) {
      const task::Action& action = actions[static_cast<std::size_t>(op / 2)];
      for (auto f : (op % 2 == 1 ? action.end_effects : action.start_effects).del) {
        if (goal_fact_[f]) goal_del_.push_back(f);
      }
    }
    goal_del_begin_.push_back(static_cast<std::int32_t>(goal_del_.size()));
  }
  if (agents_.active()) {
    std::vector<std::int32_t> adders(static_cast<std::size_t>(num_facts_) + 1, 0);
    for (auto f : add_) {
      if (f < num_facts_) ++adders[f + 1];
    }
    for (std::size_t i = 1; i < adders.size(); ++i) adders[i] += adders[i - 1];
    adder_begin_ = adders;
    adder_.resize(static_cast<std::size_t>(adders.back()));
    for (int op = 0; op < num_ops_; ++op) {
      for (int i = add_begin_[op]; i < add_begin_[op + 1]; ++i) {
        if (add_[i] < num_facts_) adder_[adders[add_[i]]++] = op;
      }
    }
    op_stamp_.assign(static_cast<std::size_t>(num_ops_), 0);
    op_time_s_.assign(static_cast<std::size_t>(num_ops_), 0.0);
    fact_time_s_.assign(static_cast<std::size_t>(total_facts), 0.0);
  }
  GroupOperators();
}

RelaxedPlanHeuristic::Exploration RelaxedPlanHeuristic::BuildExploration(
    std::vector<std::int32_t> pre_begin, std::vector<std::int32_t> pre,
    const std::vector<bool>& exists) const {
  const auto& actions = task_.task().actions;
  const int started_end = num_facts_ + task_.num_actions();
  Exploration x;
  x.pre_begin = std::move(pre_begin);
  x.pre = std::move(pre);
  // An end is triggered by started(a) and its at-end conditions only (see
  // fact_ops); a group's "some alternative" fact is an over-all one there.
  auto triggers = [&](int op, std::int32_t f) {
    if (op % 2 == 0) return true;
    if (f >= num_facts_) return f < started_end;
    const auto& at_end = actions[static_cast<std::size_t>(op / 2)].at_end.positive;
    return std::find(at_end.begin(), at_end.end(), f) != at_end.end();
  };
  std::vector<std::int32_t> count(static_cast<std::size_t>(started_end + num_aux_) + 1, 0);
  x.op_missing_init.assign(static_cast<std::size_t>(num_ops_), 1 << 30);
  for (int op = 0; op < num_ops_; ++op) {
    if (!exists[op]) continue;
    std::int32_t n = 0;
    for (auto f : CsrRow(x.pre, x.pre_begin, op)) {
      if (!triggers(op, f)) continue;
      ++count[f + 1];
      ++n;
    }
    x.op_missing_init[op] = n;
    if (x.pre_begin[op + 1] == x.pre_begin[op]) x.no_pre_ops.push_back(op);
  }
  for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
  x.fact_ops_begin = count;
  x.fact_ops.resize(static_cast<std::size_t>(count.back()));
  std::vector<std::int32_t> fill(count.begin(), count.end() - 1);
  for (int op = 0; op < num_ops_; ++op) {
    if (!exists[op]) continue;
    for (auto f : CsrRow(x.pre, x.pre_begin, op)) {
      if (triggers(op, f)) x.fact_ops[fill[f]++] = op;
    }
  }
  x.pair_check.assign(static_cast<std::size_t>(num_ops_), PairCheck{});
  for (int op = 0; op < num_ops_; op += 2) {
    const int end = op + 1;
    if (!exists[op] || !actions[static_cast<std::size_t>(op / 2)].is_durative || has_num_eff_[op] ||
        has_num_eff_[end] || has_num_pre_[end]) {
      continue;
    }
    PairCheck& c = x.pair_check[static_cast<std::size_t>(op)];
    c.begin = static_cast<std::int32_t>(x.pair_facts.size());
    c.started = num_facts_ + op / 2;
    for (int i = add_begin_[op]; i < add_begin_[op + 1]; ++i) {
      if (add_[i] < num_facts_) x.pair_facts.push_back(add_[i]);
    }
    x.pair_facts.insert(x.pair_facts.end(), add_.begin() + add_begin_[end],
                        add_.begin() + add_begin_[end + 1]);
    for (int i = x.pre_begin[end]; i < x.pre_begin[end + 1]; ++i) {
      if (x.pre[i] != c.started) x.pair_facts.push_back(x.pre[i]);
    }
    c.end = static_cast<std::int32_t>(x.pair_facts.size());
  }
  return x;
}

namespace {

// splitmix64's finaliser.
std::uint64_t Mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

// A fact's share of an order-free hash of a set of facts: the sum.
std::uint64_t FactHash(task::FactId f) {
  return Mix(static_cast<std::uint32_t>(f));
}

std::uint64_t SetHash(const std::vector<task::FactId>& facts) {
  std::uint64_t h = 0;
  for (auto f : facts) h += FactHash(f);
  return h;
}

// Appends the sorted facts of `facts` but `skip`, then a separator.
void AppendSortedWithout(const std::vector<task::FactId>& facts, task::FactId skip,
                         std::vector<std::int32_t>& key) {
  const auto from = key.size();
  for (auto f : facts) {
    if (f != skip) key.push_back(f);
  }
  std::sort(key.begin() + static_cast<std::ptrdiff_t>(from), key.end());
  key.erase(std::unique(key.begin() + static_cast<std::ptrdiff_t>(from), key.end()), key.end());
  key.push_back(-1);
}

bool Contains(const std::vector<task::FactId>& facts, task::FactId f) {
  return std::find(facts.begin(), facts.end(), f) != facts.end();
}

// Everything the relaxation reads of `action` but its condition `f`.
void RelaxedKey(const task::Action& action, task::FactId f, std::vector<std::int32_t>& key) {
  key.clear();
  key.push_back(action.is_durative ? 1 : 0);
  key.push_back((Contains(action.at_start.positive, f) ? 1 : 0) +
                (Contains(action.over_all.positive, f) ? 2 : 0));
  AppendSortedWithout(action.at_start.positive, f, key);
  AppendSortedWithout(action.over_all.positive, f, key);
  AppendSortedWithout(action.at_end.positive, -1, key);
  // The relaxation ignores negative conditions, but a member given as
  // helpful must be as applicable as any other.
  AppendSortedWithout(action.at_start.negative, -1, key);
  AppendSortedWithout(action.over_all.negative, -1, key);
  AppendSortedWithout(action.at_end.negative, -1, key);
  AppendSortedWithout(action.start_effects.add, -1, key);
  AppendSortedWithout(action.start_effects.del, -1, key);
  AppendSortedWithout(action.end_effects.add, -1, key);
  AppendSortedWithout(action.end_effects.del, -1, key);
}

}  // namespace

void RelaxedPlanHeuristic::GroupOperators() {
  const auto& actions = task_.task().actions;
  const int num_actions = task_.num_actions();
  rep_of_.resize(static_cast<std::size_t>(num_actions));
  for (int a = 0; a < num_actions; ++a) rep_of_[a] = a;
  alt_fact_.assign(static_cast<std::size_t>(num_actions), -1);
  group_of_.assign(static_cast<std::size_t>(num_actions), -1);
  bool windows = false;
  for (int a = 0; a < num_actions && !windows; ++a) windows = task_.IsWindowAction(a);
  auto plain = [&](int a) {
    const task::Action& action = actions[static_cast<std::size_t>(a)];
    if (!op_exists_[2 * a] || has_num_pre_[2 * a] || has_num_eff_[2 * a]) return false;
    if (action.is_durative && (has_num_pre_[2 * a + 1] || has_num_eff_[2 * a + 1])) return false;
    return action.start_effects.conditional.empty() && action.end_effects.conditional.empty();
  };
  // Each action under each of its start and over-all condition facts (not
  // an at-end one: those trigger ends), hashed by everything the relaxation
  // reads of it but that fact. Order-free set hashes, so that nothing is
  // sorted or allocated per candidate; equal hashes are checked below.
  struct Candidate {
    std::uint64_t hash;
    std::int32_t action, fact, key = -1;
  };
  std::vector<Candidate> candidates;
  for (int a = 0; a < num_actions && !windows; ++a) {
    if (!plain(a)) continue;
    const task::Action& action = actions[static_cast<std::size_t>(a)];
    std::uint64_t rest = action.is_durative ? 1 : 2;
    for (const auto* facts :
         {&action.at_end.positive, &action.at_start.negative, &action.over_all.negative,
          &action.at_end.negative, &action.start_effects.add, &action.start_effects.del,
          &action.end_effects.add, &action.end_effects.del}) {
      rest = Mix(rest ^ SetHash(*facts));
    }
    const std::uint64_t start_sum = SetHash(action.at_start.positive);
    const std::uint64_t over_all_sum = SetHash(action.over_all.positive);
    for (const auto* facts : {&action.at_start.positive, &action.over_all.positive}) {
      for (auto it = facts->begin(); it != facts->end(); ++it) {
        const task::FactId f = *it;
        const bool at_start = Contains(action.at_start.positive, f);
        const bool over_all = Contains(action.over_all.positive, f);
        if (Contains(action.at_end.positive, f) || std::find(facts->begin(), it, f) != it ||
            (facts == &action.over_all.positive && at_start)) {
          continue;  // an end's trigger, or seen already
        }
        const std::uint64_t hash = Mix(Mix(rest ^ (start_sum - (at_start ? FactHash(f) : 0))) ^
                                       (over_all_sum - (over_all ? FactHash(f) : 0))) ^
                                   (at_start ? 1 : 0) ^ (over_all ? 2 : 0);
        candidates.push_back({hash, a, f});
      }
    }
  }
  // Candidates stay in action order; `by_hash` visits them by hash.
  std::vector<std::int32_t> by_hash(candidates.size());
  for (std::size_t i = 0; i < by_hash.size(); ++i) by_hash[i] = static_cast<std::int32_t>(i);
  std::sort(by_hash.begin(), by_hash.end(), [&](std::int32_t x, std::int32_t y) {
    return candidates[x].hash != candidates[y].hash ? candidates[x].hash < candidates[y].hash
                                                    : x < y;
  });
  // Within a run of equal hashes, the members whose key equals the first's
  // share a key id (a candidate that only collided stays alone).
  std::vector<std::int32_t> key_size;
  std::vector<std::int32_t> first_key, key;
  for (std::size_t i = 0; i < by_hash.size();) {
    const Candidate& first = candidates[by_hash[i]];
    std::size_t j = i + 1;
    while (j < by_hash.size() && candidates[by_hash[j]].hash == first.hash) ++j;
    if (j - i >= 2) {
      const auto id = static_cast<std::int32_t>(key_size.size());
      key_size.push_back(0);
      RelaxedKey(actions[static_cast<std::size_t>(first.action)], first.fact, first_key);
      for (std::size_t k = i; k < j; ++k) {
        Candidate& c = candidates[by_hash[k]];
        if (k > i) {
          RelaxedKey(actions[static_cast<std::size_t>(c.action)], c.fact, key);
          if (key != first_key) continue;
        }
        c.key = id;
        ++key_size[static_cast<std::size_t>(id)];
      }
    }
    i = j;
  }
  // Each action joins its largest candidate group (the first on ties);
  // groups left with one member are none.
  auto size_of = [&](const Candidate& c) {
    return c.key < 0 ? 0 : key_size[static_cast<std::size_t>(c.key)];
  };
  std::vector<Candidate> chosen;
  for (std::size_t i = 0; i < candidates.size();) {
    std::size_t best = i, j = i;
    for (; j < candidates.size() && candidates[j].action == candidates[i].action; ++j) {
      if (size_of(candidates[j]) > size_of(candidates[best])) best = j;
    }
    if (size_of(candidates[best]) >= 2) chosen.push_back(candidates[best]);
    i = j;
  }
  candidates.clear();
  std::stable_sort(chosen.begin(), chosen.end(),
                   [](const Candidate& x, const Candidate& y) { return x.key < y.key; });
  std::map<std::vector<std::int32_t>, std::int32_t> aux_ids;  // alternatives -> aux
  std::vector<std::int32_t> alternatives;
  std::vector<std::pair<std::int32_t, std::int32_t>> fact_aux;  // (fact, aux)
  for (std::size_t i = 0; i < chosen.size();) {
    std::size_t j = i;
    while (j < chosen.size() && chosen[j].key == chosen[i].key) ++j;
    if (j - i >= 2) {
      const int group = static_cast<int>(group_begin_.size()) - 1;
      alternatives.clear();
      for (std::size_t k = i; k < j; ++k) {
        const int a = chosen[k].action;
        rep_of_[a] = chosen[i].action;
        alt_fact_[a] = chosen[k].fact;
        group_of_[a] = group;
        group_members_.push_back(a);
        alternatives.push_back(chosen[k].fact);
      }
      group_begin_.push_back(static_cast<std::int32_t>(group_members_.size()));
      std::sort(alternatives.begin(), alternatives.end());
      const auto [it, fresh] =
          aux_ids.try_emplace(alternatives, static_cast<std::int32_t>(aux_ids.size()));
      if (fresh) {
        for (auto f : alternatives) fact_aux.emplace_back(f, it->second);
      }
      group_aux_.push_back(it->second);  // made a fact id below
    }
    i = j;
  }
  if (group_aux_.empty()) return;  // grouped_ stays empty, and unread
  aux_base_ = num_facts_ + num_actions;
  num_aux_ = static_cast<int>(aux_ids.size());
  for (auto& aux : group_aux_) aux += aux_base_;
  std::vector<std::int32_t> aux_count(static_cast<std::size_t>(num_facts_) + 1, 0);
  for (const auto& [f, aux] : fact_aux) ++aux_count[static_cast<std::size_t>(f) + 1];
  for (std::size_t i = 1; i < aux_count.size(); ++i) aux_count[i] += aux_count[i - 1];
  fact_aux_begin_ = aux_count;
  fact_aux_.resize(fact_aux.size());
  for (const auto& [f, aux] : fact_aux) fact_aux_[aux_count[f]++] = aux_base_ + aux;
  // The grouped tables: members but the representative do not exist, and
  // the representative's alternative reads "some alternative".
  std::vector<bool> exists = op_exists_;
  std::vector<std::int32_t> pre_begin{0}, pre;
  for (int op = 0; op < num_ops_; ++op) {
    const int a = op / 2;
    if (rep_of_[a] != a) exists[op] = false;
    for (auto f : CsrRow(exact_.pre, exact_.pre_begin, op)) {
      pre.push_back(group_of_[a] >= 0 && f == alt_fact_[a] ? group_aux_[group_of_[a]] : f);
    }
    pre_begin.push_back(static_cast<std::int32_t>(pre.size()));
  }
  grouped_ = BuildExploration(std::move(pre_begin), std::move(pre), exists);
  const auto total = static_cast<std::size_t>(aux_base_ + num_aux_);
  fact_layer_.resize(total);
  undoes_goal_.resize(total);
  goal_undone_.resize(total);
  fact_achiever_.resize(total);
  fact_marked_.resize(total);
  goal_fact_.resize(total, 0);
  aux_source_.resize(static_cast<std::size_t>(num_aux_));
  started_by_.resize(static_cast<std::size_t>(num_actions));
}

void RelaxedPlanHeuristic::SetMakespanAware(bool on) {
  makespan_aware_ = on && agents_.active();
}

RelaxedPlanHeuristic::Interval RelaxedPlanHeuristic::EvalInterval(const task::NumericExpr& expr,
                                                                  const StateData& state,
                                                                  task::ActionId a) {
  using Op = task::NumericExpr::Op;
  eval_stack_.resize(expr.nodes.size());
  for (std::size_t i = 0; i < expr.nodes.size(); ++i) {
    const auto& n = expr.nodes[i];
    Interval r{0, 0};
    switch (n.op) {
      case Op::kConstant:
        r = {n.value, n.value};
        break;
      case Op::kVariable:
        r = interval_[n.var];
        break;
      case Op::kTotalTime:
        r = {0, kInf};
        break;
      case Op::kDuration: {
        // The duration as it would be in this state (rovers' recharge).
        double lo = 0, hi = kInf;
        if (a >= 0) {
          for (const auto& d : task_.task().actions[a].duration) {
            auto v = d.value.Evaluate(state.values);
            if (!v) continue;
            if (d.comparator == task::Comparator::kEqual) {
              lo = std::max(lo, *v);
              hi = std::min(hi, *v);
            } else if (d.comparator == task::Comparator::kGreaterEqual ||
                       d.comparator == task::Comparator::kGreater) {
              lo = std::max(lo, *v);
            } else {
              hi = std::min(hi, *v);
            }
          }
        }
        if (hi < lo) hi = lo;
        r = {lo, hi};
        break;
      }
      case Op::kAdd: {
        const auto& x = eval_stack_[n.lhs];
        const auto& y = eval_stack_[n.rhs];
        r = {x.lo + y.lo, x.hi + y.hi};
        break;
      }
      case Op::kSub: {
        const auto& x = eval_stack_[n.lhs];
        const auto& y = eval_stack_[n.rhs];
        r = {x.lo - y.hi, x.hi - y.lo};
        break;
      }
      case Op::kMul: {
        const auto& x = eval_stack_[n.lhs];
        const auto& y = eval_stack_[n.rhs];
        double p[4] = {x.lo * y.lo, x.lo * y.hi, x.hi * y.lo, x.hi * y.hi};
        r = {kInf, -kInf};
        for (double v : p) {
          if (std::isnan(v)) v = 0;  // 0 * inf
          r.lo = std::min(r.lo, v);
          r.hi = std::max(r.hi, v);
        }
        break;
      }
      case Op::kDiv: {
        const auto& x = eval_stack_[n.lhs];
        const auto& y = eval_stack_[n.rhs];
        if (y.lo <= 0 && y.hi >= 0) {
          if (y.lo == 0 && y.hi == 0) {
            r = {std::nan(""), std::nan("")};
          } else {
            r = {-kInf, kInf};
          }
        } else {
          double p[4] = {x.lo / y.lo, x.lo / y.hi, x.hi / y.lo, x.hi / y.hi};
          r = {kInf, -kInf};
          for (double v : p) {
            if (std::isnan(v)) v = 0;
            r.lo = std::min(r.lo, v);
            r.hi = std::max(r.hi, v);
          }
        }
        break;
      }
      case Op::kNeg: {
        const auto& x = eval_stack_[n.lhs];
        r = {-x.hi, -x.lo};
        break;
      }
    }
    eval_stack_[i] = r;
  }
  if (expr.nodes.empty()) return {std::nan(""), std::nan("")};
  return eval_stack_.back();
}

bool RelaxedPlanHeuristic::Satisfiable(const task::NumericCondition& c, const StateData& state,
                                       task::ActionId a) {
  const Interval l = EvalInterval(c.lhs, state, a);
  const Interval r = EvalInterval(c.rhs, state, a);
  if (std::isnan(l.lo) || std::isnan(r.lo) || std::isnan(l.hi) || std::isnan(r.hi)) return false;
  constexpr double kTol = 1e-9;
  switch (c.comparator) {
    case task::Comparator::kLess:
      return l.lo < r.hi - kTol;
    case task::Comparator::kLessEqual:
      return l.lo <= r.hi + kTol;
    case task::Comparator::kEqual:
      return l.lo <= r.hi + kTol && r.lo <= l.hi + kTol;
    case task::Comparator::kGreaterEqual:
      return l.hi >= r.lo - kTol;
    case task::Comparator::kGreater:
      return l.hi > r.lo + kTol;
  }
  return false;
}

void RelaxedPlanHeuristic::MarkOp(int op) {
  if (op < 0 || op_marked_[op]) return;
  op_marked_[op] = 1;
  marked_ops_.push_back(op);
  stack_.push_back(op);
  if (makespan_aware_ && (op & 1) == 0) {
    const double d = agents_.DurationOf(op / 2);
    for (auto g : agents_.AgentsOf(op / 2)) load_s_[static_cast<std::size_t>(g)] += d;
  }
}

void RelaxedPlanHeuristic::MarkFact(int fact, int need_layer) {
  if (fact_marked_[fact]) return;
  fact_marked_[fact] = 1;
  marked_facts_.push_back(fact);
  if (fact_layer_[fact] <= 0) return;
  MarkOp(makespan_aware_ ? ChooseAchiever(fact, need_layer) : fact_achiever_[fact]);
}

bool RelaxedPlanHeuristic::DeletesHeldGoal(int op) const {
  for (int i = goal_del_begin_[op]; i < goal_del_begin_[op + 1]; ++i) {
    if (fact_layer_[goal_del_[i]] == 0) return true;
  }
  return false;
}

int RelaxedPlanHeuristic::CountUndoneGoals(const StateData& state) {
  for (auto op : marked_ops_) {
    for (int i = goal_del_begin_[op]; i < goal_del_begin_[op + 1]; ++i) {
      const int g = goal_del_[i];
      if (!state.Holds(g) || goal_undone_[g]) continue;
      if ((op & 1) == 0) {
        const auto end_adds = Adds(op + 1);
        if (std::find(end_adds.begin(), end_adds.end(), g) != end_adds.end()) continue;
      }
      goal_undone_[g] = 1;
      undone_goals_.push_back(g);
    }
  }
  const int undone = static_cast<int>(undone_goals_.size());
  for (auto g : undone_goals_) goal_undone_[g] = 0;
  undone_goals_.clear();
  return undone;
}

double RelaxedPlanHeuristic::FinishEstimate(int op) const {
  const int a = op / 2;
  // A running action's end: its agents' work is already in their ready times.
  if ((op & 1) != 0 && fact_layer_[num_facts_ + a] == 0) return op_time_s_[op];
  double charged_s = 0.0;
  for (auto g : agents_.AgentsOf(a)) {
    charged_s = std::max(
        charged_s, load_s_[static_cast<std::size_t>(g)] - ready_s_[static_cast<std::size_t>(g)]);
  }
  return op_time_s_[op] + charged_s;
}

int RelaxedPlanHeuristic::ChooseAchiever(int fact, int need_layer) const {
  int best = fact_achiever_[fact];
  if (fact >= num_facts_ || best < 0) return best;  // started(a): only its start adds it
  double best_s = FinishEstimate(best);
  for (int i = adder_begin_[fact]; i < adder_begin_[fact + 1]; ++i) {
    const int op = adder_[i];
    if (op == best || op_stamp_[op] != stamp_ || op_layer_[op] >= need_layer) continue;
    const double t = FinishEstimate(op);
    // Strictly earlier (beyond rounding): ties keep FF's first achiever.
    if (t < best_s - 1e-6) {
      best = op;
      best_s = t;
    }
  }
  return best;
}

void RelaxedPlanHeuristic::MarkNumeric(const task::NumericCondition& c, int layer,
                                       const StateData& state, task::ActionId a) {
  for (const auto* expr : {&c.lhs, &c.rhs}) {
    for (const auto& n : expr->nodes) {
      if (n.op != task::NumericExpr::Op::kVariable) continue;
      const auto v = n.var;
      const bool can_raise = raiser_[v] >= 0 && raise_layer_[v] <= layer;
      const bool can_lower = lowerer_[v] >= 0 && lower_layer_[v] <= layer;
      if (can_raise && can_lower) {
        // Which direction does the condition need? Try each half of the
        // final interval around the state's value.
        const Interval saved = interval_[v];
        const double now = state.values[v];
        interval_[v] = {now, saved.hi};
        const bool up = Satisfiable(c, state, a);
        interval_[v] = {saved.lo, now};
        const bool down = Satisfiable(c, state, a);
        interval_[v] = saved;
        if (up && !down) {
          MarkOp(raiser_[v]);
        } else if (down && !up) {
          MarkOp(lowerer_[v]);
        } else if (up && down) {
          MarkOp(raise_layer_[v] <= lower_layer_[v] ? raiser_[v] : lowerer_[v]);
        } else {
          MarkOp(raiser_[v]);
          MarkOp(lowerer_[v]);
        }
      } else if (can_raise) {
        MarkOp(raiser_[v]);
      } else if (can_lower) {
        MarkOp(lowerer_[v]);
      }
    }
  }
}

void RelaxedPlanHeuristic::ExemptRunningEnds(const StateData& state) {
  // A suppressed fact only keeps new actions from counting on a window too
  // short for them; running actions already fit (the schedule holds them
  // inside their envelopes), so the relaxed plan does not re-achieve it for
  // their ends. The exploration needs no exemption: an end never waits for
  // its over-all conditions (Exploration::fact_ops).
  for (const auto& r : state.running) {
    const task::Action& action = task_.task().actions[static_cast<std::size_t>(r.action)];
    for (auto f : action.over_all.positive) {
      if (!suppressed_[f]) continue;
      if (std::find(action.at_end.positive.begin(), action.at_end.positive.end(), f) !=
          action.at_end.positive.end()) {
        continue;
      }
      exempt_ends_.push_back({f, 2 * r.action + 1});
    }
  }
}

bool RelaxedPlanHeuristic::IsExemptEnd(int fact, int op) const {
  for (const auto& [f, o] : exempt_ends_) {
    if (f == fact && o == op) return true;
  }
  return false;
}

bool RelaxedPlanHeuristic::AllGroupMembersUsable(std::span<const std::uint8_t> usable) const {
  if (usable.empty()) return true;
  for (const auto a : group_members_) {
    if (!usable[2 * a] || (op_exists_[2 * a + 1] && !usable[2 * a + 1])) return false;
  }
  return true;
}

int RelaxedPlanHeuristic::Evaluate(const StateData& state, std::vector<SnapId>* preferred,
                                   std::span<const double> window_slack,
                                   std::span<const std::uint8_t> usable, const Timeline* schedule) {
  const bool grouped =
      group_operators_ && num_aux_ > 0 && !makespan_aware_ && AllGroupMembersUsable(usable);
  const Exploration& x = grouped ? grouped_ : exact_;
  // All bytes 0xff is -1 in every int: memset, not an element loop.
  std::memset(fact_layer_.data(), 0xff, fact_layer_.size() * sizeof(fact_layer_[0]));
  // op_layer_ is only read for operators that became applicable (plan
  // operators and numeric changers), which set it: no reset needed.
  std::copy(x.op_missing_init.begin(), x.op_missing_init.end(), op_missing_.begin());
  if (!usable.empty()) {
    for (int op = 0; op < num_ops_; ++op) {
      if (!usable[op]) op_missing_[op] = 1 << 30;
    }
  }
  int goals_left = num_goal_facts_;
  skipped_pairs_ = 0;
  for (std::size_t v = 0; v < interval_.size(); ++v) {
    interval_[v] = {state.values[v], state.values[v]};
    raiser_[v] = lowerer_[v] = -1;
    raise_layer_[v] = lower_layer_[v] = -1;
  }
  applicable_.clear();
  numeric_waiting_.clear();
  new_facts_.clear();
  if (++undo_stamp_ == 0) {  // wrapped: forget every old stamp
    std::fill(op_undo_stamp_.begin(), op_undo_stamp_.end(), 0);
    undo_stamp_ = 1;
  }
  // Previous evaluation's suppressed facts (cleared here, not at its end:
  // one place for both).
  for (auto f : suppressed_list_) suppressed_[f] = 0;
  suppressed_list_.clear();
  exempt_ends_.clear();
  if (makespan_aware_) {
    if (++stamp_ == 0) {  // wrapped: forget every old stamp
      std::fill(op_stamp_.begin(), op_stamp_.end(), 0);
      stamp_ = 1;
    }
    agents_.ReadyTimes(state, schedule, &ready_s_);
  }
  // `time_s`: when the fact holds at the earliest (read only with makespan_aware_).
  const bool keep_held_goals = keep_held_goals_ && !goal_del_.empty() && !makespan_aware_;
  // A group's "some alternative" fact follows the first alternative
  // reached, and, keeping held goals, the first of its layer reached
  // without undoing one, as `reach` does for a fact's achiever.
  auto reach_alternative = [&](int f, int layer, bool undoes_goal) {
    for (int i = fact_aux_begin_[f]; i < fact_aux_begin_[f + 1]; ++i) {
      const int aux = fact_aux_[i];
      if (fact_layer_[aux] < 0) {
        fact_layer_[aux] = layer;
        fact_achiever_[aux] = -1;
        if (keep_held_goals) undoes_goal_[aux] = undoes_goal;
        aux_source_[aux - aux_base_] = f;
        new_facts_.push_back(aux);
      } else if (keep_held_goals && !undoes_goal && fact_layer_[aux] == layer &&
                 undoes_goal_[aux]) {
        undoes_goal_[aux] = 0;
        aux_source_[aux - aux_base_] = f;
      }
    }
  };
  auto reach = [&](int f, int layer, int achiever, double time_s, bool undoes_goal = false) {
    if (fact_layer_[f] >= 0) {
      // Reached earlier in this layer only through an operator that undoes
      // a goal the state holds: this one, in the same layer, keeps them.
      if (keep_held_goals && !undoes_goal && fact_layer_[f] == layer && undoes_goal_[f]) {
        fact_achiever_[f] = achiever;
        undoes_goal_[f] = 0;
        if (grouped && f < num_facts_) reach_alternative(f, layer, false);
      }
      return;
    }
    fact_layer_[f] = layer;
    fact_achiever_[f] = achiever;
    if (keep_held_goals) undoes_goal_[f] = undoes_goal;
    if (makespan_aware_) fact_time_s_[f] = time_s;
    goals_left -= goal_fact_[f];
    new_facts_.push_back(f);
    if (grouped && f < num_facts_) reach_alternative(f, layer, undoes_goal);
  };
  std::size_t window_index = 0;
  for (const auto& r : state.running) {
    if (!task_.IsWindowAction(r.action)) continue;
    const double slack = window_index < window_slack.size() ? window_slack[window_index] : kInf;
    ++window_index;
    for (auto f : window_facts_[r.action]) {
      if (min_invariant_duration_[f] < kInf &&
          slack < min_invariant_duration_[f] + 2 * epsilon_s_ - 1e-9 && !suppressed_[f]) {
        suppressed_[f] = 1;
        suppressed_list_.push_back(f);
      }
    }
  }
  for (std::size_t w = 0; w < state.facts.size(); ++w) {
    std::uint64_t bits = state.facts[w];
    while (bits) {
      const int b = __builtin_ctzll(bits);
      bits &= bits - 1;
      const int f = static_cast<int>(w * 64) + b;
      if (!suppressed_list_.empty() && suppressed_[f]) continue;
      reach(f, 0, -1, 0.0);
    }
  }
  if (!suppressed_list_.empty()) ExemptRunningEnds(state);
  const auto& tils = task_.tils();
  for (std::size_t k = static_cast<std::size_t>(state.next_til); k < tils.size(); ++k) {
    for (auto f : tils[k].add) reach(f, 0, -1, tils[k].time_s);
  }
  for (const auto& r : state.running) {
    const double started_s = schedule != nullptr ? schedule->StartedAt(r.action) : 0.0;
    const int a = grouped ? rep_of_[r.action] : r.action;
    if (grouped && fact_layer_[num_facts_ + a] < 0) started_by_[a] = r.action;
    reach(num_facts_ + a, 0, -1, started_s + r.min_duration_s);
  }
  // An operator whose conditions hold at `layer` is applied there, or, when
  // it undoes a held goal with delay_undoers, kGoalUndoerDelayLayers later;
  // its layer stays the one its conditions hold in, so one the state
  // enables is still helpful.
  const bool delay_undoers = delay_goal_undoers_ && !goal_del_.empty() && !makespan_aware_;
  delayed_.clear();
  std::size_t next_delayed = 0;
  auto make_applicable = [&](int op, int layer) {
    op_layer_[op] = layer;
    if (delay_undoers && DeletesHeldGoal(op)) {
      delayed_.push_back({layer + kGoalUndoerDelayLayers, op});
    } else {
      applicable_.push_back(op);
    }
  };
  // Operators without fact preconditions are enabled from the start.
  for (auto op : x.no_pre_ops) {
    if (!usable.empty() && !usable[op]) continue;
    if (num_pre_[op].empty()) {
      make_applicable(op, 0);
    } else {
      numeric_waiting_.push_back(op);
    }
  }

  const task::Condition& goal = task_.task().goal;
  int layer = 0;
  int stagnant = 0;
  std::size_t processed_applicable = 0;
  std::vector<std::int32_t>& numeric_ops = layer_ops_;  // applicable ops with numeric effects
  numeric_ops.clear();
  int goal_layer = -1;
  // A skipped pair still counts as progress where it would have made some:
  // started(a) new in its layer, end(a) applicable in the next one.
  bool skipped_pair = false, skipped_before = false;
  int skipped = 0;  // skipped_pairs_, kept in a register
  auto numeric_goal_holds = [&]() {
    for (const auto& c : goal.numeric) {
      if (!Satisfiable(c, state, -1)) return false;
    }
    return true;
  };
  // Without numeric goals or agents' times, the extraction reads only the
  // goal facts' achievers from the goal layer: once the last goal fact is
  // reached, the rest of that layer's operators change nothing it reads.
  const bool stop_at_last_goal = goal.numeric.empty() && !makespan_aware_;
  while (true) {
    // Every goal fact reached by the previous layer: the operators these
    // facts would enable are never part of the relaxed plan (its operators
    // come before the goal layer), so the goal layer is not explored.
    if (goals_left == 0 && numeric_goal_holds()) {
      goal_layer = layer;
      break;
    }
    skipped_before = skipped_pair;
    skipped_pair = false;
    // Facts new at this layer enable operators. The hottest loop: raw
    // pointers, so that the counter stores do not force reloads.
    {
      const std::int32_t* const fact_ops = x.fact_ops.data();
      const std::int32_t* const fact_ops_begin = x.fact_ops_begin.data();
      std::int32_t* const missing = op_missing_.data();
      const std::uint8_t* const has_num_pre = has_num_pre_.data();
      const PairCheck* const pairs = x.pair_check.data();
      const std::int32_t* const pair_facts = x.pair_facts.data();
      const std::int32_t* const fact_layer = fact_layer_.data();
      for (auto f : new_facts_) {
        const std::int32_t* const end = fact_ops + fact_ops_begin[f + 1];
        // Its flag is final: facts change it only in the layer that
        // reaches them, before they are counted here.
        if (keep_held_goals && undoes_goal_[f]) {
          for (const std::int32_t* it = fact_ops + fact_ops_begin[f]; it != end; ++it) {
            op_undo_stamp_[*it] = undo_stamp_;
          }
        }
        for (const std::int32_t* it = fact_ops + fact_ops_begin[f]; it != end; ++it) {
          const int op = *it;
          if (--missing[op] != 0) continue;
          if (has_num_pre[op]) {
            numeric_waiting_.push_back(op);
          } else if (PairRedundant(pairs[op], fact_layer, pair_facts)) {
            skipped_pair = true;
            ++skipped;
          } else {
            make_applicable(op, layer);
          }
        }
      }
    }
    for (; next_delayed < delayed_.size() && delayed_[next_delayed].layer <= layer;
         ++next_delayed) {
      applicable_.push_back(delayed_[next_delayed].op);
    }
    for (std::size_t i = 0; i < numeric_waiting_.size();) {
      const int op = numeric_waiting_[i];
      bool ok = true;
      for (const auto* c : num_pre_[op]) {
        if (!Satisfiable(*c, state, op / 2)) {
          ok = false;
          break;
        }
      }
      if (ok) {
        make_applicable(op, layer);
        numeric_waiting_[i] = numeric_waiting_.back();
        numeric_waiting_.pop_back();
      } else {
        ++i;
      }
    }
    // Apply this layer's new operators (facts) and all numeric effects.
    new_facts_.clear();
    const bool new_ops = processed_applicable < applicable_.size();
    for (; processed_applicable < applicable_.size(); ++processed_applicable) {
      const int op = applicable_[processed_applicable];
      double time_s = 0.0, started_s = 0.0;
      if (makespan_aware_) {
        for (int i = x.pre_begin[op]; i < x.pre_begin[op + 1]; ++i) {
          time_s = std::max(time_s, fact_time_s_[x.pre[i]]);
        }
        if ((op & 1) == 0) {
          for (auto g : agents_.AgentsOf(op / 2)) {
            time_s = std::max(time_s, ready_s_[static_cast<std::size_t>(g)]);
          }
        }
        op_time_s_[op] = time_s;
        op_stamp_[op] = stamp_;
        started_s = time_s + agents_.DurationOf(op / 2);
      }
      // An end's over-all conditions do not count it down (Exploration::
      // fact_ops), but they are its start's: started(a) carries their flag.
      const bool undoes_goal =
          keep_held_goals && (op_undo_stamp_[op] == undo_stamp_ || DeletesHeldGoal(op));
      for (int i = add_begin_[op]; i < add_begin_[op + 1]; ++i) {
        reach(add_[i], layer + 1, op, add_[i] < num_facts_ ? time_s : started_s, undoes_goal);
      }
      if (has_num_eff_[op]) numeric_ops.push_back(op);
      // Keeping held goals, the rest of the layer may still reach a goal
      // fact without undoing one.
      if (goals_left == 0 && stop_at_last_goal && !keep_held_goals) break;
    }
    if (goals_left == 0 && stop_at_last_goal) {
      goal_layer = layer + 1;
      break;
    }
    bool widened = false;
    if (!numeric_ops.empty()) {
      next_interval_ = interval_;
      for (auto op : numeric_ops) {
        for (const auto* e : num_eff_[op]) {
          const Interval v = EvalInterval(e->value, state, op / 2);
          Interval& t = next_interval_[e->var];
          const Interval cur = interval_[e->var];
          Interval cand = cur;
          switch (e->op) {
            case task::AssignOp::kAssign:
              cand = v;
              break;
            case task::AssignOp::kIncrease:
              cand = {cur.lo + v.lo, cur.hi + v.hi};
              break;
            case task::AssignOp::kDecrease:
              cand = {cur.lo - v.hi, cur.hi - v.lo};
              break;
            case task::AssignOp::kScaleUp:
            case task::AssignOp::kScaleDown: {
              const bool up = e->op == task::AssignOp::kScaleUp;
              double p[4];
              if (up) {
                p[0] = cur.lo * v.lo;
                p[1] = cur.lo * v.hi;
                p[2] = cur.hi * v.lo;
                p[3] = cur.hi * v.hi;
              } else if (v.lo > 0 || v.hi < 0) {
                p[0] = cur.lo / v.lo;
                p[1] = cur.lo / v.hi;
                p[2] = cur.hi / v.lo;
                p[3] = cur.hi / v.hi;
              } else {
                p[0] = -kInf;
                p[1] = kInf;
                p[2] = -kInf;
                p[3] = kInf;
              }
              cand = {*std::min_element(p, p + 4), *std::max_element(p, p + 4)};
              break;
            }
          }
          if (std::isnan(cand.lo) || std::isnan(cand.hi)) continue;
          // The first operator (of the first layer) that raises or lowers
          // the interval is the variable's changer in that direction.
          const bool undefined = std::isnan(cur.lo) || std::isnan(cur.hi);
          if (raiser_[e->var] < 0 && (undefined || cand.hi > cur.hi)) {
            raiser_[e->var] = op;
            raise_layer_[e->var] = layer + 1;
          }
          if (lowerer_[e->var] < 0 && (undefined || cand.lo < cur.lo)) {
            lowerer_[e->var] = op;
            lower_layer_[e->var] = layer + 1;
          }
          if (std::isnan(t.lo)) {
            t = cand;
          } else {
            t.lo = std::min(t.lo, cand.lo);
            t.hi = std::max(t.hi, cand.hi);
          }
        }
      }
      for (std::size_t v = 0; v < interval_.size(); ++v) {
        const Interval& a = interval_[v];
        const Interval& b = next_interval_[v];
        const bool same = (a.lo == b.lo || (std::isnan(a.lo) && std::isnan(b.lo))) &&
                          (a.hi == b.hi || (std::isnan(a.hi) && std::isnan(b.hi)));
        if (!same) widened = true;
      }
      interval_.swap(next_interval_);
    }
    if (new_facts_.empty() && !new_ops && !skipped_pair && !skipped_before &&
        next_delayed == delayed_.size()) {
      if (!widened || (numeric_waiting_.empty() && goal.numeric.empty())) {
        dead_end_proven_ = true;
        skipped_pairs_ = skipped;
        return kDeadEnd;
      }
      if (++stagnant > kMaxStagnantLayers) {
        dead_end_proven_ = false;
        skipped_pairs_ = skipped;
        return kDeadEnd;
      }
    } else {
      stagnant = 0;
    }
    ++layer;
  }
  skipped_pairs_ = skipped;

  // Extract a relaxed plan backwards from the goal.
  for (auto op : marked_ops_) op_marked_[op] = 0;
  for (auto f : marked_facts_) fact_marked_[f] = 0;
  marked_ops_.clear();
  marked_facts_.clear();
  stack_.clear();
  if (makespan_aware_) load_s_ = ready_s_;
  auto extract_needs = [&]() {
    while (!stack_.empty()) {
      const int op = stack_.back();
      stack_.pop_back();
      for (int i = x.pre_begin[op]; i < x.pre_begin[op + 1]; ++i) {
        const int f = x.pre[i];
        // Every exempt fact is suppressed (ExemptRunningEnds): the scan only
        // for those.
        if (!exempt_ends_.empty() && f < num_facts_ && suppressed_[f] && IsExemptEnd(f, op)) {
          continue;
        }
        // "Some alternative holds": the alternative that got there first.
        MarkFact(f >= aux_base_ && num_aux_ > 0 ? aux_source_[f - aux_base_] : f, op_layer_[op]);
      }
      for (const auto* c : num_pre_[op]) {
        if (!ConditionHoldsNumeric(*c, state)) MarkNumeric(*c, op_layer_[op], state, op / 2);
      }
    }
  };
  // One goal's whole support before the next goal's achiever is chosen, so
  // that the choice sees the work charged so far (the set marked without
  // agents does not depend on the order). Goals are taken in the task's
  // order: taking those reached latest first (as list scheduling does)
  // gave worse first plans on generated fjord missions.
  for (auto f : goal.positive) {
    MarkFact(f, goal_layer);
    extract_needs();
  }
  for (const auto& c : goal.numeric) {
    if (!ConditionHoldsNumeric(c, state)) MarkNumeric(c, goal_layer, state, -1);
  }
  extract_needs();
  int h = static_cast<int>(marked_ops_.size());
  if (keep_held_goals) h += kUndoneGoalCost * CountUndoneGoals(state);
  // Each running action needs its end. Grouped, one marked end stands for
  // the group's representative: a second running member of the group
  // needs one more (the running set is small; a scan back is enough).
  for (std::size_t i = 0; i < state.running.size(); ++i) {
    const int a = grouped ? rep_of_[state.running[i].action] : state.running[i].action;
    bool needs_end = !op_marked_[2 * a + 1];
    for (std::size_t j = 0; grouped && !needs_end && j < i; ++j) {
      needs_end = rep_of_[state.running[j].action] == a;
    }
    if (needs_end) ++h;
  }
  if (preferred) {
    preferred->clear();
    for (auto op : marked_ops_) {
      if (op_layer_[op] != 0) continue;
      const int g = grouped ? group_of_[op / 2] : -1;
      if (g < 0) {
        preferred->push_back(op);
      } else if ((op & 1) != 0) {
        preferred->push_back(2 * started_by_[op / 2] + 1);  // the running member's end
      } else {
        // The member whose alternative the state holds.
        const int source = aux_source_[group_aux_[g] - aux_base_];
        for (int i = group_begin_[g]; i < group_begin_[g + 1]; ++i) {
          if (alt_fact_[group_members_[i]] == source) {
            preferred->push_back(2 * group_members_[i]);
            break;
          }
        }
      }
    }
    std::sort(preferred->begin(), preferred->end());
  }
  return h;
}

}  // namespace seaplan::search
