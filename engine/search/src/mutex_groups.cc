#include "mutex_groups.h"

#include <algorithm>
#include <deque>
#include <set>
#include <string>
#include <unordered_map>
#include <utility>

namespace seaplan::search {
namespace {

// (predicate or schema, argument position): one counted pattern of a candidate.
struct Pattern {
  bool is_action = false;
  std::int32_t name = -1;  // interned predicate or schema name
  std::int32_t position = 0;
  auto operator<=>(const Pattern&) const = default;
};
using Candidate = std::vector<Pattern>;  // sorted

// One snap of the ground task, in members: what it requires true, adds and
// deletes (running markers included).
struct Snap {
  std::vector<GroupMember> pre, add, del;
  task::ActionId action = -1;
  bool is_end = false;
};

class Synthesis {
 public:
  explicit Synthesis(const task::GroundTask& task) : task_(task) {
    for (const auto& f : task.facts) {
      fact_name_.push_back(Intern(f.predicate));
      fact_args_.push_back(InternArgs(f.args));
    }
    for (const auto& a : task.actions) {
      action_name_.push_back(Intern(a.name));
      action_args_.push_back(InternArgs(a.args));
    }
    for (task::ActionId a = 0; a < static_cast<task::ActionId>(task.actions.size()); ++a) {
      const task::Action& action = task.actions[static_cast<std::size_t>(a)];
      Snap start;
      start.action = a;
      start.pre = action.at_start.positive;
      start.add = action.start_effects.add;
      for (const auto& c : action.start_effects.conditional) {
        start.add.insert(start.add.end(), c.add.begin(), c.add.end());
      }
      start.del = action.start_effects.del;
      if (action.is_durative) start.add.push_back(RunningMember(a));
      snaps_.push_back(std::move(start));
      if (!action.is_durative) continue;
      Snap end;
      end.action = a;
      end.is_end = true;
      // The search applies an end only where the action's over-all
      // conditions still hold (Transitions::Apply), so the end requires them
      // too: a drop that ends on a surface it keeps clear over all.
      end.pre = action.at_end.positive;
      end.pre.insert(end.pre.end(), action.over_all.positive.begin(),
                     action.over_all.positive.end());
      end.pre.push_back(RunningMember(a));
      end.add = action.end_effects.add;
      for (const auto& c : action.end_effects.conditional) {
        end.add.insert(end.add.end(), c.add.begin(), c.add.end());
      }
      end.del = action.end_effects.del;
      end.del.push_back(RunningMember(a));
      snaps_.push_back(std::move(end));
    }
    for (auto& s : snaps_) {
      std::sort(s.add.begin(), s.add.end());
      s.add.erase(std::unique(s.add.begin(), s.add.end()), s.add.end());
      // Each member once: a delete listed twice (a ground action whose two
      // arguments are one object) removes one member, not two.
      for (auto* v : {&s.pre, &s.del}) {
        std::sort(v->begin(), v->end());
        v->erase(std::unique(v->begin(), v->end()), v->end());
      }
    }
  }

  // The groups of every invariant found.
  std::vector<std::vector<GroupMember>> Run(int* checked) {
    std::deque<Candidate> queue;
    std::set<Candidate> seen;
    std::set<std::pair<std::int32_t, std::int32_t>> seeds;
    for (std::size_t f = 0; f < task_.facts.size(); ++f) {
      for (std::size_t p = 0; p < fact_args_[f].size(); ++p) {
        seeds.emplace(fact_name_[f], static_cast<std::int32_t>(p));
      }
    }
    for (const auto& [name, position] : seeds) {
      Candidate c{Pattern{false, name, position}};
      seen.insert(c);
      queue.push_back(std::move(c));
    }
    std::set<std::vector<GroupMember>> groups;
    while (!queue.empty() && *checked < MutexGroups::kMaxCandidates &&
           static_cast<std::size_t>(*checked) * snaps_.size() < MutexGroups::kMaxSnapChecks) {
      Candidate c = std::move(queue.front());
      queue.pop_front();
      ++*checked;
      std::vector<Pattern> options;
      const Verdict v = Check(c, &options);
      if (v == Verdict::kInvariant) {
        for (auto& g : Instances(c)) {
          if (g.size() >= 2) groups.insert(std::move(g));
        }
        continue;
      }
      if (v == Verdict::kRefuted || static_cast<int>(c.size()) >= MutexGroups::kMaxPairs) continue;
      for (const Pattern& o : options) {
        Candidate grown = c;
        grown.insert(std::lower_bound(grown.begin(), grown.end(), o), o);
        if (seen.insert(grown).second) queue.push_back(std::move(grown));
      }
    }
    return {groups.begin(), groups.end()};
  }

 private:
  enum class Verdict { kInvariant, kRefuted, kGrow };

  std::int32_t Intern(const std::string& s) {
    auto [it, inserted] = ids_.emplace(s, static_cast<std::int32_t>(ids_.size()));
    return it->second;
  }
  std::vector<std::int32_t> InternArgs(const std::vector<std::string>& args) {
    std::vector<std::int32_t> out;
    for (const auto& a : args) out.push_back(Intern(a));
    return out;
  }

  // The objects whose instance of `c` holds `m` (distinct, few).
  void Keys(const Candidate& c, GroupMember m, std::vector<std::int32_t>* keys) const {
    keys->clear();
    const bool running = IsRunningMember(m);
    const auto index = static_cast<std::size_t>(running ? ActionOfRunning(m) : m);
    const std::int32_t name = running ? action_name_[index] : fact_name_[index];
    const auto& args = running ? action_args_[index] : fact_args_[index];
    for (const Pattern& p : c) {
      if (p.is_action != running || p.name != name) continue;
      if (static_cast<std::size_t>(p.position) >= args.size()) continue;
      const std::int32_t key = args[static_cast<std::size_t>(p.position)];
      if (std::find(keys->begin(), keys->end(), key) == keys->end()) keys->push_back(key);
    }
  }

  Verdict Check(const Candidate& c, std::vector<Pattern>* options) {
    std::vector<std::int32_t> keys;
    // At most one member of each instance true initially.
    std::unordered_map<std::int32_t, int> initial;
    for (task::FactId f : task_.initial_facts) {
      Keys(c, f, &keys);
      for (auto k : keys) {
        if (++initial[k] > 1) return Verdict::kRefuted;
      }
    }
    for (const auto& til : task_.timed_literals) {
      Keys(c, til.fact, &keys);
      if (til.value && !keys.empty()) return Verdict::kRefuted;
    }
    // Per snap: members added and members required and deleted, per object.
    std::vector<std::pair<std::int32_t, int>> added, removed;  // (object, count)
    auto bump = [](std::vector<std::pair<std::int32_t, int>>& v, std::int32_t k) {
      for (auto& [key, n] : v) {
        if (key == k) {
          ++n;
          return;
        }
      }
      v.emplace_back(k, 1);
    };
    for (const Snap& s : snaps_) {
      added.clear();
      removed.clear();
      for (GroupMember m : s.add) {
        // Required, deleted and added again: no change.
        if (std::binary_search(s.pre.begin(), s.pre.end(), m) &&
            std::binary_search(s.del.begin(), s.del.end(), m))
          continue;
        Keys(c, m, &keys);
        for (auto k : keys) bump(added, k);
      }
      if (added.empty()) continue;
      for (GroupMember m : s.del) {
        if (!std::binary_search(s.pre.begin(), s.pre.end(), m)) continue;
        if (std::binary_search(s.add.begin(), s.add.end(), m)) continue;
        Keys(c, m, &keys);
        for (auto k : keys) bump(removed, k);
      }
      for (const auto& [k, n] : added) {
        int gone = 0;
        for (const auto& [key, r] : removed) {
          if (key == k) gone = r;
        }
        if (n <= gone) continue;
        if (n > 1) return Verdict::kRefuted;
        // One member added, none taken: grow by a pattern of something the
        // snap requires and deletes that mentions the same object.
        for (GroupMember m : s.del) {
          if (!std::binary_search(s.pre.begin(), s.pre.end(), m)) continue;
          const bool running = IsRunningMember(m);
          const auto index = static_cast<std::size_t>(running ? ActionOfRunning(m) : m);
          const auto& args = running ? action_args_[index] : fact_args_[index];
          const std::int32_t name = running ? action_name_[index] : fact_name_[index];
          for (std::size_t p = 0; p < args.size(); ++p) {
            if (args[p] != k) continue;
            const Pattern o{running, name, static_cast<std::int32_t>(p)};
            if (!std::binary_search(c.begin(), c.end(), o)) options->push_back(o);
          }
        }
        return options->empty() ? Verdict::kRefuted : Verdict::kGrow;
      }
    }
    return Verdict::kInvariant;
  }

  // Every instance of `c`: the members per object.
  std::vector<std::vector<GroupMember>> Instances(const Candidate& c) const {
    std::unordered_map<std::int32_t, std::vector<GroupMember>> by_key;
    std::vector<std::int32_t> keys;
    for (task::FactId f = 0; f < static_cast<task::FactId>(task_.facts.size()); ++f) {
      Keys(c, f, &keys);
      for (auto k : keys) by_key[k].push_back(f);
    }
    for (task::ActionId a = 0; a < static_cast<task::ActionId>(task_.actions.size()); ++a) {
      if (!task_.actions[static_cast<std::size_t>(a)].is_durative) continue;
      Keys(c, RunningMember(a), &keys);
      for (auto k : keys) by_key[k].push_back(RunningMember(a));
    }
    std::vector<std::vector<GroupMember>> out;
    for (auto& [k, members] : by_key) {
      std::sort(members.begin(), members.end());
      out.push_back(std::move(members));
    }
    return out;
  }

  const task::GroundTask& task_;
  std::unordered_map<std::string, std::int32_t> ids_;
  std::vector<std::int32_t> fact_name_, action_name_;
  std::vector<std::vector<std::int32_t>> fact_args_, action_args_;
  std::vector<Snap> snaps_;
};

}  // namespace

MutexGroups::MutexGroups(const task::GroundTask& task)
    : num_facts_(static_cast<int>(task.facts.size())) {
  groups_ = Synthesis(task).Run(&candidates_checked_);
  const std::size_t slots = task.facts.size() + task.actions.size();
  std::vector<std::vector<std::int32_t>> of(slots);
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    for (GroupMember m : groups_[g]) of[Slot(m)].push_back(static_cast<std::int32_t>(g));
  }
  member_groups_begin_.assign(slots + 1, 0);
  for (std::size_t s = 0; s < slots; ++s) {
    member_groups_begin_[s + 1] = member_groups_begin_[s] + static_cast<std::int32_t>(of[s].size());
    member_groups_.insert(member_groups_.end(), of[s].begin(), of[s].end());
  }
}

std::size_t MutexGroups::Slot(GroupMember m) const {
  return IsRunningMember(m)
             ? static_cast<std::size_t>(num_facts_) + static_cast<std::size_t>(ActionOfRunning(m))
             : static_cast<std::size_t>(m);
}

std::span<const std::int32_t> MutexGroups::GroupsOf(GroupMember m) const {
  const std::size_t s = Slot(m);
  if (s + 1 >= member_groups_begin_.size()) return {};
  return {member_groups_.data() + member_groups_begin_[s],
          static_cast<std::size_t>(member_groups_begin_[s + 1] - member_groups_begin_[s])};
}

bool MutexGroups::Mutex(GroupMember a, GroupMember b) const {
  if (a == b) return false;
  const auto ga = GroupsOf(a), gb = GroupsOf(b);
  std::size_t i = 0, j = 0;
  while (i < ga.size() && j < gb.size()) {
    if (ga[i] == gb[j]) return true;
    if (ga[i] < gb[j]) {
      ++i;
    } else {
      ++j;
    }
  }
  return false;
}

}  // namespace seaplan::search
