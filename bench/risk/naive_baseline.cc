#include "naive_baseline.h"

#include <cmath>
#include <memory>
#include <vector>

#include "Eigen/Dense"

namespace seaplan::bench {
namespace {

using Eigen::MatrixXd;
using Eigen::VectorXd;

struct NaiveShip {
  explicit NaiveShip(const ship::ShipParams& params) : p(params) {
    mass = p.Mass();
    i_z = p.YawInertia();
    x_du = mass * p.added_mass_coefficient_surge;
    y_dv = mass * p.added_mass_coefficient_sway;
    n_dr = i_z * p.added_mass_coefficient_yaw;
  }
  MatrixXd Rotation(double psi) const {
    MatrixXd r(3, 3);
    r << std::cos(psi), -std::sin(psi), 0, std::sin(psi), std::cos(psi), 0, 0, 0, 1;
    return r;
  }
  MatrixXd Mass() const {
    MatrixXd m(3, 3);
    m << mass + x_du, 0, 0, 0, mass + y_dv, mass * p.x_g_m, 0, mass * p.x_g_m, i_z + n_dr;
    return m;
  }
  VectorXd Wind(const ship::Environment& env, double psi, double u, double v) const {
    const double uw = env.wind_speed_mps * std::cos(env.wind_direction_from_rad - psi);
    const double vw = env.wind_speed_mps * std::sin(env.wind_direction_from_rad - psi);
    const double u_rw = uw - u, v_rw = vw - v;
    const double g = -std::atan2(v_rw, u_rw);
    const double q = 0.5 * p.air_density_kgpm3 * (u_rw * u_rw + v_rw * v_rw);
    VectorXd f(3);
    f << q * (-p.wind_coefficient_x * std::cos(g)) * p.beam_m * p.front_height_m,
        q * (p.wind_coefficient_y * std::sin(g)) * p.length_m * p.side_height_m,
        q * (p.wind_coefficient_n * std::sin(2 * g)) * p.length_m * p.side_height_m * p.length_m;
    return f;
  }
  void Step(ship::ShipState& s, const ship::Environment& env, double dt) const {
    const double psi = s.eta[2], u = s.nu[0], v = s.nu[1], r = s.nu[2];
    VectorXd vel(3);
    vel << u, v, r;
    const VectorXd eta_dot = Rotation(psi) * vel;
    VectorXd vc_ned(3);
    vc_ned << env.current_north_mps, env.current_east_mps, 0;
    const VectorXd vc = Rotation(psi).inverse() * vc_ned;
    const double u_r = u - vc[0], v_r = v - vc[1];
    MatrixXd crb(3, 3), ca(3, 3), dl(3, 3), dnl(3, 3);
    crb << 0, 0, -mass * (p.x_g_m * r + v), 0, 0, mass * u, mass * (p.x_g_m * r + v), -mass * u, 0;
    ca << 0, 0, y_dv * v_r, 0, 0, -x_du * u_r, -y_dv * v_r, x_du * u_r, 0;
    dl << mass / p.damping_time_constant_surge_s, 0, 0, 0, mass / p.damping_time_constant_sway_s, 0,
        0, 0, i_z / p.damping_time_constant_yaw_s;
    dnl << p.nonlinear_damping_surge * u, 0, 0, 0, p.nonlinear_damping_sway * v, 0, 0, 0,
        p.nonlinear_damping_yaw * r;
    const VectorXd nu_dot = Mass().inverse() * (-crb * vel - ca * (vel - vc) -
                                                (dl + dnl) * (vel - vc) + Wind(env, psi, u, v));
    for (int i = 0; i < 3; ++i) {
      s.eta[i] += eta_dot[i] * dt;
      s.nu[i] += nu_dot[i] * dt;
    }
  }
  ship::ShipParams p;
  double mass, i_z, x_du, y_dv, n_dr;
};

risk::HullPolygon NaiveHull(const ship::ShipState& s, double l, double b) {
  // Built through heap vectors, as a shapely Polygon would be.
  std::vector<Eigen::Vector2d> body = {
      {l / 2, -b / 2}, {l / 2, b / 2}, {-l / 2, b / 2}, {-l / 2, -b / 2}};
  std::vector<Eigen::Vector2d> world;
  for (const auto& c : body) {
    // NOLINTNEXTLINE(performance-inefficient-vector-operation): naive on purpose (see above).
    world.push_back({s.eta[0] + c[0] * std::cos(s.eta[2]) - c[1] * std::sin(s.eta[2]),
                     s.eta[1] + c[0] * std::sin(s.eta[2]) + c[1] * std::cos(s.eta[2])});
  }
  risk::HullPolygon h;
  for (int i = 0; i < 4; ++i) {
    h.corners_ne[i] = world[i];
    h.bounds.Extend(world[i]);
  }
  return h;
}

// events.py StartUpEvent: builds its distribution on construction and on
// every probability update.
struct NaiveEvent {
  NaiveEvent(const risk::RecoveryEventParams& p, double t) : params(p) { Update(t); }
  void Update(double t) {
    const double s = std::sqrt(params.std);  // scipy lognorm(s = sqrt(std))
    const double scale = params.mean_s, loc = params.min_time_s;
    const double cdf =
        t <= loc ? 0.0 : 0.5 * std::erfc(-std::log((t - loc) / scale) / (s * std::sqrt(2.0)));
    probability = params.nominal_probability * cdf;
  }
  risk::RecoveryEventParams params;
  double probability = 0.0;
};

struct NaivePathElement {
  std::shared_ptr<NaiveEvent> event;
  bool occurs;
};

}  // namespace

risk::TtgResult NaiveTimeToGrounding(const ship::ShipParams& params, const ship::ShipState& start,
                                     const ship::Environment& env,
                                     const risk::GroundingTest& obstacles, double horizon_s,
                                     double dt_s) {
  auto model = std::make_unique<NaiveShip>(params);  // risks.py set_initial_states
  ship::ShipState s = start;
  std::vector<ship::ShipState> positions;  // drifting_ship_positions
  risk::TtgResult r;
  double t = 0.0;
  bool grounded = false;
  while (t <= horizon_s && !grounded) {
    model->Step(s, env, dt_s);
    positions.push_back(s);
    t += dt_s;
    ++r.steps;
    grounded = obstacles.HullIntersects(NaiveHull(s, params.length_m, params.beam_m));
  }
  r.ttg_s = t;
  r.grounded = grounded;
  return r;
}

double NaiveGroundingProbability(const risk::DriftingGroundingParams& p, ship::MsoMode mode,
                                 double t) {
  using risk::RecoveryEvent;
  auto ev = [&](RecoveryEvent e) {
    return std::make_shared<NaiveEvent>(p.events[static_cast<int>(e)], t);
  };
  auto trig = [&](risk::Component c) {
    return 1.0 - std::exp(-p.failure_rate_per_s[static_cast<int>(c)] * p.risk_interval_s);
  };
  // CaseStudyScenario builds every event and tree for every call.
  auto start_me = ev(RecoveryEvent::kStartMe), restart_me = ev(RecoveryEvent::kRestartMe);
  auto start_dg1 = ev(RecoveryEvent::kStartDg1), start_dg2 = ev(RecoveryEvent::kStartDg2);
  auto restart_dg1 = ev(RecoveryEvent::kRestartDg1), restart_dg2 = ev(RecoveryEvent::kRestartDg2);
  auto start_hsg = ev(RecoveryEvent::kStartHsg), restart_hsg = ev(RecoveryEvent::kRestartHsg);
  using Tree = std::vector<std::vector<NaivePathElement>>;
  struct Scenario {
    double p_loss;
    Tree tree;
  };
  std::vector<std::vector<Scenario>> modes;
  modes.push_back(
      {{trig(risk::Component::kMainEngine),
        {{{restart_me, true}},
         {{restart_me, false}, {start_dg1, true}, {start_hsg, true}},
         {{restart_me, false}, {start_dg1, false}, {start_dg2, true}, {start_hsg, true}}}}});
  modes.push_back({{trig(risk::Component::kMainEngine),
                    {{{restart_me, true}}, {{restart_me, false}, {start_hsg, true}}}}});
  modes.push_back(
      {{trig(risk::Component::kDieselGenerator1) * trig(risk::Component::kDieselGenerator2),
        {{{start_me, true}},
         {{start_me, false}, {restart_dg1, true}},
         {{start_me, false}, {restart_dg1, false}, {restart_dg2, true}}}},
       {trig(risk::Component::kHsg),
        {{{start_me, true}}, {{start_me, false}, {restart_hsg, true}}}}});
  double prod = 1.0;
  for (const Scenario& s : modes[static_cast<int>(mode)]) {
    double success = 0.0;
    for (const auto& path : s.tree) {
      double pp = 1.0;
      for (const NaivePathElement& el : path) {
        el.event->Update(t);  // path_element.update_probability
        pp *= el.occurs ? el.event->probability : 1.0 - el.event->probability;
      }
      success += pp;
    }
    prod -= (1.0 - success) * s.p_loss;
  }
  return 1.0 - prod;
}

}  // namespace seaplan::bench
