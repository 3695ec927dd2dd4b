#include "landmarks.h"

#include <algorithm>
#include <deque>
#include <span>
#include <string>
#include <string_view>
#include <tuple>

#include "absl/container/flat_hash_map.h"
#include "absl/hash/hash.h"

namespace seaplan::search {
namespace {

// `out` = sorted union of the sorted `a` and `b`.
void Union(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b,
           std::vector<std::int32_t>* out) {
  out->clear();
  std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(*out));
}

// CSR from (key, value) pairs with keys in [0, n).
void BuildCsr(int n, const std::vector<std::pair<std::int32_t, std::int32_t>>& pairs,
              std::vector<std::int32_t>* begin, std::vector<std::int32_t>* values) {
  begin->assign(static_cast<std::size_t>(n) + 1, 0);
  for (const auto& [k, v] : pairs) ++(*begin)[static_cast<std::size_t>(k) + 1];
  for (std::size_t i = 1; i < begin->size(); ++i) (*begin)[i] += (*begin)[i - 1];
  values->resize(pairs.size());
  std::vector<std::int32_t> fill(begin->begin(), begin->end() - 1);
  for (const auto& [k, v] : pairs) (*values)[static_cast<std::size_t>(fill[k]++)] = v;
}

// Narrows `shared` to its intersection with the sorted `set`, or takes
// `set` whole when it is the first (`*first`). `scratch` is reused.
void IntersectInto(std::span<const std::int32_t> set, bool* first,
                   std::vector<std::int32_t>* shared, std::vector<std::int32_t>* scratch) {
  if (*first) {
    shared->assign(set.begin(), set.end());
    *first = false;
    return;
  }
  scratch->clear();
  std::set_intersection(shared->begin(), shared->end(), set.begin(), set.end(),
                        std::back_inserter(*scratch));
  shared->swap(*scratch);
}

}  // namespace

LandmarkGraph::LandmarkGraph(const SnapTask& task, const RelaxedPlanHeuristic& relaxed,
                             const StopToken* stop)
    : num_facts_(task.num_facts()) {
  const int total = relaxed.num_relaxed_facts();
  const int num_ops = relaxed.num_relaxed_ops();
  index_of_.assign(static_cast<std::size_t>(total), -1);
  // fact -> operators needing it.
  std::vector<std::pair<std::int32_t, std::int32_t>> pairs;
  std::vector<std::int32_t> missing(static_cast<std::size_t>(num_ops), 0);
  for (int op = 0; op < num_ops; ++op) {
    if (!relaxed.OpExists(op)) continue;
    for (auto f : relaxed.Preconditions(op)) pairs.emplace_back(f, op);
    missing[static_cast<std::size_t>(op)] =
        static_cast<std::int32_t>(relaxed.Preconditions(op).size());
  }
  std::vector<std::int32_t> users_begin, users;
  BuildCsr(total, pairs, &users_begin, &users);

  std::vector<std::vector<std::int32_t>> label(static_cast<std::size_t>(total));
  std::vector<std::uint8_t> reached(static_cast<std::size_t>(total), 0), fixed(reached);
  std::vector<std::uint8_t> queued(static_cast<std::size_t>(num_ops), 0);
  std::deque<std::int32_t> queue;
  auto enqueue_users = [&](std::int32_t f, bool on_first_reach) {
    for (auto i = users_begin[static_cast<std::size_t>(f)];
         i < users_begin[static_cast<std::size_t>(f) + 1]; ++i) {
      const auto op = static_cast<std::size_t>(users[static_cast<std::size_t>(i)]);
      if (on_first_reach) --missing[op];
      if (missing[op] == 0 && !queued[op]) {
        queued[op] = 1;
        queue.push_back(static_cast<std::int32_t>(op));
      }
    }
  };
  auto reach_fixed = [&](std::int32_t f) {
    const auto fi = static_cast<std::size_t>(f);
    if (reached[fi]) return;
    reached[fi] = fixed[fi] = 1;
    label[fi] = {f};
    enqueue_users(f, true);
  };
  for (auto f : task.task().initial_facts) reach_fixed(f);
  for (const auto& til : task.tils()) {
    for (auto f : til.add) reach_fixed(f);
  }
  for (int op = 0; op < num_ops; ++op) {
    if (relaxed.OpExists(op) && missing[static_cast<std::size_t>(op)] == 0 &&
        !queued[static_cast<std::size_t>(op)]) {
      queued[static_cast<std::size_t>(op)] = 1;
      queue.push_back(op);
    }
  }
  // Labels only shrink once set (an operator's union of its preconditions'
  // labels only shrinks), so intersecting a fact's label with each new
  // union of one achiever keeps the intersection over all achievers.
  std::vector<std::int32_t> op_label, with_fact, next;
  std::size_t steps = 0;
  while (!queue.empty()) {
    if (stop != nullptr && (++steps & 1023) == 0 && stop->StopRequested()) return;
    const std::int32_t op = queue.front();
    queue.pop_front();
    queued[static_cast<std::size_t>(op)] = 0;
    op_label.clear();
    for (auto p : relaxed.Preconditions(op)) {
      Union(op_label, label[static_cast<std::size_t>(p)], &next);
      op_label.swap(next);
    }
    for (auto f : relaxed.Adds(op)) {
      const auto fi = static_cast<std::size_t>(f);
      if (fixed[fi]) continue;
      Union(op_label, {f}, &with_fact);
      if (!reached[fi]) {
        reached[fi] = 1;
        label[fi] = with_fact;
        enqueue_users(f, true);
        continue;
      }
      next.clear();
      std::set_intersection(label[fi].begin(), label[fi].end(), with_fact.begin(), with_fact.end(),
                            std::back_inserter(next));
      if (next.size() == label[fi].size()) continue;
      label[fi].swap(next);
      enqueue_users(f, false);
    }
  }

  // Fact landmarks: the goal facts' labels.
  const auto& goal = task.task().goal.positive;
  for (auto g : goal) {
    if (!reached[static_cast<std::size_t>(g)]) return;  // relaxed unsolvable: none
  }
  std::vector<std::int32_t> all;
  for (auto g : goal) {
    const auto& l = label[static_cast<std::size_t>(g)];
    all.insert(all.end(), l.begin(), l.end());
  }
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  std::vector<std::vector<std::int32_t>> sets;  // members of landmark i, sorted
  for (auto f : all) {
    index_of_[static_cast<std::size_t>(f)] = static_cast<std::int32_t>(sets.size());
    sets.push_back({f});
  }
  const std::size_t num_fact_landmarks = sets.size();
  // Goals are fact landmarks; the disjunctive ones appended below are none.
  is_goal_.assign(num_fact_landmarks, 0);
  for (auto g : goal)
    is_goal_[static_cast<std::size_t>(index_of_[static_cast<std::size_t>(g)])] = 1;

  // Relaxed fact -> reachable operators adding it.
  std::vector<std::int32_t> adders_begin, adders;
  pairs.clear();
  for (int op = 0; op < num_ops; ++op) {
    if (!relaxed.OpExists(op) || missing[static_cast<std::size_t>(op)] != 0) continue;
    for (auto f : relaxed.Adds(op)) pairs.emplace_back(f, op);
  }
  BuildCsr(total, pairs, &adders_begin, &adders);
  // Disjunctions group facts of one predicate (started(a): of a's schema).
  std::vector<std::int32_t> group_of(static_cast<std::size_t>(total));
  {
    absl::flat_hash_map<std::string_view, std::int32_t> names;
    const task::GroundTask& ground = task.task();
    for (int f = 0; f < total; ++f) {
      const bool is_fact = f < num_facts_;
      const std::string& name = is_fact
                                    ? ground.facts[static_cast<std::size_t>(f)].predicate
                                    : ground.actions[static_cast<std::size_t>(f - num_facts_)].name;
      const auto it = names.try_emplace(name, static_cast<std::int32_t>(names.size())).first;
      // A predicate and a schema of one name stay apart.
      group_of[static_cast<std::size_t>(f)] = 2 * it->second + (is_fact ? 0 : 1);
    }
  }

  // Backwards from every landmark, the goals' and the disjunctions' found on
  // the way: its first achievers are the operators adding a member whose
  // preconditions' labels hold none (so the landmark is false before them).
  // Preconditions they all share are landmarks already (Zhu and Givan's
  // labels hold every fact landmark of the relaxation) and are ordered
  // greedy-necessary before it. Of the others, grouped by predicate, a
  // group that every first achiever needs one fact of is a disjunctive
  // landmark (RHW, as LAMA finds them), ordered the same way: "some ship
  // holds container c" before "c unloaded", which no single fact is.
  absl::flat_hash_map<std::vector<std::int32_t>, std::int32_t,
                      absl::Hash<std::vector<std::int32_t>>>
      disjunction_index;
  std::vector<std::pair<std::int32_t, std::int32_t>> orderings;  // (child, parent)
  std::vector<std::int32_t> stamp(static_cast<std::size_t>(num_ops), -1), first_achievers, shared;
  std::vector<std::tuple<std::int32_t, std::int32_t, std::int32_t>>
      grouped;  // (group, achiever, fact)
  std::vector<std::int32_t> group, set;
  for (std::size_t li = 0; li < sets.size(); ++li) {
    if (stop != nullptr && (li & 63) == 0 && stop->StopRequested()) break;  // the search ends too
    const auto i = static_cast<std::int32_t>(li);
    set.assign(sets[li].begin(), sets[li].end());  // a copy: `sets` grows below
    if (set.size() == 1 && fixed[static_cast<std::size_t>(set[0])]) continue;
    first_achievers.clear();
    for (auto m : set) {
      for (auto k = adders_begin[static_cast<std::size_t>(m)];
           k < adders_begin[static_cast<std::size_t>(m) + 1]; ++k) {
        const std::int32_t op = adders[static_cast<std::size_t>(k)];
        if (stamp[static_cast<std::size_t>(op)] == i) continue;
        stamp[static_cast<std::size_t>(op)] = i;
        const bool after_set = std::any_of(
            relaxed.Preconditions(op).begin(), relaxed.Preconditions(op).end(), [&](auto p) {
              const auto& pl = label[static_cast<std::size_t>(p)];
              return std::any_of(set.begin(), set.end(), [&](auto x) {
                return std::binary_search(pl.begin(), pl.end(), x);
              });
            });
        if (!after_set) first_achievers.push_back(op);
      }
    }
    if (first_achievers.empty()) continue;
    bool first = true;
    shared.clear();
    for (auto op : first_achievers)
      IntersectInto(relaxed.Preconditions(op), &first, &shared, &next);
    for (auto p : shared) {
      const int j = index_of_[static_cast<std::size_t>(p)];
      if (j >= 0 && j != i) orderings.emplace_back(i, j);
    }
    if (sets.size() >= num_fact_landmarks + kMaxDisjunctiveLandmarks) continue;
    grouped.clear();
    for (std::size_t a = 0; a < first_achievers.size(); ++a) {
      for (auto p : relaxed.Preconditions(first_achievers[a])) {
        if (std::binary_search(shared.begin(), shared.end(), p)) continue;
        grouped.emplace_back(group_of[static_cast<std::size_t>(p)], static_cast<std::int32_t>(a),
                             p);
      }
    }
    std::sort(grouped.begin(), grouped.end());
    for (std::size_t b = 0; b < grouped.size();) {
      std::size_t e = b;
      int achievers_needing = 0;
      group.clear();
      for (; e < grouped.size() && std::get<0>(grouped[e]) == std::get<0>(grouped[b]); ++e) {
        if (e == b || std::get<1>(grouped[e]) != std::get<1>(grouped[e - 1])) ++achievers_needing;
        group.push_back(std::get<2>(grouped[e]));
      }
      b = e;
      if (achievers_needing != static_cast<int>(first_achievers.size())) continue;
      std::sort(group.begin(), group.end());
      group.erase(std::unique(group.begin(), group.end()), group.end());
      // One fact would be a fact landmark (found already); a member true at
      // the start or a fact landmark makes it hold no news; a large one
      // guides little and costs a test per member in every state.
      if (group.size() < 2 || group.size() > kMaxDisjunctionSize) continue;
      if (std::any_of(group.begin(), group.end(), [&](auto f) {
            return fixed[static_cast<std::size_t>(f)] ||
                   index_of_[static_cast<std::size_t>(f)] >= 0;
          }))
        continue;
      // Running actions only below a goal or a disjunction: below any other
      // fact landmark they would say "it is being achieved" twice over
      // (satellite-tw-til p02: "some turn to d starts" before "pointing to
      // d" took the first plan from 0.01 to 2.3 s).
      if (group[0] >= num_facts_ && li < num_fact_landmarks && !is_goal_[li]) continue;
      const auto [it, inserted] =
          disjunction_index.try_emplace(group, static_cast<std::int32_t>(sets.size()));
      if (inserted) sets.push_back(group);
      if (it->second != i) orderings.emplace_back(i, it->second);
    }
  }

  member_begin_.assign(1, 0);
  for (const auto& s : sets) {
    members_.insert(members_.end(), s.begin(), s.end());
    member_begin_.push_back(static_cast<std::int32_t>(members_.size()));
  }
  is_goal_.resize(sets.size(), 0);
  num_disjunctive_ = static_cast<int>(sets.size() - num_fact_landmarks);

  // Achievers of each landmark (of any member), and the landmarks each snap adds.
  std::vector<std::pair<std::int32_t, std::int32_t>> adds;  // (landmark, op)
  for (int i = 0; i < size(); ++i) {
    for (auto m : members(i)) {
      for (auto k = adders_begin[static_cast<std::size_t>(m)];
           k < adders_begin[static_cast<std::size_t>(m) + 1]; ++k) {
        adds.emplace_back(i, adders[static_cast<std::size_t>(k)]);
      }
    }
  }
  std::sort(adds.begin(), adds.end());
  adds.erase(std::unique(adds.begin(), adds.end()), adds.end());
  BuildCsr(size(), adds, &achiever_begin_, &achievers_);
  std::vector<std::pair<std::int32_t, std::int32_t>> by_snap;
  by_snap.reserve(adds.size());
  for (const auto& [i, op] : adds) by_snap.emplace_back(op, i);
  BuildCsr(num_ops, by_snap, &added_by_begin_, &added_by_);

  BuildCsr(size(), orderings, &parent_begin_, &parents_);
  for (auto& [child, parent] : orderings) std::swap(child, parent);
  BuildCsr(size(), orderings, &child_begin_, &children_);
}

int LandmarkGraph::AddReasonableOrderings(const RelaxedPlanHeuristic& relaxed,
                                          const MutexGroups& mutex, const StopToken* stop) {
  const int n = size();
  if (n == 0 || mutex.groups().empty()) return 0;
  // Simple landmarks of facts (no started(a), no disjunction).
  const auto fact_of = [&](int i) { return members(i)[0]; };
  const auto is_fact = [&](int i) { return members(i).size() == 1 && fact_of(i) < num_facts_; };
  // Per fact landmark a: the facts every achiever of a adds besides a, and
  // a's greedy-necessary parents that are facts: what must hold when a is
  // first reached.
  std::vector<std::vector<std::int32_t>> with(static_cast<std::size_t>(n));
  std::vector<std::int32_t> shared, adds, next;
  for (int a = 0; a < n; ++a) {
    if (!is_fact(a)) continue;
    const std::int32_t fa = fact_of(a);
    bool first = true;
    shared.clear();
    for (auto k = achiever_begin_[static_cast<std::size_t>(a)];
         k < achiever_begin_[static_cast<std::size_t>(a) + 1]; ++k) {
      const auto op_adds = relaxed.Adds(achievers_[static_cast<std::size_t>(k)]);
      adds.assign(op_adds.begin(), op_adds.end());
      std::sort(adds.begin(), adds.end());
      IntersectInto(adds, &first, &shared, &next);
    }
    auto& w = with[static_cast<std::size_t>(a)];
    for (auto f : shared) {
      if (f != fa && f < num_facts_) w.push_back(f);
    }
    for (auto p : parents(a)) {
      if (is_fact(p)) w.push_back(fact_of(p));
    }
    w.push_back(fa);
  }
  // Children lists of every ordering so far, grown as orderings are added,
  // to refuse one that closes a cycle: a -> b does when b already comes
  // before a. Adding a -> b gives b no new descendant (a is none of them),
  // so b's descendants are found once, before its orderings are added.
  std::vector<std::vector<std::int32_t>> out(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    for (auto p : parents(i)) out[static_cast<std::size_t>(p)].push_back(i);
  }
  std::vector<std::uint8_t> after_b(static_cast<std::size_t>(n));
  std::vector<std::int32_t> stack;
  std::vector<std::pair<std::int32_t, std::int32_t>> orderings;  // (child, parent)
  for (int i = 0; i < n; ++i) {
    for (auto p : parents(i)) orderings.emplace_back(i, p);
  }
  int added = 0;
  std::size_t checks = 0;
  for (int b = 0; b < n && checks <= kMaxReasonableChecks; ++b) {
    if (!is_goal(b) || !is_fact(b)) continue;
    if (stop != nullptr && stop->StopRequested()) break;
    std::fill(after_b.begin(), after_b.end(), 0);
    stack.assign(1, b);
    after_b[static_cast<std::size_t>(b)] = 1;
    while (!stack.empty()) {
      const int x = stack.back();
      stack.pop_back();
      for (auto c : out[static_cast<std::size_t>(x)]) {
        if (!after_b[static_cast<std::size_t>(c)]) {
          after_b[static_cast<std::size_t>(c)] = 1;
          stack.push_back(c);
        }
      }
    }
    checks += static_cast<std::size_t>(n);
    const std::int32_t fb = fact_of(b);
    const auto ps = parents(b);
    for (int a = 0; a < n; ++a) {
      if (after_b[static_cast<std::size_t>(a)] || !is_fact(a)) continue;
      const auto& w = with[static_cast<std::size_t>(a)];
      checks += w.size();
      if (!std::any_of(w.begin(), w.end(), [&](std::int32_t f) { return mutex.Mutex(f, fb); }))
        continue;
      if (std::find(ps.begin(), ps.end(), a) != ps.end()) continue;
      out[static_cast<std::size_t>(a)].push_back(b);
      orderings.emplace_back(b, a);
      ++added;
    }
  }
  if (added > 0) BuildCsr(n, orderings, &parent_begin_, &parents_);
  return added;
}

bool LandmarkGraph::Holds(int i, const StateData& state) const {
  for (const std::int32_t f : members(i)) {
    if (f < num_facts_ ? state.Holds(f) : state.IsRunning(f - num_facts_)) return true;
  }
  return false;
}

LandmarkCounter::LandmarkCounter(const LandmarkGraph& graph)
    : graph_(graph), words_((static_cast<std::size_t>(graph.size()) + 63) / 64) {}

bool LandmarkCounter::ParentsAccepted(std::span<const std::uint64_t> accepted, int i) const {
  for (auto p : graph_.parents(i)) {
    if (!Test(accepted, p)) return false;
  }
  return true;
}

int LandmarkCounter::Update(std::span<const std::uint64_t> parent_accepted, const StateData& state,
                            std::span<std::uint64_t> accepted) const {
  const int n = graph_.size();
  if (parent_accepted.empty()) {
    std::fill(accepted.begin(), accepted.end(), 0);
  } else {
    std::copy(parent_accepted.begin(), parent_accepted.end(), accepted.begin());
  }
  for (int i = 0; i < n; ++i) {
    if (Test(accepted, i) || !graph_.Holds(i, state)) continue;
    if (!parent_accepted.empty() && !ParentsAccepted(parent_accepted, i)) continue;
    accepted[static_cast<std::size_t>(i) >> 6] |= std::uint64_t{1} << (i & 63);
  }
  int h = 0;
  for (int i = 0; i < n; ++i) {
    if (!Test(accepted, i)) {
      ++h;
      continue;
    }
    if (graph_.Holds(i, state)) continue;
    bool again = graph_.is_goal(i);
    for (auto c : graph_.children(i)) {
      if (again) break;
      again = !Test(accepted, c);
    }
    if (again) ++h;
  }
  return h;
}

bool LandmarkCounter::AddsNextLandmark(std::span<const std::uint64_t> accepted,
                                       const StateData& state, SnapId snap) const {
  for (auto i : graph_.added_by(snap)) {
    if (!Test(accepted, i) && !graph_.Holds(i, state) && ParentsAccepted(accepted, i)) return true;
  }
  return false;
}

}  // namespace seaplan::search
