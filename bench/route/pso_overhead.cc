// Why engine/route runs its own PSO: the per-evaluation overhead of pagmo2's
// pso (type-erased problem, std::vector decision and fitness vectors per
// call, population bookkeeping) measured against a cost function as cheap as
// the route optimiser's fast evaluation (~0.35 us).
//
// Usage: route_pso_overhead
#include <time.h>

#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "pagmo/algorithms/pso.hpp"
#include "pagmo/population.hpp"
#include "pagmo/problem.hpp"
#include "pagmo/types.hpp"

namespace {

double CpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

// A 2-D cost with a little arithmetic, like one waypoint's cost terms.
double Cost(double x, double y) {
  double s = 0.0;
  for (int i = 0; i < 8; ++i) s += std::exp(-0.04 * std::hypot(x - 100.0 * i, y - 50.0 * i));
  return 1e-4 * (x * x + y * y) + s;
}

struct Waypoint {
  pagmo::vector_double fitness(const pagmo::vector_double& v) const { return {Cost(v[0], v[1])}; }
  std::pair<pagmo::vector_double, pagmo::vector_double> get_bounds() const {
    return {{-500.0, -500.0}, {500.0, 500.0}};
  }
};

}  // namespace

int main() {
  constexpr int kSwarms = 38, kParticles = 30, kIterations = 100;
  // pagmo: 30 particles, 100 generations, one population per waypoint;
  // variant 1 (inertia weight, per-dimension r) and gbest topology = our PSO.
  double t0 = CpuSeconds();
  double sink = 0.0;
  long long evals = 0;
  for (int w = 0; w < kSwarms; ++w) {
    pagmo::problem prob{Waypoint{}};
    pagmo::population pop{prob, kParticles, static_cast<unsigned>(w)};
    pagmo::algorithm algo{
        pagmo::pso(kIterations, 0.75, 1.0, 2.0, 1.0, 1u, 1u, 4u, false, static_cast<unsigned>(w))};
    pop = algo.evolve(pop);
    sink += pop.champion_f()[0];
    evals += static_cast<long long>(pop.get_problem().get_fevals());
  }
  const double pagmo_s = CpuSeconds() - t0;

  // The same number of bare evaluations in a plain loop.
  t0 = CpuSeconds();
  double x = 1.0, y = 2.0;
  for (long long i = 0; i < evals; ++i) {
    sink += Cost(x, y);
    x += 1e-6;
    y -= 1e-6;
  }
  const double bare_s = CpuSeconds() - t0;
  std::printf(
      "pagmo::pso, %d swarms x %d particles x %d generations: %lld evaluations, %.3f s CPU (%.3f "
      "us/eval)\n",
      kSwarms, kParticles, kIterations, evals, pagmo_s, 1e6 * pagmo_s / evals);
  std::printf("same cost function, bare loop: %.3f s CPU (%.3f us/eval)\n", bare_s,
              1e6 * bare_s / evals);
  std::printf(
      "pagmo overhead per evaluation: %.3f us (the route optimiser's whole fast evaluation is "
      "~0.35 us)\n",
      1e6 * (pagmo_s - bare_s) / evals);
  return sink > 0 ? 0 : 1;
}
