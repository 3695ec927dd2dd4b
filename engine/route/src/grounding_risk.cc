#include "seaplan/route/grounding_risk.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace seaplan::route {

const char* MsoModeName(MsoMode mode) {
  switch (mode) {
    case MsoMode::kPto: return "PTO";
    case MsoMode::kMec: return "MEC";
    case MsoMode::kPti: return "PTI";
  }
  return "?";
}

double RecoveryEvent::Probability(double available_s) const {
  const double t = available_s - min_s;
  if (!(t > 0.0)) return 0.0;
  const double sigma = std::sqrt(std);
  const double z = std::log(t / mean_s) / sigma;
  return nominal_probability * 0.5 * std::erfc(-z / std::sqrt(2.0));
}

absl::Status EventTreeParameters::Validate() const {
  for (double r : {main_engine_failure_rate, genset1_failure_rate, genset2_failure_rate,
                   hsg_failure_rate}) {
    if (!(r >= 0.0 && r < 1.0)) return absl::InvalidArgumentError(absl::StrCat("failure rate ", r, " outside [0, 1) per s"));
  }
  if (!(risk_interval_s > 0.0)) return absl::InvalidArgumentError("risk_interval_s must be > 0");
  for (const RecoveryEvent* e : {&start_main_engine, &restart_main_engine, &start_genset1, &start_genset2,
                                 &restart_genset1, &restart_genset2, &start_hsg, &restart_hsg}) {
    if (!(e->nominal_probability >= 0 && e->nominal_probability <= 1 && e->mean_s > 0 && e->std > 0 &&
          e->min_s >= 0)) {
      return absl::InvalidArgumentError("recovery event needs p in [0,1], mean > 0, std > 0, min >= 0");
    }
  }
  return absl::OkStatus();
}

ModeArray EventTreeGroundingModel::Probabilities(double ttg_s) const {
  const EventTreeParameters& p = p_;
  auto trigger = [&](double rate) { return 1.0 - std::exp(-rate * p.risk_interval_s); };
  const double me = trigger(p.main_engine_failure_rate);
  const double dgs = trigger(p.genset1_failure_rate) * trigger(p.genset2_failure_rate);
  const double hsg = trigger(p.hsg_failure_rate);

  const double r_me = p.restart_main_engine.Probability(ttg_s);
  const double s_me = p.start_main_engine.Probability(ttg_s);
  const double s_dg1 = p.start_genset1.Probability(ttg_s);
  const double s_dg2 = p.start_genset2.Probability(ttg_s);
  const double r_dg1 = p.restart_genset1.Probability(ttg_s);
  const double r_dg2 = p.restart_genset2.Probability(ttg_s);
  const double s_hsg = p.start_hsg.Probability(ttg_s);
  const double r_hsg = p.restart_hsg.Probability(ttg_s);

  // Success = sum over the event-tree paths (SHIP_MODEL.md 7).
  const double ok_pto = r_me + (1 - r_me) * s_dg1 * s_hsg + (1 - r_me) * (1 - s_dg1) * s_dg2 * s_hsg;
  const double ok_mec = r_me + (1 - r_me) * s_hsg;
  const double ok_pti_dgs = s_me + (1 - s_me) * r_dg1 + (1 - s_me) * (1 - r_dg1) * r_dg2;
  const double ok_pti_hsg = s_me + (1 - s_me) * r_hsg;

  ModeArray out;
  out[0] = me * (1 - ok_pto);
  out[1] = me * (1 - ok_mec);
  out[2] = 1.0 - (1.0 - dgs * (1 - ok_pti_dgs)) * (1.0 - hsg * (1 - ok_pti_hsg));
  return out;
}

}  // namespace seaplan::route
