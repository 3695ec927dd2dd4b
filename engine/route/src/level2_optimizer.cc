#include "seaplan/route/level2_optimizer.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <chrono>
#include <cmath>
#include <exception>
#include <functional>
#include <limits>
#include <memory>
#include <thread>

#include "absl/strings/str_cat.h"
#include "nlopt.hpp"
#include "seaplan/common/log.h"
#include "seaplan/route/sail_check.h"
#include "seaplan/route/turn_fillet.h"
#include "seaplan/ship/hull_dynamics.h"

namespace seaplan::route {
namespace {

double Dist(EastNorth a, EastNorth b) {
  return std::hypot(a.east_m - b.east_m, a.north_m - b.north_m);
}

// Points at fractions k/n (k = 0..n) of the polyline's length.
std::vector<EastNorth> Resample(const std::vector<EastNorth>& line, int n) {
  std::vector<double> cum(line.size(), 0.0);
  for (size_t i = 1; i < line.size(); ++i) cum[i] = cum[i - 1] + Dist(line[i - 1], line[i]);
  const double total = cum.back();
  std::vector<EastNorth> out(n + 1);
  size_t seg = 1;
  for (int k = 0; k <= n; ++k) {
    const double s = total * k / n;
    while (seg + 1 < line.size() && cum[seg] < s) ++seg;
    const double len = cum[seg] - cum[seg - 1];
    const double t = len > 0 ? std::clamp((s - cum[seg - 1]) / len, 0.0, 1.0) : 0.0;
    out[k] = {line[seg - 1].east_m + t * (line[seg].east_m - line[seg - 1].east_m),
              line[seg - 1].north_m + t * (line[seg].north_m - line[seg - 1].north_m)};
  }
  out[0] = line.front();
  out[n] = line.back();
  return out;
}

struct Refs {
  EastNorth prev, ref, next;
  double heading_rad = 0.0;  // drift heading, from north clockwise
  double scale_m = 1.0;      // search scale: half of |next - prev|
  bool movable = true;
};

struct RiskSample {
  double ttg_s = 0.0;
  ModeArray p{};
  double proximity = 0.0;
};

class RiskEvaluator {
 public:
  virtual ~RiskEvaluator() = default;
  virtual void Evaluate(EastNorth w, RiskSample* out) = 0;
};

// The drift of an unpowered ship relative to its start point.
struct DriftTrack {
  std::vector<EastNorth> offset;  // after each Euler step
  std::vector<double> heading;    // rad
  std::vector<double> time_s;     // model time after each step
};

DriftTrack SimulateDrift(const ship::HullDynamics& dyn, const ship::Environment& env,
                         double heading, double speed, double horizon_s, double dt_s) {
  DriftTrack t;
  ship::ShipModelWithoutPropulsion model(dyn, env, ship::ShipState::At(0.0, 0.0, heading, speed));
  while (model.time_s() <= horizon_s) {  // SITS loop convention
    model.Step(dt_s);
    t.offset.push_back({model.state().east_m(), model.state().north_m()});
    t.heading.push_back(model.state().heading_rad());
    t.time_s.push_back(model.time_s());
  }
  return t;
}

// kFast: one drift track per waypoint (translation invariance), tabulated P(G).
class FastEvaluator final : public RiskEvaluator {
 public:
  FastEvaluator(const ObstacleField& field, DriftTrack track, const std::vector<ModeArray>& table,
                double zeta)
      : field_(field), track_(std::move(track)), table_(table), zeta_(zeta) {}
  void Evaluate(EastNorth w, RiskSample* out) override {
    out->proximity = field_.SumExpDistance(w, zeta_);
    const size_t n = track_.offset.size();
    size_t k = 0;
    for (; k < n; ++k) {
      if (field_.HullHits(
              {w.east_m + track_.offset[k].east_m, w.north_m + track_.offset[k].north_m},
              track_.heading[k]))
        break;
    }
    if (k == n) k = n - 1;
    out->ttg_s = track_.time_s[k];
    out->p = table_[k];
  }

 private:
  const ObstacleField& field_;
  DriftTrack track_;
  const std::vector<ModeArray>& table_;
  double zeta_;
};

// kExact: everything from scratch at every evaluation.
class ExactEvaluator final : public RiskEvaluator {
 public:
  ExactEvaluator(const ObstacleField& field, const ship::HullDynamics& dyn,
                 const ship::Environment& env, const ModeGroundingModel& grounding, double heading,
                 const Level2Options& o)
      : field_(field),
        dyn_(dyn),
        env_(env),
        grounding_(grounding),
        heading_(heading),
        speed_(o.drift_initial_speed_mps),
        horizon_(o.ttg_horizon_s),
        dt_(o.ttg_step_s),
        zeta_(o.weights.zeta1_per_m) {}
  void Evaluate(EastNorth w, RiskSample* out) override {
    out->proximity = field_.SumExpDistanceBruteForce(w, zeta_);
    ship::ShipModelWithoutPropulsion model(
        dyn_, env_, ship::ShipState::At(w.north_m, w.east_m, heading_, speed_));
    while (model.time_s() <= horizon_) {
      model.Step(dt_);
      const auto& s = model.state();
      if (field_.HullHitsBruteForce({s.east_m(), s.north_m()}, s.heading_rad())) break;
    }
    out->ttg_s = model.time_s();
    out->p = grounding_.Probabilities(out->ttg_s);
  }

 private:
  const ObstacleField& field_;
  const ship::HullDynamics& dyn_;
  ship::Environment env_;
  const ModeGroundingModel& grounding_;
  double heading_, speed_, horizon_, dt_, zeta_;
};

struct CostTerms {
  double path = 0.0;
  ModeArray mode_cost{};
  int best_mode = 0;
  double total = 0.0;
};

void ComputeCost(const CostWeights& w, const Refs& r, EastNorth p, const RiskSample& s,
                 CostTerms* out) {
  out->path = 0.0;
  if (r.movable) {
    const double dr = Dist(p, r.ref);
    const double spacing = Dist(p, r.prev) - Dist(p, r.next);
    const double s2 = spacing * spacing;
    out->path = w.mu1_per_m2 * dr * dr + w.mu2_per_m6 * s2 * s2 * s2;
  }
  const double ground = w.grounding_cost * w.mu3 * s.proximity;
  const double to_next = Dist(p, r.next);
  int best = 0;
  for (int m = 0; m < kModeCount; ++m) {
    out->mode_cost[m] =
        ground + w.grounding_cost * w.mu4 * s.p[m] + w.consumption[m] * w.mu5_per_m * to_next;
    if (out->mode_cost[m] < out->mode_cost[best]) best = m;
  }
  out->best_mode = best;
  out->total = out->path + out->mode_cost[best];
}

uint64_t SplitMix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// Small xoshiro256** generator: fixed algorithm (std::uniform_real_distribution
// is implementation-defined), a few ns per draw, no allocation.
class Rng {
 public:
  explicit Rng(uint64_t seed) {
    for (auto& s : s_) s = seed = SplitMix64(seed);
  }
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

 private:
  static uint64_t Rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  uint64_t Next() {
    const uint64_t result = Rotl(s_[1] * 5, 7) * 9;
    const uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = Rotl(s_[3], 45);
    return result;
  }
  uint64_t s_[4];
};

struct WaypointTask {
  int alt = 0;
  int k = 0;
  Refs refs;
  EastNorth position;
  int64_t evaluations = 0;
};

// Our own PSO rather than pagmo2's pso: (1) pagmo evaluates through a
// type-erased problem with std::vector decision and fitness vectors per call;
// bench/route/pso_overhead measures 0.12 us of overhead per evaluation, a
// third of our whole fast evaluation (0.35 us); (2) its max_vel is a fraction
// of the bounds box (here the whole chart) where we want one segment length
// per iteration; (3) seeding the swarm on the perpendicular spread needs
// set_x per particle, and the personal bests' side output (the argmin mode)
// has no place in its fitness vector. Per-swarm seeds would be possible with
// pagmo too (one algorithm per waypoint); we keep them: RNG from (seed,
// alternative, waypoint), so thread count never changes results.
EastNorth RunPso(const PsoOptions& o, const CostWeights& w, const Refs& r, RiskEvaluator& eval,
                 EastNorth lo, EastNorth hi, uint64_t seed, const StopToken& stop,
                 int64_t* evaluations) {
  const int n = o.particles;
  struct Particle {
    EastNorth position, v, best;
    double best_cost;
  };
  std::vector<Particle> ps(n);
  Rng rng(seed);
  const double vmax = o.velocity_limit * r.scale_m;
  double tx = r.next.east_m - r.prev.east_m, ty = r.next.north_m - r.prev.north_m;
  const double tl = std::hypot(tx, ty);
  if (tl > 0) {
    tx /= tl;
    ty /= tl;
  } else {
    tx = 1;
    ty = 0;
  }
  const EastNorth left{-ty, tx};
  const int pairs = std::max(1, n / 2);
  auto clamp_pos = [&](EastNorth p) {
    return EastNorth{std::clamp(p.east_m, lo.east_m, hi.east_m),
                     std::clamp(p.north_m, lo.north_m, hi.north_m)};
  };
  // Particle 0 on the reference, then alternately left and right of the
  // reference line, out to one search scale.
  for (int j = 0; j < n; ++j) {
    const int i = (j + 1) / 2;
    const double side = (j % 2 == 1) ? 1.0 : -1.0;
    const double off = r.scale_m * static_cast<double>(i) / pairs * side;
    ps[j].position =
        clamp_pos({r.ref.east_m + left.east_m * off, r.ref.north_m + left.north_m * off});
    ps[j].v = {(2 * rng.Uniform() - 1) * 0.1 * vmax, (2 * rng.Uniform() - 1) * 0.1 * vmax};
    ps[j].best_cost = std::numeric_limits<double>::infinity();
  }
  EastNorth gbest = r.ref;
  double gbest_cost = std::numeric_limits<double>::infinity();
  RiskSample sample;
  CostTerms terms;
  auto evaluate_all = [&] {
    for (auto& p : ps) {
      eval.Evaluate(p.position, &sample);
      ComputeCost(w, r, p.position, sample, &terms);
      ++*evaluations;
      if (terms.total < p.best_cost) {
        p.best_cost = terms.total;
        p.best = p.position;  // a copy, not an alias of the moving position
      }
    }
    for (const auto& p : ps) {
      if (p.best_cost < gbest_cost) {
        gbest_cost = p.best_cost;
        gbest = p.best;
      }
    }
  };
  evaluate_all();
  for (int it = 0; it < o.iterations; ++it) {
    if (stop.StopRequested()) break;
    for (auto& p : ps) {
      const double r1x = rng.Uniform(), r1y = rng.Uniform(), r2x = rng.Uniform(),
                   r2y = rng.Uniform();
      p.v.east_m = o.inertia * p.v.east_m +
                   o.cognitive * r1x * (p.best.east_m - p.position.east_m) +
                   o.social * r2x * (gbest.east_m - p.position.east_m);
      p.v.north_m = o.inertia * p.v.north_m +
                    o.cognitive * r1y * (p.best.north_m - p.position.north_m) +
                    o.social * r2y * (gbest.north_m - p.position.north_m);
      p.v.east_m = std::clamp(p.v.east_m, -vmax, vmax);
      p.v.north_m = std::clamp(p.v.north_m, -vmax, vmax);
      p.position = clamp_pos({p.position.east_m + p.v.east_m, p.position.north_m + p.v.north_m});
    }
    evaluate_all();
  }
  return gbest;
}

struct PolishData {
  const CostWeights* w;
  const Refs* r;
  RiskEvaluator* eval;
  int mode;
  int64_t* evaluations;
};

double PolishObjective(unsigned /*n*/, const double* x, double* /*grad*/, void* data) {
  auto* d = static_cast<PolishData*>(data);
  RiskSample s;
  CostTerms t;
  const EastNorth p{x[0], x[1]};
  d->eval->Evaluate(p, &s);
  ComputeCost(*d->w, *d->r, p, s, &t);
  ++*d->evaluations;
  return t.path + t.mode_cost[d->mode];
}

EastNorth Polish(const PolishOptions& o, const CostWeights& w, const Refs& r, RiskEvaluator& eval,
                 EastNorth start, int mode, EastNorth lo, EastNorth hi, int64_t* evaluations) {
  PolishData data{&w, &r, &eval, mode, evaluations};
  double x0[2] = {start.east_m, start.north_m};
  const double f0 = PolishObjective(2, x0, nullptr, &data);
  try {
    nlopt::opt opt(nlopt::LN_BOBYQA, 2);
    const double reach = r.scale_m;
    std::vector<double> lb = {std::max(lo.east_m, start.east_m - reach),
                              std::max(lo.north_m, start.north_m - reach)};
    std::vector<double> ub = {std::min(hi.east_m, start.east_m + reach),
                              std::min(hi.north_m, start.north_m + reach)};
    opt.set_lower_bounds(lb);
    opt.set_upper_bounds(ub);
    opt.set_min_objective(PolishObjective, &data);
    opt.set_maxeval(o.max_evaluations);
    opt.set_xtol_abs(o.xtol_m);
    opt.set_initial_step(o.initial_step_m);
    std::vector<double> x = {start.east_m, start.north_m};
    double f = f0;
    opt.optimize(x, f);
    if (f < f0) return {x[0], x[1]};
  } catch (const std::exception& e) {
    // NLopt reports roundoff / bound trouble by throwing: keep the PSO point.
  }
  return start;
}

// Viterbi over modes with a switching cost; ties go to the lower mode index.
std::vector<int> AssignModes(const std::vector<ModeArray>& cost, double switch_cost) {
  const size_t n = cost.size();
  std::vector<std::array<int, kModeCount>> from(n);
  ModeArray acc = n ? cost[0] : ModeArray{};
  for (size_t k = 1; k < n; ++k) {
    ModeArray next;
    for (int m = 0; m < kModeCount; ++m) {
      int best = 0;
      double best_v = std::numeric_limits<double>::infinity();
      for (int q = 0; q < kModeCount; ++q) {
        const double v = acc[q] + (q == m ? 0.0 : switch_cost);
        if (v < best_v) {
          best_v = v;
          best = q;
        }
      }
      from[k][m] = best;
      next[m] = best_v + cost[k][m];
    }
    acc = next;
  }
  std::vector<int> modes(n, 0);
  if (n == 0) return modes;
  int m = 0;
  for (int q = 1; q < kModeCount; ++q) {
    if (acc[q] < acc[m]) m = q;
  }
  for (size_t k = n; k-- > 0;) {
    modes[k] = m;
    if (k > 0) m = from[k][m];
  }
  return modes;
}

void RunParallel(int count, int threads, const std::function<void(int)>& fn) {
  const int t = std::max(1, std::min(threads, count));
  if (t == 1) {
    for (int i = 0; i < count; ++i) fn(i);
    return;
  }
  std::atomic<int> next{0};
  std::vector<std::thread> pool;
  pool.reserve(t);
  for (int i = 0; i < t; ++i) {
    pool.emplace_back([&] {
      for (int j = next.fetch_add(1); j < count; j = next.fetch_add(1)) fn(j);
    });
  }
  for (auto& th : pool) th.join();
}

// Keeps an optimised route as safe as its Level-1 polyline. The optimiser
// moves each waypoint on its own, so the straight segment between two moved
// waypoints can cut a headland that the Level-1 path went round (long
// segments on large charts do so often). Repair, until nothing changes: a
// waypoint inside an obstacle goes back to its reference (a point of the
// Level-1 polyline); a segment that touches an obstacle sends both its ends
// back to their references; a segment whose ends are both references and
// still touches (the chord cuts a corner of the Level-1 path) follows the
// Level-1 polyline between them. Every step only moves towards the Level-1
// path, which touches no obstacle, so the loop ends with a safe route.
struct Repair {
  std::vector<bool> snapped;  // per waypoint: moved back to its reference
  std::vector<bool> follow;   // per segment k -> k+1: follows the Level-1 path
  int snapped_count = 0;
  int followed_count = 0;
};

// Can a hull turning on `radius_m` sail the corner at w[k]? Its turn takes
// radius tan(theta / 2) of each leg; an inner leg is shared with the turn
// at its other end.
bool TurnSailable(const std::vector<EastNorth>& w, size_t k, double radius_m) {
  const EastNorth a = w[k - 1], b = w[k], c = w[k + 1];
  const double in_m = Dist(a, b), out_m = Dist(b, c);
  if (in_m < 1e-9 || out_m < 1e-9) return true;
  const double theta = std::abs(TurnAngle(a, b, c));
  const double need_m = radius_m * std::tan(std::min(theta, 0.999 * M_PI) / 2.0);
  const double in_share = k == 1 ? 1.0 : 0.5;
  const double out_share = k + 2 == w.size() ? 1.0 : 0.5;
  return need_m <= in_share * in_m + 1e-6 && need_m <= out_share * out_m + 1e-6;
}

Repair RepairRoute(const ObstacleField& field, const std::vector<EastNorth>& refs,
                   double turn_radius_m, std::vector<EastNorth>* positions) {
  std::vector<EastNorth>& w = *positions;
  const size_t n = w.size() - 1;
  Repair r;
  r.snapped.assign(n + 1, false);
  r.follow.assign(n, false);
  r.snapped[0] = r.snapped[n] = true;  // start and goal are fixed
  auto snap = [&](size_t k) {
    if (r.snapped[k]) return false;
    r.snapped[k] = true;
    w[k] = refs[k];
    ++r.snapped_count;
    return true;
  };
  for (size_t k = 1; k < n; ++k) {
    if (field.Inside(w[k])) snap(k);
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t k = 0; k < n; ++k) {
      if (r.follow[k] || !field.SegmentHits(w[k], w[k + 1])) continue;
      if (r.snapped[k] && r.snapped[k + 1]) {
        r.follow[k] = true;
        ++r.followed_count;
      } else {
        snap(k);
        snap(k + 1);
      }
      changed = true;
    }
    // Turns the hull cannot sail: only moved waypoints go back (a corner
    // between references is the Level-1 path's own).
    for (size_t k = 1; turn_radius_m > 0 && k < n; ++k) {
      if (!r.snapped[k] && !TurnSailable(w, k, turn_radius_m)) changed |= snap(k);
    }
  }
  return r;
}

// The waypoints' positions, the route they make.
std::vector<EastNorth> Positions(const std::vector<WaypointTask>& tasks) {
  std::vector<EastNorth> line;
  line.reserve(tasks.size());
  for (const WaypointTask& t : tasks) line.push_back(t.position);
  return line;
}

// A waypoint inserted at `position` (a Level-1 or fillet vertex) after
// waypoint k of alternative `alt`: evaluated like the others, not moved.
WaypointTask FixedWaypoint(size_t alt, int k, EastNorth position) {
  WaypointTask t;
  t.alt = static_cast<int>(alt);
  t.k = k;
  t.refs.ref = position;
  t.refs.movable = false;
  t.position = position;
  return t;
}

// The track arrives and never enters the (buffered) obstacles.
bool SailedClear(const SailedTrack& s) {
  return s.Clear();
}

// The waypoints of a route derived from `from` (turn_fillet.h's points: a
// waypoint of `from`, or a new vertex evaluated like the others, not moved);
// counts the new ones in `inserted`.
std::vector<WaypointTask> WaypointsOf(size_t alt, const std::vector<WaypointTask>& from,
                                      const std::vector<FilletPoint>& points, int* inserted) {
  std::vector<WaypointTask> out;
  out.reserve(points.size());
  assert(!points.empty() && points.front().source >= 0);  // a new vertex takes its k from before
  for (const FilletPoint& p : points) {
    if (p.source >= 0) {
      out.push_back(from[p.source]);
    } else {
      out.push_back(FixedWaypoint(alt, out.back().k, p.position));
      ++*inserted;
    }
  }
  return out;
}

// The Level-1 vertices strictly between arc lengths s0 < s1 of `line`.
std::vector<EastNorth> VerticesBetween(const std::vector<EastNorth>& line, double s0, double s1) {
  std::vector<EastNorth> out;
  double cum = 0.0;
  for (size_t i = 1; i + 1 < line.size(); ++i) {
    cum += Dist(line[i - 1], line[i]);
    if (cum > s0 && cum < s1) out.push_back(line[i]);
  }
  return out;
}

}  // namespace

StatusOr<double> SimulateTimeToGrounding(const ObstacleField& field, const ship::ShipParams& ship,
                                         const ship::Environment& env, EastNorth start,
                                         double heading_rad, double speed_mps, double horizon_s,
                                         double step_s) {
  if (!(step_s > 0.0) || !(horizon_s > 0.0) || horizon_s / step_s > 1e5) {
    return absl::InvalidArgumentError("TTG needs step > 0, horizon > 0 and at most 1e5 steps");
  }
  SEAPLAN_ASSIGN_OR_RETURN(ship::HullDynamics dyn, ship::HullDynamics::Create(ship));
  ship::ShipModelWithoutPropulsion model(
      dyn, env, ship::ShipState::At(start.north_m, start.east_m, heading_rad, speed_mps));
  while (model.time_s() <= horizon_s) {
    model.Step(step_s);
    const auto& s = model.state();
    if (field.HullHits({s.east_m(), s.north_m()}, s.heading_rad())) break;
  }
  return model.time_s();
}

absl::Status CostWeights::Validate() const {
  for (double v : {mu1_per_m2, mu2_per_m6, grounding_cost, mu3, zeta1_per_m, mu4, mu5_per_m,
                   mode_switch_cost, consumption[0], consumption[1], consumption[2]}) {
    if (!(v >= 0.0 && std::isfinite(v))) {
      return absl::InvalidArgumentError(
          absl::StrCat("cost weights must be finite and >= 0, got ", v));
    }
  }
  if (!(zeta1_per_m > 0.0)) return absl::InvalidArgumentError("zeta1_per_m must be > 0");
  return absl::OkStatus();
}

absl::Status PsoOptions::Validate() const {
  if (particles < 1 || particles > 10000) {
    return absl::InvalidArgumentError(
        absl::StrCat("pso.particles must be in [1, 10000], got ", particles));
  }
  if (iterations < 0 || iterations > 100000) {
    return absl::InvalidArgumentError(
        absl::StrCat("pso.iterations must be in [0, 100000], got ", iterations));
  }
  for (double v : {inertia, cognitive, social}) {
    if (!(v >= 0.0 && v <= 10.0))
      return absl::InvalidArgumentError("pso weights must be in [0, 10]");
  }
  if (!(velocity_limit > 0.0 && velocity_limit <= 100.0)) {
    return absl::InvalidArgumentError("pso.velocity_limit must be in (0, 100]");
  }
  return absl::OkStatus();
}

absl::Status Level2Options::Validate() const {
  if (segments < 2 || segments > 1000) {
    return absl::InvalidArgumentError(
        absl::StrCat("segments must be in [2, 1000], got ", segments));
  }
  SEAPLAN_RETURN_IF_ERROR(pso.Validate());
  SEAPLAN_RETURN_IF_ERROR(weights.Validate());
  if (polish.max_evaluations < 0 || !(polish.initial_step_m > 0) || !(polish.xtol_m > 0)) {
    return absl::InvalidArgumentError(
        "polish needs max_evaluations >= 0, initial_step_m > 0, xtol_m > 0");
  }
  if (!(ttg_step_s > 0.0) || !(ttg_horizon_s > 0.0) || ttg_horizon_s / ttg_step_s > 100000) {
    return absl::InvalidArgumentError("TTG needs step > 0, horizon > 0 and at most 1e5 steps");
  }
  if (!(drift_initial_speed_mps >= 0.0 && drift_initial_speed_mps < 50.0)) {
    return absl::InvalidArgumentError("drift_initial_speed_mps must be in [0, 50)");
  }
  if (threads < 1 || threads > 256)
    return absl::InvalidArgumentError("threads must be in [1, 256]");
  if (!(turn_radius_m >= 0.0 && turn_radius_m < 1e5)) {
    return absl::InvalidArgumentError("turn_radius_m must be in [0, 1e5)");
  }
  if (!(sail_speed_mps > 0.0 && sail_speed_mps < 50.0)) {
    return absl::InvalidArgumentError(
        absl::StrCat("sail_speed_mps must be in (0, 50), got ", sail_speed_mps));
  }
  SEAPLAN_RETURN_IF_ERROR(sail_repair.Validate());
  // Checked whether or not the fillets are on (a bad value is an error, not
  // silently unused); radius 0 (fillets off with the turn check) is checked
  // with the default radius.
  TurnFilletOptions fillet = Fillet();
  if (fillet.radius_m == 0.0) fillet.radius_m = TurnFilletOptions{}.radius_m;
  if (absl::Status st = fillet.Validate(); !st.ok()) {
    return absl::InvalidArgumentError(st.message());
  }
  return absl::OkStatus();
}

TurnFilletOptions Level2Options::Fillet() const {
  TurnFilletOptions fillet;
  fillet.radius_m = fillet_radius_m != 0.0 ? fillet_radius_m : turn_radius_m;
  fillet.clearance_m = fillet_clearance_m;
  fillet.min_radius_m = std::min(fillet_min_radius_m, fillet.radius_m);
  return fillet;
}

StatusOr<Level2Result> OptimizeLevel2(const Level2Problem& problem, const Level2Options& options,
                                      const StopToken& stop) {
  const auto t0 = std::chrono::steady_clock::now();
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  if (problem.field == nullptr || problem.grounding == nullptr) {
    return absl::InvalidArgumentError("Level2Problem needs a field and a grounding model");
  }
  for (size_t a = 0; a < problem.alternatives.size(); ++a) {
    const auto& alt = problem.alternatives[a];
    if (alt.size() < 2) {
      return absl::InvalidArgumentError(
          absl::StrCat("alternative ", a, " has ", alt.size(), " points (need >= 2)"));
    }
    for (const EastNorth& p : alt) {
      if (!std::isfinite(p.east_m) || !std::isfinite(p.north_m)) {
        return absl::InvalidArgumentError(
            absl::StrCat("alternative ", a, " has a non-finite point"));
      }
    }
  }
  SEAPLAN_ASSIGN_OR_RETURN(ship::HullDynamics dyn, ship::HullDynamics::Create(problem.drift_ship));
  const ObstacleField& field = *problem.field;
  const CostWeights& w = options.weights;
  const int n = options.segments;
  const EastNorth lo = field.area_min(), hi = field.area_max();

  // P(G) per Euler step of the TTG loop (the only TTG values it produces).
  std::vector<ModeArray> table;
  {
    const DriftTrack probe = SimulateDrift(dyn, problem.environment, 0.0, 0.0,
                                           options.ttg_horizon_s, options.ttg_step_s);
    for (double t : probe.time_s) table.push_back(problem.grounding->Probabilities(t));
  }

  // Tasks: every waypoint 0..n of every alternative (0 and n fixed).
  std::vector<WaypointTask> tasks;
  for (size_t a = 0; a < problem.alternatives.size(); ++a) {
    const std::vector<EastNorth> refs = Resample(problem.alternatives[a], n);
    for (int k = 0; k <= n; ++k) {
      WaypointTask t;
      t.alt = static_cast<int>(a);
      t.k = k;
      t.refs.prev = refs[std::max(k - 1, 0)];
      t.refs.ref = refs[k];
      t.refs.next = refs[std::min(k + 1, n)];
      const EastNorth d{t.refs.next.east_m - t.refs.prev.east_m,
                        t.refs.next.north_m - t.refs.prev.north_m};
      t.refs.heading_rad = std::atan2(d.east_m, d.north_m);
      t.refs.scale_m =
          std::max(1.0, Dist(t.refs.prev, t.refs.next) / (k == 0 || k == n ? 1.0 : 2.0));
      t.refs.movable = k > 0 && k < n;
      t.position = refs[k];
      tasks.push_back(t);
    }
  }
  auto make_evaluator = [&](const Refs& r) -> std::unique_ptr<RiskEvaluator> {
    if (options.risk_evaluation == RiskEvaluation::kExact) {
      return std::make_unique<ExactEvaluator>(field, dyn, problem.environment, *problem.grounding,
                                              r.heading_rad, options);
    }
    return std::make_unique<FastEvaluator>(
        field,
        SimulateDrift(dyn, problem.environment, r.heading_rad, options.drift_initial_speed_mps,
                      options.ttg_horizon_s, options.ttg_step_s),
        table, w.zeta1_per_m);
  };

  // Phase 1: PSO per movable waypoint.
  RunParallel(static_cast<int>(tasks.size()), options.threads, [&](int i) {
    WaypointTask& t = tasks[i];
    if (!t.refs.movable) return;
    auto eval = make_evaluator(t.refs);
    const uint64_t seed =
        SplitMix64(options.pso.seed ^
                   SplitMix64((static_cast<uint64_t>(t.alt) << 32) | static_cast<uint64_t>(t.k)));
    t.position = RunPso(options.pso, w, t.refs, *eval, lo, hi, seed, stop, &t.evaluations);
  });

  // Mode costs at the current positions, DP per alternative.
  const size_t alt_count = problem.alternatives.size();
  auto evaluate_all = [&](std::vector<RiskSample>* samples, std::vector<CostTerms>* terms) {
    samples->assign(tasks.size(), {});
    terms->assign(tasks.size(), {});
    RunParallel(static_cast<int>(tasks.size()), options.threads, [&](int i) {
      auto eval = make_evaluator(tasks[i].refs);
      eval->Evaluate(tasks[i].position, &(*samples)[i]);
      ComputeCost(w, tasks[i].refs, tasks[i].position, (*samples)[i], &(*terms)[i]);
      ++tasks[i].evaluations;
    });
  };
  auto assign = [&](const std::vector<CostTerms>& terms) {
    std::vector<int> modes(tasks.size(), 0);
    for (size_t a = 0; a < alt_count; ++a) {
      std::vector<ModeArray> costs(n);
      const size_t base = a * (n + 1);
      for (int k = 0; k < n; ++k) costs[k] = terms[base + k].mode_cost;
      const std::vector<int> m = AssignModes(costs, w.mode_switch_cost);
      for (int k = 0; k < n; ++k) modes[base + k] = m[k];
      modes[base + n] = m[n - 1];
    }
    return modes;
  };
  std::vector<RiskSample> samples;
  std::vector<CostTerms> terms;
  evaluate_all(&samples, &terms);
  std::vector<int> modes = assign(terms);

  // Phase 2: polish with the mode fixed, then re-assign.
  if (options.polish.max_evaluations > 0 && !stop.StopRequested()) {
    RunParallel(static_cast<int>(tasks.size()), options.threads, [&](int i) {
      WaypointTask& t = tasks[i];
      if (!t.refs.movable) return;
      auto eval = make_evaluator(t.refs);
      t.position =
          Polish(options.polish, w, t.refs, *eval, t.position, modes[i], lo, hi, &t.evaluations);
    });
    evaluate_all(&samples, &terms);
    modes = assign(terms);
  }

  const TurnFilletOptions fillet = options.Fillet();
  // Step 6's fillets on a wider circle: the hull under its autopilot turns
  // wider than the fillet radius on a run of small corners.
  TurnFilletOptions wider = fillet;
  wider.radius_m = 1.5 * fillet.radius_m;
  wider.min_radius_m = fillet.min_radius_m > 0.0 ? fillet.radius_m : 0.0;
  const bool fillets = options.FilletsOn();

  Level2Result result;
  result.stopped = stop.StopRequested();
  result.alternatives.resize(alt_count);
  // Per alternative: its candidate routes (steps 5 and 6) in the order step 6
  // sails them, each with its costs, modes and waypoints, and its polyline.
  std::vector<std::vector<AlternativeResult>> candidates(alt_count);
  std::vector<std::vector<std::vector<EastNorth>>> candidate_lines(alt_count);
  std::vector<std::vector<std::vector<WaypointTask>>> candidate_tasks(alt_count);
  // A candidate's costs, modes and waypoint results: the optimised
  // waypoints' as evaluated, or (`changed`) every waypoint evaluated again.
  auto evaluate_candidate = [&](size_t a, std::vector<WaypointTask> waypoints, bool changed,
                                AlternativeResult out) {
    const size_t base = a * (n + 1);
    std::vector<RiskSample> route_samples(samples.begin() + base, samples.begin() + base + n + 1);
    std::vector<CostTerms> route_terms(terms.begin() + base, terms.begin() + base + n + 1);
    std::vector<int> route_modes(modes.begin() + base, modes.begin() + base + n + 1);
    if (changed) {
      // Inserted vertices: neighbours and drift heading along the
      // candidate. The others keep their references (their cost terms are
      // defined on them; the fuel term's |w - r_{k+1}| is then the chord).
      const size_t m = waypoints.size();
      for (size_t k = 0; k < m; ++k) {
        Refs& r = waypoints[k].refs;
        if (!r.movable && k > 0 && k + 1 < m) {
          r.prev = waypoints[k - 1].position;
          r.next = waypoints[k + 1].position;
          const EastNorth d{r.next.east_m - r.prev.east_m, r.next.north_m - r.prev.north_m};
          r.heading_rad = std::atan2(d.east_m, d.north_m);
        }
      }
      route_samples.assign(m, {});
      route_terms.assign(m, {});
      for (size_t k = 0; k < m; ++k) {
        auto eval = make_evaluator(waypoints[k].refs);
        eval->Evaluate(waypoints[k].position, &route_samples[k]);
        ComputeCost(w, waypoints[k].refs, waypoints[k].position, route_samples[k], &route_terms[k]);
        ++out.evaluations;
      }
      std::vector<ModeArray> costs(m - 1);
      for (size_t k = 0; k + 1 < m; ++k) costs[k] = route_terms[k].mode_cost;
      route_modes = AssignModes(costs, w.mode_switch_cost);
      route_modes.push_back(route_modes.back());
    }

    const size_t m = waypoints.size();
    for (size_t k = 0; k < m; ++k) {
      const WaypointTask& t = waypoints[k];
      WaypointResult wr;
      wr.position = t.position;
      wr.reference = t.refs.ref;
      wr.heading_rad = t.refs.heading_rad;
      wr.mode = static_cast<MsoMode>(route_modes[k]);
      wr.ttg_s = route_samples[k].ttg_s;
      wr.grounding_probability = route_samples[k].p;
      wr.proximity = route_samples[k].proximity;
      wr.mode_cost = route_terms[k].mode_cost;
      wr.path_cost = route_terms[k].path;
      if (k + 1 < m) {
        const int mode = route_modes[k];
        const double ground =
            w.grounding_cost * (w.mu3 * wr.proximity + w.mu4 * wr.grounding_probability[mode]);
        out.grounding_cost += ground;
        out.mso_cost += wr.mode_cost[mode] - ground;
        if (k > 0 && route_modes[k - 1] != mode) {
          ++out.mode_switches;
          out.switching_cost += w.mode_switch_cost;
        }
      }
      out.path_cost += wr.path_cost;
      if (field.Inside(wr.position)) out.crosses_obstacle = true;
      if (k > 0 && field.SegmentHits(out.waypoints.back().position, wr.position))
        out.crosses_obstacle = true;
      out.waypoints.push_back(wr);
    }
    out.expected_cost = out.grounding_cost + out.mso_cost + out.switching_cost;
    out.objective = out.expected_cost + out.path_cost;
    return out;
  };
  for (size_t a = 0; a < alt_count; ++a) {
    const size_t base = a * (n + 1);
    // This alternative's waypoints, samples, costs and modes as optimised.
    const std::vector<WaypointTask> route(tasks.begin() + base, tasks.begin() + base + n + 1);
    int64_t route_evaluations = 0;
    for (const WaypointTask& t : route) route_evaluations += t.evaluations;

    std::vector<EastNorth> refs(n + 1), positions(n + 1);
    for (int k = 0; k <= n; ++k) {
      refs[k] = route[k].refs.ref;
      positions[k] = route[k].position;
    }
    const Repair repair = RepairRoute(field, refs, options.turn_radius_m, &positions);
    const std::vector<EastNorth>& line = problem.alternatives[a];
    // The waypoints a candidate starts from: the optimised route repaired,
    // or (step 6's fallback) the Level-1 polyline, none of it optimised.
    struct Waypoints {
      std::vector<WaypointTask> tasks;
      bool changed = false;  // not the optimised route as it is
      int snapped = 0, inserted = 0;
    };
    Waypoints repaired{
        {}, repair.snapped_count > 0 || repair.followed_count > 0, repair.snapped_count, 0};
    {
      double total = 0.0;
      for (size_t i = 1; i < line.size(); ++i) total += Dist(line[i - 1], line[i]);
      for (int k = 0; k <= n; ++k) {
        WaypointTask t = route[k];
        t.position = positions[k];
        t.evaluations = 0;
        repaired.tasks.push_back(t);
        if (k == n || !repair.follow[k]) continue;
        for (EastNorth v : VerticesBetween(line, total * k / n, total * (k + 1) / n)) {
          repaired.tasks.push_back(FixedWaypoint(a, k, v));  // a Level-1 vertex
          ++repaired.inserted;
        }
      }
    }
    Waypoints level1{{}, true, n - 1, static_cast<int>(line.size()) - 2};
    level1.tasks.push_back(route.front());
    level1.tasks.back().evaluations = 0;
    for (size_t i = 1; i + 1 < line.size(); ++i)
      level1.tasks.push_back(FixedWaypoint(a, 0, line[i]));
    level1.tasks.push_back(route.back());
    level1.tasks.back().evaluations = 0;

    // The candidates: step 5's route first (its corners filleted), then
    // step 6's (the header says why these).
    struct CandidateMaker {
      RouteSource source;
      const Waypoints* from;
      const TurnFilletOptions* fillet;  // null: the corners left sharp
    };
    std::vector<CandidateMaker> makers = {
        {RouteSource::kOptimised, &repaired, fillets ? &fillet : nullptr}};
    if (options.sail_check && fillets) {
      makers.insert(makers.end(), {{RouteSource::kOptimisedSharp, &repaired, nullptr},
                                   {RouteSource::kOptimised, &repaired, &wider},
                                   {RouteSource::kLevel1, &level1, &fillet},
                                   {RouteSource::kLevel1Sharp, &level1, nullptr},
                                   {RouteSource::kLevel1, &level1, &wider}});
    } else if (options.sail_check) {
      makers.push_back({RouteSource::kLevel1, &level1, nullptr});
    }
    for (const CandidateMaker& maker : makers) {
      AlternativeResult out;
      out.source = maker.source;
      out.snapped_waypoints = maker.from->snapped;
      out.inserted_waypoints = maker.from->inserted;
      out.evaluations = route_evaluations;
      std::vector<WaypointTask> waypoints = maker.from->tasks;
      bool changed = maker.from->changed;
      if (maker.fillet != nullptr) {
        SEAPLAN_ASSIGN_OR_RETURN(FilletRoute filleted,
                                 FilletTurns(field, Positions(waypoints), *maker.fillet));
        out.filleted_turns = filleted.filleted;
        out.tightened_turns = filleted.tightened;
        out.unsailable_turns = std::move(filleted.unsailable);
        if (filleted.filleted > 0) {
          waypoints = WaypointsOf(a, waypoints, filleted.points, &out.inserted_waypoints);
          changed = true;
        }
      }
      candidate_tasks[a].push_back(waypoints);
      candidate_lines[a].push_back(Positions(waypoints));
      candidates[a].push_back(evaluate_candidate(a, std::move(waypoints), changed, std::move(out)));
    }
  }

  // The choice: the obstacle-free alternative with the lowest expected cost;
  // with the sail check, one whose sailed track keeps clear before any that
  // does not. An alternative's candidates are sailed in order until one's
  // track keeps clear (that one is kept), else the one whose track keeps the
  // most clearance is. The alternatives are sailed cheapest first: the one
  // whose remaining candidates could cost least (a lower bound, so the
  // choice is the one sailing every alternative would make), until a clear
  // alternative costs no more than any other could.
  if (!options.sail_check) {
    for (size_t a = 0; a < alt_count; ++a) result.alternatives[a] = std::move(candidates[a][0]);
  } else {
    struct Sailing {
      size_t next = 0;  // the next candidate to sail
      int kept = -1;    // the candidate kept so far
      SailedTrack track;
      bool done = false;
    };
    std::vector<Sailing> sailing(alt_count);
    const double inf = std::numeric_limits<double>::infinity();
    auto lowest_cost_to_come = [&](size_t a) {
      double c = inf;
      for (size_t j = sailing[a].next; j < candidates[a].size(); ++j) {
        if (!candidates[a][j].crosses_obstacle) c = std::min(c, candidates[a][j].expected_cost);
      }
      return c;
    };
    auto clear_choice = [&]() {
      int best_a = -1;
      for (size_t a = 0; a < alt_count; ++a) {
        const Sailing& s = sailing[a];
        if (s.kept < 0 || !SailedClear(s.track) || candidates[a][s.kept].crosses_obstacle) continue;
        if (best_a < 0 || candidates[a][s.kept].expected_cost <
                              candidates[best_a][sailing[best_a].kept].expected_cost) {
          best_a = static_cast<int>(a);
        }
      }
      return best_a;
    };
    for (;;) {
      int next_a = -1;
      double next_cost = inf;
      for (size_t a = 0; a < alt_count; ++a) {
        if (sailing[a].done) continue;
        const double c = lowest_cost_to_come(a);
        if (next_a < 0 || c < next_cost) {
          next_a = static_cast<int>(a);
          next_cost = c;
        }
      }
      if (next_a < 0) break;  // every alternative sailed: none keeps clear
      if (const int clear = clear_choice(); clear >= 0) {
        const double c = candidates[clear][sailing[clear].kept].expected_cost;
        if (c < next_cost || (c == next_cost && clear < next_a)) break;
      }
      Sailing& s = sailing[next_a];
      SEAPLAN_ASSIGN_OR_RETURN(SailedTrack track, SailRoute(candidate_lines[next_a][s.next],
                                                            options.sail_speed_mps, &field));
      if (s.kept < 0 || SailedClear(track) || track.clearance_m > s.track.clearance_m) {
        s.kept = static_cast<int>(s.next);
        s.track = std::move(track);
      }
      ++s.next;
      s.done = SailedClear(s.track) || s.next == candidates[next_a].size();
    }
    // No candidate of any alternative keeps clear: the kept ones are bent
    // where their tracks come closest to an obstacle and sailed again
    // (sail_check.h RepairSailedRoute), cheapest first, until one keeps
    // clear. The bent route keeps out of the buffered obstacles like the
    // others (its segments are checked) and is evaluated like them.
    if (options.sail_repair.max_sails > 0 && clear_choice() < 0 && !stop.StopRequested()) {
      std::vector<size_t> order;
      for (size_t a = 0; a < alt_count; ++a) {
        const Sailing& s = sailing[a];
        if (s.kept >= 0 && !candidates[a][s.kept].crosses_obstacle) order.push_back(a);
      }
      std::stable_sort(order.begin(), order.end(), [&](size_t x, size_t y) {
        return candidates[x][sailing[x].kept].expected_cost <
               candidates[y][sailing[y].kept].expected_cost;
      });
      for (size_t a : order) {
        if (stop.StopRequested()) break;
        Sailing& s = sailing[a];
        const std::vector<EastNorth>& line = candidate_lines[a][s.kept];
        StatusOr<SailRepair> repaired = RepairSailedRoute(
            field, line, s.track, options.sail_speed_mps, options.sail_repair, &stop);
        if (!repaired.ok()) {  // the candidate stays as it was, with its warning
          log::Warn("route: repair of alternative {} failed: {}", a, repaired.status().ToString());
          continue;
        }
        SailRepair& fix = *repaired;
        if (fix.bends == 0) continue;
        const AlternativeResult& was = candidates[a][s.kept];
        AlternativeResult out;
        out.source = was.source;
        out.snapped_waypoints = was.snapped_waypoints;
        out.inserted_waypoints = was.inserted_waypoints;
        out.filleted_turns = was.filleted_turns;
        out.tightened_turns = was.tightened_turns;
        // The corners the repair moved are no longer the route's.
        for (const UnsailableTurn& turn : was.unsailable_turns) {
          if (std::any_of(fix.points.begin(), fix.points.end(), [&](const FilletPoint& p) {
                return Distance(p.position, turn.corner) < 1.0;
              })) {
            out.unsailable_turns.push_back(turn);
          }
        }
        out.evaluations = was.evaluations;
        out.sail_bends = fix.bends;
        // Moved vertices replace their originals; only the added ones are new.
        int moved_or_added = 0;
        std::vector<WaypointTask> waypoints =
            WaypointsOf(a, candidate_tasks[a][s.kept], fix.points, &moved_or_added);
        out.inserted_waypoints +=
            static_cast<int>(fix.points.size()) - static_cast<int>(line.size());
        out = evaluate_candidate(a, std::move(waypoints), true, std::move(out));
        if (out.crosses_obstacle) continue;
        candidates[a][s.kept] = std::move(out);
        s.track = std::move(fix.track);
        if (SailedClear(s.track)) break;
      }
    }
    for (size_t a = 0; a < alt_count; ++a) {
      const Sailing& s = sailing[a];
      // Not sailed (a cheaper alternative keeps clear): its first candidate.
      AlternativeResult& out = result.alternatives[a];
      out = std::move(candidates[a][std::max(s.kept, 0)]);
      if (s.kept < 0) continue;
      out.sail_checked = true;
      out.sailed_clear = SailedClear(s.track);
      out.sailed_arrived = s.track.arrived;
      out.sailed_clearance_m = s.track.clearance_m;
      out.sailed_closest = s.track.closest;
    }
  }
  double best = std::numeric_limits<double>::infinity();
  for (size_t a = 0; a < alt_count; ++a) {
    const AlternativeResult& out = result.alternatives[a];
    result.evaluations += out.evaluations;
    // A route whose sailed track keeps clear beats any that does not.
    const double rank = out.expected_cost + (out.sail_checked && !out.sailed_clear ? 1e300 : 0.0);
    if (!out.crosses_obstacle && (rank < best || result.chosen < 0)) {
      best = rank;
      result.chosen = static_cast<int>(a);
    }
  }
  result.stopped = result.stopped || stop.StopRequested();  // also during the sail check
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace seaplan::route
