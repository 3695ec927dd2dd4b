#include "agent_loads.h"

#include <algorithm>
#include <string>

#include "absl/container/flat_hash_map.h"

namespace seaplan::search {

AgentLoads::AgentLoads(const SnapTask& task) {
  const task::GroundTask& gt = task.task();
  absl::flat_hash_map<std::string, std::int32_t> agent_index;
  std::vector<std::vector<std::int32_t>> per_action(gt.actions.size());
  for (std::size_t a = 0; a < gt.actions.size(); ++a) {
    const task::Action& action = gt.actions[a];
    if (!action.is_durative || task.Pruned(static_cast<task::ActionId>(a))) continue;
    auto consider = [&](task::FactId f) {
      const task::Fact& fact = gt.facts[static_cast<std::size_t>(f)];
      // A relation of the object to another (its place, its cargo): a
      // held unary fact (a direction pointed at) does not make a performer.
      if (fact.args.size() < 2) return;
      const std::string& object = fact.args.front();
      if (std::find(action.args.begin(), action.args.end(), object) == action.args.end()) return;
      const auto [it, inserted] =
          agent_index.try_emplace(object, static_cast<std::int32_t>(agent_index.size()));
      per_action[a].push_back(it->second);
    };
    for (auto f : action.start_effects.del) consider(f);
    for (auto f : action.over_all.positive) consider(f);
    std::sort(per_action[a].begin(), per_action[a].end());
    per_action[a].erase(std::unique(per_action[a].begin(), per_action[a].end()),
                        per_action[a].end());
  }
  agents_begin_.push_back(0);
  duration_s_.resize(gt.actions.size(), 0.0);
  for (std::size_t a = 0; a < gt.actions.size(); ++a) {
    agents_.insert(agents_.end(), per_action[a].begin(), per_action[a].end());
    agents_begin_.push_back(static_cast<std::int32_t>(agents_.size()));
    if (gt.actions[a].is_durative) {
      duration_s_[a] = std::max(0.0, gt.actions[a].ConstantDuration().value_or(0.0));
    }
  }
  std::vector<std::vector<std::int32_t>> facts_of(agent_index.size());
  for (std::size_t f = 0; f < gt.facts.size(); ++f) {
    if (gt.facts[f].args.empty()) continue;
    const auto it = agent_index.find(gt.facts[f].args.front());
    if (it != agent_index.end())
      facts_of[static_cast<std::size_t>(it->second)].push_back(static_cast<std::int32_t>(f));
  }
  agent_facts_begin_.push_back(0);
  for (const auto& facts : facts_of) {
    agent_facts_.insert(agent_facts_.end(), facts.begin(), facts.end());
    agent_facts_begin_.push_back(static_cast<std::int32_t>(agent_facts_.size()));
  }
}

void AgentLoads::ReadyTimes(const StateData& state, const Timeline* schedule,
                            std::vector<double>* ready_s) const {
  ready_s->assign(static_cast<std::size_t>(num_agents()), 0.0);
  if (schedule == nullptr) return;
  for (int g = 0; g < num_agents(); ++g) {
    double t = 0.0;
    for (int i = agent_facts_begin_[static_cast<std::size_t>(g)];
         i < agent_facts_begin_[static_cast<std::size_t>(g) + 1]; ++i) {
      const task::FactId f = agent_facts_[static_cast<std::size_t>(i)];
      if (state.Holds(f)) t = std::max(t, schedule->FactReadUntil(f));
    }
    (*ready_s)[static_cast<std::size_t>(g)] = t;
  }
  for (const auto& r : state.running) {
    const double end_s = schedule->StartedAt(r.action) + r.min_duration_s;
    for (auto g : AgentsOf(r.action)) {
      double& t = (*ready_s)[static_cast<std::size_t>(g)];
      t = std::max(t, end_s);
    }
  }
}

}  // namespace seaplan::search
