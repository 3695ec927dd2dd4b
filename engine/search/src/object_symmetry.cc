#include "object_symmetry.h"

#include <algorithm>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>

#include "seaplan/task/grounder.h"

namespace seaplan::search {

namespace {

// Beyond this many ground actions the detection is skipped: its cost grows
// with the actions naming each candidate object.
constexpr std::size_t kMaxActions = 200'000;

bool ExprEqual(const task::NumericExpr& a, const task::NumericExpr& b) {
  if (a.nodes.size() != b.nodes.size()) return false;
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    const auto &x = a.nodes[i], &y = b.nodes[i];
    if (x.op != y.op || x.var != y.var || x.lhs != y.lhs || x.rhs != y.rhs) return false;
    if (x.op == task::NumericExpr::Op::kConstant && x.value != y.value) return false;
  }
  return true;
}

bool NumericConditionsEqual(const std::vector<task::NumericCondition>& a,
                            const std::vector<task::NumericCondition>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].comparator != b[i].comparator || !ExprEqual(a[i].lhs, b[i].lhs) ||
        !ExprEqual(a[i].rhs, b[i].rhs))
      return false;
  }
  return true;
}

bool NumericEffectsEqual(const std::vector<task::NumericEffect>& a,
                         const std::vector<task::NumericEffect>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].var != b[i].var || a[i].op != b[i].op || !ExprEqual(a[i].value, b[i].value))
      return false;
  }
  return true;
}

// The swap of two objects as a map of fact and action ids; built per pair.
// Lookups reuse the swap's scratch lists, so that checking a pair allocates
// once, not per fact and action it maps.
class Swap {
 public:
  Swap(const task::GroundTask& task, const task::FactIndex& facts, const task::ActionIndex& actions,
       const std::string& x, const std::string& y)
      : task_(task), facts_(facts), actions_(actions), x_(x), y_(y) {}

  // The image of fact `f`; -1 when it does not exist or names both objects.
  task::FactId Fact(task::FactId f) const {
    const auto& fact = task_.facts[static_cast<std::size_t>(f)];
    return ImageOf(f, fact.args, [&] { return facts_.Find(fact.predicate, image_); });
  }
  task::ActionId Action(task::ActionId a) const {
    const auto& action = task_.actions[static_cast<std::size_t>(a)];
    return ImageOf(a, action.args,
                   [&] { return actions_.Find(action.name, image_, action.variant); });
  }
  // True when the image of `from` is `to` (as sets).
  bool FactsMap(const std::vector<task::FactId>& from, const std::vector<task::FactId>& to) const {
    if (from.size() != to.size()) return false;
    from_image_.clear();
    for (auto f : from) {
      const task::FactId g = Fact(f);
      if (g < 0) return false;
      from_image_.push_back(g);
    }
    to_sorted_.assign(to.begin(), to.end());
    std::sort(from_image_.begin(), from_image_.end());
    std::sort(to_sorted_.begin(), to_sorted_.end());
    return from_image_ == to_sorted_;
  }
  bool ConditionMaps(const task::Condition& a, const task::Condition& b) const {
    return FactsMap(a.positive, b.positive) && FactsMap(a.negative, b.negative) &&
           NumericConditionsEqual(a.numeric, b.numeric);
  }
  bool EffectsMap(const task::Effects& a, const task::Effects& b) const {
    return a.conditional.empty() && b.conditional.empty() && FactsMap(a.add, b.add) &&
           FactsMap(a.del, b.del) && NumericEffectsEqual(a.numeric, b.numeric);
  }

 private:
  // Which of the two objects `args` names (one, when they are the same
  // object: the swap of an object with itself is the identity).
  enum class Named { kNeither, kOne, kBoth };

  // The image of the fact or action `id` named with `args`: itself when it
  // names neither object, -1 when it names both, else what `find` returns
  // for the swapped arguments (`image_`).
  template <typename Find>
  std::int32_t ImageOf(std::int32_t id, const std::vector<std::string>& args, Find find) const {
    switch (Image(args)) {
      case Named::kBoth:
        return -1;
      case Named::kNeither:
        return id;
      case Named::kOne:
        break;
    }
    return find();
  }

  // `image_` becomes `args` with the two objects swapped (when kOne).
  Named Image(const std::vector<std::string>& args) const {
    bool seen_x = false, seen_y = false;
    for (const auto& a : args) {
      if (a == x_) {
        seen_x = true;
      } else if (a == y_) {
        seen_y = true;
      }
    }
    if (seen_x && seen_y) return Named::kBoth;
    if (!seen_x && !seen_y) return Named::kNeither;
    image_ = args;  // element-wise: reuses the scratch strings' buffers
    for (auto& a : image_) {
      if (a == x_) {
        a = y_;
      } else if (a == y_) {
        a = x_;
      }
    }
    return Named::kOne;
  }

  const task::GroundTask& task_;
  const task::FactIndex& facts_;
  const task::ActionIndex& actions_;
  const std::string& x_;
  const std::string& y_;
  // Scratch.
  mutable std::vector<std::string> image_;
  mutable std::vector<task::FactId> from_image_, to_sorted_;
};

}  // namespace

ObjectSymmetry::ObjectSymmetry(const SnapTask& snap) : task_(snap) {
  const task::GroundTask& task = snap.task();
  if (task.actions.size() > kMaxActions) return;
  std::unordered_map<std::string, int> object_index;
  std::vector<std::string> objects;
  auto object = [&](const std::string& name) {
    auto [it, inserted] = object_index.try_emplace(name, static_cast<int>(objects.size()));
    if (inserted) objects.push_back(name);
    return it->second;
  };
  // Where each object appears: (predicate or action name, position), and
  // the facts and actions naming it.
  std::vector<std::vector<std::string>> occurrences;
  std::vector<std::vector<task::FactId>> object_facts;
  std::vector<std::vector<task::ActionId>> object_actions;
  std::vector<bool> in_numeric;
  auto grow = [&]() {
    occurrences.resize(objects.size());
    object_facts.resize(objects.size());
    object_actions.resize(objects.size());
    in_numeric.resize(objects.size(), false);
  };
  const task::FactIndex fact_ids(task);
  const task::ActionIndex action_ids(task);
  for (std::size_t f = 0; f < task.facts.size(); ++f) {
    const auto& fact = task.facts[f];
    for (std::size_t i = 0; i < fact.args.size(); ++i) {
      const int o = object(fact.args[i]);
      grow();
      occurrences[static_cast<std::size_t>(o)].push_back("f" + fact.predicate + "/" +
                                                         std::to_string(i));
      auto& list = object_facts[static_cast<std::size_t>(o)];
      if (list.empty() || list.back() != static_cast<task::FactId>(f))
        list.push_back(static_cast<task::FactId>(f));
    }
  }
  for (std::size_t a = 0; a < task.actions.size(); ++a) {
    const auto& action = task.actions[a];
    for (std::size_t i = 0; i < action.args.size(); ++i) {
      const int o = object(action.args[i]);
      grow();
      occurrences[static_cast<std::size_t>(o)].push_back("a" + action.name + "/" +
                                                         std::to_string(i));
      auto& list = object_actions[static_cast<std::size_t>(o)];
      if (list.empty() || list.back() != static_cast<task::ActionId>(a))
        list.push_back(static_cast<task::ActionId>(a));
    }
  }
  for (const auto& var : task.numeric_vars) {
    for (const auto& arg : var.args) {
      const int o = object(arg);
      grow();
      in_numeric[static_cast<std::size_t>(o)] = true;
    }
  }
  grow();
  std::vector<std::vector<task::ActionId>> fact_users(task.facts.size());
  for (std::size_t a = 0; a < task.actions.size(); ++a) {
    const auto& action = task.actions[a];
    auto use = [&](const std::vector<task::FactId>& list) {
      for (auto f : list) {
        auto& u = fact_users[static_cast<std::size_t>(f)];
        if (u.empty() || u.back() != static_cast<task::ActionId>(a))
          u.push_back(static_cast<task::ActionId>(a));
      }
    };
    for (const auto* c : {&action.at_start, &action.over_all, &action.at_end}) {
      use(c->positive);
      use(c->negative);
    }
    for (const auto* e : {&action.start_effects, &action.end_effects}) {
      use(e->add);
      use(e->del);
      for (const auto& ce : e->conditional) {
        use(ce.condition.positive);
        use(ce.condition.negative);
        use(ce.add);
        use(ce.del);
      }
    }
  }

  // The pairs tried cost up to k^2 / 2 swaps per group of k candidates, each
  // checking every action near the two objects: past a budget of a few
  // times the task's size the remaining candidates stay alone (fewer
  // classes, never a wrong one), so that detection stays a small part of
  // the planner's start on large tasks.
  std::size_t work_left = 8 * (task.facts.size() + task.actions.size()) + 1'000'000;
  auto swap_holds = [&](int x, int y) {
    const std::size_t goal_cost =
        task.goal.positive.size() + task.goal.negative.size() + task.timed_literals.size() + 1;
    if (goal_cost >= work_left) {
      work_left = 0;
      return false;
    }
    work_left -= goal_cost;
    const Swap swap(task, fact_ids, action_ids, objects[static_cast<std::size_t>(x)],
                    objects[static_cast<std::size_t>(y)]);
    // The goal and the timed literals first: they are what usually tells
    // two objects apart, and they are cheap to check.
    if (!swap.ConditionMaps(task.goal, task.goal)) return false;
    for (const auto& til : task.timed_literals) {
      const task::FactId g = swap.Fact(til.fact);
      if (g < 0) return false;
      if (g == til.fact) continue;
      const bool found =
          std::any_of(task.timed_literals.begin(), task.timed_literals.end(),
                      [&](const task::TimedInitialLiteral& t) {
                        return t.fact == g && t.value == til.value && t.time_s == til.time_s;
                      });
      if (!found) return false;
    }
    for (int o : {x, y}) {
      for (auto f : object_facts[static_cast<std::size_t>(o)]) {
        if (swap.Fact(f) < 0) return false;
      }
      // Actions naming the object, and those reading or writing its facts
      // (an action of domain constants may name none of them).
      std::vector<task::ActionId> check = object_actions[static_cast<std::size_t>(o)];
      for (auto f : object_facts[static_cast<std::size_t>(o)]) {
        const auto& u = fact_users[static_cast<std::size_t>(f)];
        check.insert(check.end(), u.begin(), u.end());
      }
      std::sort(check.begin(), check.end());
      check.erase(std::unique(check.begin(), check.end()), check.end());
      const std::size_t cost = check.size() + object_facts[static_cast<std::size_t>(o)].size();
      if (cost > work_left) {
        work_left = 0;
        return false;
      }
      work_left -= cost;
      for (auto a : check) {
        const task::ActionId b = swap.Action(a);
        if (b < 0) return false;
        const auto& p = task.actions[static_cast<std::size_t>(a)];
        const auto& q = task.actions[static_cast<std::size_t>(b)];
        if (p.is_durative != q.is_durative || snap.Pruned(a) != snap.Pruned(b)) return false;
        if (p.duration.size() != q.duration.size()) return false;
        for (std::size_t i = 0; i < p.duration.size(); ++i) {
          if (p.duration[i].comparator != q.duration[i].comparator ||
              !ExprEqual(p.duration[i].value, q.duration[i].value))
            return false;
        }
        if (!swap.ConditionMaps(p.at_start, q.at_start) ||
            !swap.ConditionMaps(p.over_all, q.over_all) ||
            !swap.ConditionMaps(p.at_end, q.at_end) ||
            !swap.EffectsMap(p.start_effects, q.start_effects) ||
            !swap.EffectsMap(p.end_effects, q.end_effects))
          return false;
      }
    }
    return true;
  };

  // Candidates: objects appearing in the same places the same number of
  // times, never in a numeric variable.
  std::map<std::vector<std::string>, std::vector<int>> groups;
  for (std::size_t o = 0; o < objects.size(); ++o) {
    if (in_numeric[o]) continue;
    std::sort(occurrences[o].begin(), occurrences[o].end());
    groups[occurrences[o]].push_back(static_cast<int>(o));
  }
  std::vector<std::vector<int>> found;
  for (const auto& [where, members] : groups) {
    if (members.size() < 2) continue;
    std::vector<std::vector<int>> classes;
    for (int o : members) {
      bool placed = false;
      for (auto& c : classes) {
        if (swap_holds(c.front(), o)) {
          c.push_back(o);
          placed = true;
          break;
        }
      }
      if (!placed) classes.push_back({o});
    }
    for (auto& c : classes) {
      if (c.size() >= 2) found.push_back(std::move(c));
    }
  }

  // Positions in the representative's lists, one table reused by every
  // class (entries of the previous class are reset after it).
  std::vector<std::int32_t> rep_fact_pos(task.facts.size(), -1);
  std::vector<std::int32_t> rep_action_pos(task.actions.size(), -1);
  for (const auto& members : found) {
    Class c;
    c.objects = members;
    const int rep = members.front();
    const auto& rep_facts = object_facts[static_cast<std::size_t>(rep)];
    const auto& rep_actions = object_actions[static_cast<std::size_t>(rep)];
    for (std::size_t j = 0; j < rep_facts.size(); ++j)
      rep_fact_pos[static_cast<std::size_t>(rep_facts[j])] = static_cast<std::int32_t>(j);
    for (std::size_t j = 0; j < rep_actions.size(); ++j)
      rep_action_pos[static_cast<std::size_t>(rep_actions[j])] = static_cast<std::int32_t>(j);
    bool ok = true;
    for (int o : members) {
      const Swap swap(task, fact_ids, action_ids, objects[static_cast<std::size_t>(o)],
                      objects[static_cast<std::size_t>(rep)]);
      const auto& facts = object_facts[static_cast<std::size_t>(o)];
      const auto& actions = object_actions[static_cast<std::size_t>(o)];
      std::vector<std::int32_t> to_rep, act_to_rep;
      std::vector<task::FactId> from_rep(rep_facts.size(), -1);
      std::vector<task::ActionId> act_from_rep(rep_actions.size(), -1);
      for (auto f : facts) {
        const task::FactId r = swap.Fact(f);
        const std::int32_t pos = r < 0 ? -1 : rep_fact_pos[static_cast<std::size_t>(r)];
        if (pos < 0) {
          ok = false;
          break;
        }
        to_rep.push_back(pos);
        from_rep[static_cast<std::size_t>(pos)] = f;
      }
      for (auto a : actions) {
        if (!ok) break;
        const task::ActionId r = swap.Action(a);
        const std::int32_t pos = r < 0 ? -1 : rep_action_pos[static_cast<std::size_t>(r)];
        if (pos < 0) {
          ok = false;
          break;
        }
        act_to_rep.push_back(pos);
        act_from_rep[static_cast<std::size_t>(pos)] = a;
      }
      if (!ok || facts.size() != rep_facts.size() || actions.size() != rep_actions.size()) {
        ok = false;
        break;
      }
      c.facts.push_back(facts);
      c.fact_rep_pos.push_back(std::move(to_rep));
      c.fact_from_rep.push_back(std::move(from_rep));
      c.actions.push_back(actions);
      c.action_rep_pos.push_back(std::move(act_to_rep));
      c.action_from_rep.push_back(std::move(act_from_rep));
    }
    for (auto f : rep_facts) rep_fact_pos[static_cast<std::size_t>(f)] = -1;
    for (auto a : rep_actions) rep_action_pos[static_cast<std::size_t>(a)] = -1;
    if (ok) classes_.push_back(std::move(c));
  }
}

int ObjectSymmetry::num_symmetric_objects() const {
  int n = 0;
  for (const auto& c : classes_) n += static_cast<int>(c.objects.size());
  return n;
}

void ObjectSymmetry::Canonicalize(const StateData& state, StateData* out) const {
  *out = state;
  for (const Class& c : classes_) {
    const std::size_t n = c.objects.size();
    signature_.resize(n);
    running_of_member_.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      auto& sig = signature_[i];
      sig.clear();
      for (std::size_t j = 0; j < c.facts[i].size(); ++j) {
        if (out->Holds(c.facts[i][j])) sig.push_back(c.fact_rep_pos[i][j]);
      }
      std::sort(sig.begin(), sig.end());
      sig.push_back(-1);
      const std::size_t mark = sig.size();
      auto& running = running_of_member_[i];
      running.clear();
      const auto& acts = c.actions[i];
      for (std::size_t r = 0; r < out->running.size(); ++r) {
        auto it = std::lower_bound(acts.begin(), acts.end(), out->running[r].action);
        if (it != acts.end() && *it == out->running[r].action) {
          const auto pos = c.action_rep_pos[i][static_cast<std::size_t>(it - acts.begin())];
          running.emplace_back(static_cast<std::int32_t>(r), pos);
          sig.push_back(pos);
        }
      }
      std::sort(sig.begin() + static_cast<std::ptrdiff_t>(mark), sig.end());
    }
    order_.resize(n);
    for (std::size_t i = 0; i < n; ++i) order_[i] = static_cast<int>(i);
    std::stable_sort(order_.begin(), order_.end(), [&](int a, int b) {
      return signature_[static_cast<std::size_t>(a)] < signature_[static_cast<std::size_t>(b)];
    });
    bool identity = true;
    for (std::size_t i = 0; i < n; ++i) identity = identity && order_[i] == static_cast<int>(i);
    if (identity) continue;
    // Member order_[k] becomes member k: its facts and running actions are
    // renamed through the representative's.
    scratch_ = *out;
    for (std::size_t i = 0; i < n; ++i) {
      for (auto f : c.facts[i]) scratch_.Clear(f);
    }
    scratch_.running.clear();
    named_.assign(out->running.size(), 0);
    for (std::size_t i = 0; i < n; ++i) {
      for (const auto& [r, pos] : running_of_member_[i]) named_[static_cast<std::size_t>(r)] = 1;
    }
    for (std::size_t r = 0; r < out->running.size(); ++r) {
      if (named_[r] == 0) scratch_.running.push_back(out->running[r]);
    }
    for (std::size_t k = 0; k < n; ++k) {
      const auto m = static_cast<std::size_t>(order_[k]);
      for (std::size_t j = 0; j < c.facts[m].size(); ++j) {
        if (!out->Holds(c.facts[m][j])) continue;
        const auto pos = c.fact_rep_pos[m][j];
        scratch_.Set(c.fact_from_rep[k][static_cast<std::size_t>(pos)]);
      }
      for (const auto& [r, pos] : running_of_member_[m]) {
        RunningAction moved = out->running[static_cast<std::size_t>(r)];
        moved.action = c.action_from_rep[k][static_cast<std::size_t>(pos)];
        scratch_.running.push_back(moved);
      }
    }
    std::sort(scratch_.running.begin(), scratch_.running.end(),
              [](const RunningAction& a, const RunningAction& b) { return a.action < b.action; });
    std::swap(*out, scratch_);
  }
}

}  // namespace seaplan::search
