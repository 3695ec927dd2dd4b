#include "seaplan/risk/time_to_grounding.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace seaplan::risk {

Status TtgOptions::Validate() const {
  if (!(horizon_s > 0.0) || !std::isfinite(horizon_s) || !(dt_s > 0.0) || !std::isfinite(dt_s)) {
    return absl::InvalidArgumentError(absl::StrCat("TtgOptions: horizon_s ", horizon_s,
                                                   " and dt_s ", dt_s, " must be finite and > 0"));
  }
  if (!std::isfinite(hull_length_m) || !std::isfinite(hull_beam_m)) {
    return absl::InvalidArgumentError("TtgOptions: hull dimensions must be finite");
  }
  if (horizon_s / dt_s + 1.0 > max_steps) {
    return absl::InvalidArgumentError(absl::StrCat(
        "TtgOptions: horizon_s/dt_s = ", horizon_s / dt_s, " exceeds max_steps ", max_steps));
  }
  return absl::OkStatus();
}

TimeToGroundingSimulator::TimeToGroundingSimulator(const ship::ShipParams& ship,
                                                   const TtgOptions& o)
    : dynamics_(ship),
      options_(o),
      length_m_(o.hull_length_m > 0 ? o.hull_length_m : ship.length_m),
      beam_m_(o.hull_beam_m > 0 ? o.hull_beam_m : ship.beam_m) {}

StatusOr<TimeToGroundingSimulator> TimeToGroundingSimulator::Create(const ship::ShipParams& ship,
                                                                    const TtgOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(ship.Validate());
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  return TimeToGroundingSimulator(ship, options);
}

Status TimeToGroundingSimulator::CheckInputs(const ship::ShipState& start,
                                             const ship::Environment& env) {
  if (!start.eta.allFinite() || !start.nu.allFinite()) {
    return absl::InvalidArgumentError("time to grounding: start state must be finite");
  }
  return env.Validate();
}

TtgResult TimeToGroundingSimulator::Run(const ship::ShipState& start, const ship::Environment& env,
                                        const GroundingTest& obstacles,
                                        std::vector<DriftTrackPoint>* track) const {
  ship::ShipState s = start;
  TtgResult result;
  double t = 0.0;
  if (track != nullptr) {
    track->clear();
    track->push_back({0.0, s});
  }
  // One cos/sin pair per step serves both the hull outline and the next
  // derivative; the environment's trigonometry is done once.
  const ship::PreparedEnvironment penv = ship::PreparedEnvironment::From(env);
  double c = std::cos(s.eta[2]), sn = std::sin(s.eta[2]);
  if (options_.check_initial_pose && obstacles.HullIntersects(HullPolygon::Rectangle(
                                         s.eta[0], s.eta[1], c, sn, length_m_, beam_m_))) {
    result.grounded = true;
    return result;
  }
  const Eigen::Vector3d no_control = Eigen::Vector3d::Zero();
  while (t <= options_.horizon_s) {
    dynamics_.EulerStep(s, c, sn, penv, no_control, options_.dt_s);
    t += options_.dt_s;
    ++result.steps;
    if (track != nullptr) track->push_back({t, s});
    c = std::cos(s.eta[2]);
    sn = std::sin(s.eta[2]);
    if (obstacles.HullIntersects(
            HullPolygon::Rectangle(s.eta[0], s.eta[1], c, sn, length_m_, beam_m_))) {
      result.grounded = true;
      break;
    }
  }
  result.ttg_s = t;
  return result;
}

}  // namespace seaplan::risk
