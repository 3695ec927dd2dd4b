#include "plan_lifting.h"

#include <algorithm>
#include <numeric>

#include "stn.h"

namespace seaplan::search {
namespace {

// What one event touches, split the way the validator's mutex rule needs.
struct Footprint {
  std::vector<task::FactId> adds, dels, reads, inv;
  std::vector<task::NumericVarId> num_reads, num_commute, num_set, num_inv;
  task::ActionId action = -1;  // -1 for a timed literal
};

void SortUnique(std::vector<std::int32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

void AddNumeric(const std::vector<task::NumericEffect>& effects, Footprint& fp) {
  for (const auto& e : effects) {
    const bool commutes = e.op == task::AssignOp::kIncrease || e.op == task::AssignOp::kDecrease;
    (commutes ? fp.num_commute : fp.num_set).push_back(e.var);
  }
}

Footprint MakeFootprint(const SnapTask& task, const Event& event) {
  Footprint fp;
  if (event.is_til()) {
    const TilEvent& til = task.tils()[static_cast<std::size_t>(event.til())];
    fp.adds = til.add;
    fp.dels = til.del;
    for (const auto& [v, value] : til.assign) fp.num_set.push_back(v);
  } else {
    const SnapAction& snap = task.snap(event.snap);
    fp.action = snap.action;
    fp.reads = snap.reads;
    fp.num_reads = snap.num_reads;
    fp.inv = snap.inv_reads;
    fp.num_inv = snap.inv_num_reads;
    const task::Effects& e = *snap.effects;
    fp.adds = e.add;
    fp.dels = e.del;
    AddNumeric(e.numeric, fp);
    for (const auto& ce : e.conditional) {
      fp.adds.insert(fp.adds.end(), ce.add.begin(), ce.add.end());
      fp.dels.insert(fp.dels.end(), ce.del.begin(), ce.del.end());
      AddNumeric(ce.numeric, fp);
    }
  }
  for (auto* v : {&fp.adds, &fp.dels, &fp.reads, &fp.inv, &fp.num_reads, &fp.num_commute,
                  &fp.num_set, &fp.num_inv}) {
    SortUnique(*v);
  }
  return fp;
}

// Calls on_fact(f) for every fact and on_var(v) for every variable the
// event touches, in any role (repeats possible).
template <typename OnFact, typename OnVar>
void ForEachTouched(const Footprint& fp, OnFact&& on_fact, OnVar&& on_var) {
  for (const auto* facts : {&fp.adds, &fp.dels, &fp.reads, &fp.inv}) {
    for (auto f : *facts) on_fact(static_cast<std::size_t>(f));
  }
  for (const auto* vars : {&fp.num_reads, &fp.num_commute, &fp.num_set, &fp.num_inv}) {
    for (auto v : *vars) on_var(static_cast<std::size_t>(v));
  }
}

bool Meets(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b) {
  auto i = a.begin();
  auto j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (*i == *j) return true;
    if (*i < *j) {
      ++i;
    } else {
      ++j;
    }
  }
  return false;
}

// Validator mutex rule, one direction (x changes something y relies on).
bool InterferesOneWay(const Footprint& x, const Footprint& y) {
  return Meets(x.adds, y.dels) || Meets(x.adds, y.reads) || Meets(x.dels, y.reads) ||
         Meets(x.num_commute, y.num_reads) || Meets(x.num_set, y.num_reads) ||
         Meets(x.num_set, y.num_commute) || Meets(x.num_set, y.num_set);
}

// A change of what x's invariant reads: ordered (gap 0) so the invariant sees
// the values it was validated with. Two adds (or deletes) of one fact and two
// increases of one variable commute, so they are not ordered at all: any
// reader or opposite writer between them is ordered against each of them.
bool ChangesInvariant(const Footprint& x, const Footprint& y) {
  return Meets(x.adds, y.inv) || Meets(x.dels, y.inv) || Meets(x.num_commute, y.num_inv) ||
         Meets(x.num_set, y.num_inv);
}

}  // namespace

std::optional<std::vector<double>> LiftAndReschedule(const SnapTask& task,
                                                     std::span<const Event> events,
                                                     std::span<const double> times,
                                                     double epsilon_s, bool bound_concurrency,
                                                     std::size_t max_pairs) {
  const std::size_t n = events.size();
  if (times.size() != n) return std::nullopt;
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return times[a] < times[b]; });
  std::vector<std::size_t> pos(n);
  for (std::size_t k = 0; k < n; ++k) pos[order[k]] = k;
  std::vector<Footprint> fp(n);
  for (std::size_t i = 0; i < n; ++i) fp[i] = MakeFootprint(task, events[i]);

  Stn stn;
  stn.Reset();
  const auto& tils = task.tils();
  for (const auto& til : tils) stn.AddFixedNode(til.time_s);
  std::vector<int> node(n, -1);
  std::vector<int> open_start(static_cast<std::size_t>(task.num_actions()), -1);
  std::vector<std::size_t> open_event(static_cast<std::size_t>(task.num_actions()), 0);
  // Only events that share a fact or a variable can be ordered by the rules
  // below, so each new event is paired with those alone: the timed literals
  // (either side of it) and the action events placed before it, found
  // through the facts and variables they touch. Pairing every two events
  // took minutes on a first plan of 34,554 actions (69,108 events).
  std::vector<std::vector<std::int32_t>> by_fact(static_cast<std::size_t>(task.num_facts()));
  std::vector<std::vector<std::int32_t>> by_var(static_cast<std::size_t>(task.num_vars()));
  auto index = [&](std::size_t i) {
    const auto id = static_cast<std::int32_t>(i);
    ForEachTouched(
        fp[i], [&](std::size_t f) { by_fact[f].push_back(id); },
        [&](std::size_t v) { by_var[v].push_back(id); });
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (events[i].is_til()) {
      node[i] = 1 + events[i].til();
      index(i);
    }
  }
  std::vector<std::size_t> seen(n, 0), candidates;
  std::vector<std::int32_t> placed_ends;  // bound_concurrency: end events placed so far
  std::size_t work = 0;
  // Orderings among the events placed so far (in schedule order), then the
  // new event's node; timed literals are fixed nodes, reached by edges from
  // the action events on either side.
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t j = order[k];
    if (events[j].is_til()) continue;
    const int nj = stn.BeginNode();
    node[j] = nj;
    const Footprint& b = fp[j];
    candidates.clear();
    auto collect = [&](const std::vector<std::int32_t>& touching) {
      work += touching.size();  // the walk, repeats included
      for (auto h : touching) {
        const auto hi = static_cast<std::size_t>(h);
        if (seen[hi] == k + 1) continue;
        seen[hi] = k + 1;
        candidates.push_back(hi);
      }
    };
    ForEachTouched(
        b, [&](std::size_t f) { collect(by_fact[f]); }, [&](std::size_t v) { collect(by_var[v]); });
    const bool is_end = task.snap(events[j].snap).is_end;
    if (bound_concurrency && !is_end) {
      for (auto h : placed_ends) {
        const auto hi = static_cast<std::size_t>(h);
        if (fp[hi].action != b.action) stn.AddIncoming(node[hi], epsilon_s);
      }
      work += placed_ends.size();
    }
    if (work > max_pairs) return std::nullopt;  // too large to lift: keep the found times
    for (const std::size_t h : candidates) {
      if (h == j) continue;
      const Footprint& a = fp[h];
      if (a.action >= 0 && a.action == b.action) continue;  // tied by its duration below
      const bool before = pos[h] < k;
      const bool interfere = InterferesOneWay(a, b) || InterferesOneWay(b, a);
      const bool touch = interfere || ChangesInvariant(a, b) || ChangesInvariant(b, a);
      if (!touch) continue;
      const double w = interfere ? epsilon_s : 0.0;
      if (events[h].is_til()) {
        if (before) {
          stn.AddIncoming(node[h], w);
        } else {
          stn.AddOutgoing(node[h], w);
        }
      } else if (before) {
        stn.AddIncoming(node[h], w);
      }
    }
    const Event& e = events[j];
    const SnapAction& snap = task.snap(e.snap);
    if (snap.is_end) {
      const int s = open_start[snap.action];
      if (s < 0) return std::nullopt;
      // The found duration, exactly (effects may read ?duration).
      const double d = times[j] - times[open_event[snap.action]];
      stn.AddIncoming(s, d);
      stn.AddOutgoing(s, -d);
      open_start[snap.action] = -1;
    } else if (task.task().actions[snap.action].is_durative) {
      open_start[snap.action] = nj;
      open_event[snap.action] = j;
    }
    if (!stn.FinishNode()) return std::nullopt;
    index(j);
    if (bound_concurrency && is_end) placed_ends.push_back(static_cast<std::int32_t>(j));
  }
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) out[i] = stn.time(node[i]);
  return out;
}

}  // namespace seaplan::search
