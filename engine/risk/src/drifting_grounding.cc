#include "seaplan/risk/drifting_grounding.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "absl/strings/str_cat.h"

namespace seaplan::risk {
namespace {

using E = RecoveryEvent;
using C = Component;

constexpr PathElement Occ(E e) {
  return {e, true};
}
constexpr PathElement Not(E e) {
  return {e, false};
}

ModeScenarios MakePto() {
  ModeScenarios m;
  m.size = 1;
  LoppScenario& s = m.scenarios[0];
  s.failures = {C::kMainEngine, C::kMainEngine};
  s.num_failures = 1;
  s.recovery.size = 3;
  s.recovery.paths[0] = {{Occ(E::kRestartMe)}, 1};
  s.recovery.paths[1] = {{Not(E::kRestartMe), Occ(E::kStartDg1), Occ(E::kStartHsg)}, 3};
  s.recovery.paths[2] = {
      {Not(E::kRestartMe), Not(E::kStartDg1), Occ(E::kStartDg2), Occ(E::kStartHsg)}, 4};
  return m;
}

ModeScenarios MakeMec() {
  ModeScenarios m;
  m.size = 1;
  LoppScenario& s = m.scenarios[0];
  s.failures = {C::kMainEngine, C::kMainEngine};
  s.num_failures = 1;
  s.recovery.size = 2;
  s.recovery.paths[0] = {{Occ(E::kRestartMe)}, 1};
  s.recovery.paths[1] = {{Not(E::kRestartMe), Occ(E::kStartHsg)}, 2};
  return m;
}

ModeScenarios MakePti() {
  ModeScenarios m;
  m.size = 2;
  LoppScenario& gensets = m.scenarios[0];
  gensets.failures = {C::kDieselGenerator1, C::kDieselGenerator2};
  gensets.num_failures = 2;
  gensets.recovery.size = 3;
  gensets.recovery.paths[0] = {{Occ(E::kStartMe)}, 1};
  gensets.recovery.paths[1] = {{Not(E::kStartMe), Occ(E::kRestartDg1)}, 2};
  // The public code repeats "restart DG1" here; DG2 is what the tree means.
  gensets.recovery.paths[2] = {{Not(E::kStartMe), Not(E::kRestartDg1), Occ(E::kRestartDg2)}, 3};
  LoppScenario& hsg = m.scenarios[1];
  hsg.failures = {C::kHsg, C::kHsg};
  hsg.num_failures = 1;
  hsg.recovery.size = 2;
  hsg.recovery.paths[0] = {{Occ(E::kStartMe)}, 1};
  hsg.recovery.paths[1] = {{Not(E::kStartMe), Occ(E::kRestartHsg)}, 2};
  return m;
}

double PathProbability(const EventTreePath& path, const std::array<double, kNumRecoveryEvents>& p) {
  double prob = 1.0;
  for (int i = 0; i < path.size; ++i) {
    const double pe = p[static_cast<int>(path.elements[i].event)];
    prob *= path.elements[i].occurs ? pe : 1.0 - pe;
  }
  return prob;
}

double TreeProbability(const EventTree& tree, const std::array<double, kNumRecoveryEvents>& p) {
  double sum = 0.0;
  for (int i = 0; i < tree.size; ++i) sum += PathProbability(tree.paths[i], p);
  return sum;
}

}  // namespace

std::string_view LognormalReadingName(LognormalReading r) {
  switch (r) {
    case LognormalReading::kScipyCode:
      return "scipy-code";
    case LognormalReading::kDurationMoments:
      return "duration-moments";
  }
  return "?";
}

std::string_view RecoveryEventName(RecoveryEvent e) {
  static constexpr std::array<std::string_view, kNumRecoveryEvents> kNames = {
      "start ME",    "restart ME",  "start DG1", "start DG2",
      "restart DG1", "restart DG2", "start HSG", "restart HSG"};
  const int i = static_cast<int>(e);
  return i >= 0 && i < kNumRecoveryEvents ? kNames[i] : "?";
}

const ModeScenarios& ScenariosOf(MsoMode mode) {
  static const ModeScenarios kPto = MakePto();
  static const ModeScenarios kMec = MakeMec();
  static const ModeScenarios kPti = MakePti();
  switch (mode) {
    case MsoMode::kPto:
      return kPto;
    case MsoMode::kMec:
      return kMec;
    case MsoMode::kPti:
      return kPti;
  }
  return kPto;
}

StatusOr<ShiftedLognormal> ShiftedLognormal::Create(const RecoveryEventParams& p,
                                                    LognormalReading reading) {
  if (!std::isfinite(p.mean_s) || !std::isfinite(p.std) || !std::isfinite(p.min_time_s) ||
      !(p.mean_s > 0.0) || !(p.std > 0.0) || !(p.min_time_s >= 0.0)) {
    return absl::InvalidArgumentError(absl::StrCat("recovery event: mean ", p.mean_s, ", std ",
                                                   p.std, ", min ", p.min_time_s,
                                                   " must be finite, mean/std > 0, min >= 0"));
  }
  switch (reading) {
    case LognormalReading::kScipyCode:
      return ShiftedLognormal(std::log(p.mean_s), std::sqrt(p.std), p.min_time_s);
    case LognormalReading::kDurationMoments: {
      const double excess = p.mean_s - p.min_time_s;
      if (!(excess > 0.0)) {
        return absl::InvalidArgumentError(
            absl::StrCat("recovery event: duration-moments reading needs mean ", p.mean_s,
                         " > min time ", p.min_time_s));
      }
      const double var_ln = std::log1p((p.std * p.std) / (excess * excess));
      return ShiftedLognormal(std::log(excess) - 0.5 * var_ln, std::sqrt(var_ln), p.min_time_s);
    }
  }
  return absl::InvalidArgumentError("unknown lognormal reading");
}

double ShiftedLognormal::Cdf(double t) const {
  if (!(t > shift_)) return 0.0;
  // Phi(z) = 0.5 erfc(-z / sqrt 2).
  return 0.5 * std::erfc(-(std::log(t - shift_) - mu_) * inv_sigma_sqrt2_);
}

Status DriftingGroundingParams::Validate() const {
  for (int i = 0; i < kNumComponents; ++i) {
    if (!(failure_rate_per_s[i] >= 0.0) || !std::isfinite(failure_rate_per_s[i])) {
      return absl::InvalidArgumentError(absl::StrCat("DriftingGroundingParams.failure_rate_per_s[",
                                                     i, "] = ", failure_rate_per_s[i],
                                                     " must be finite and >= 0"));
    }
  }
  for (int i = 0; i < kNumRecoveryEvents; ++i) {
    const double p = events[i].nominal_probability;
    if (!(p >= 0.0 && p <= 1.0)) {
      return absl::InvalidArgumentError(
          absl::StrCat("DriftingGroundingParams.events[", i, "] (",
                       std::string(RecoveryEventName(static_cast<RecoveryEvent>(i))),
                       "): nominal probability ", p, " not in [0, 1]"));
    }
    auto cdf = ShiftedLognormal::Create(events[i], reading);
    if (!cdf.ok()) {
      return absl::InvalidArgumentError(
          absl::StrCat("DriftingGroundingParams.events[", i, "] (",
                       std::string(RecoveryEventName(static_cast<RecoveryEvent>(i))),
                       "): ", cdf.status().message()));
    }
  }
  if (!(risk_interval_s > 0.0) || !std::isfinite(risk_interval_s)) {
    return absl::InvalidArgumentError(
        absl::StrCat("DriftingGroundingParams.risk_interval_s ", risk_interval_s, " must be > 0"));
  }
  if (!(table_step_s > 0.0) || !(table_max_ttg_s >= 0.0) || !std::isfinite(table_max_ttg_s) ||
      table_max_ttg_s / table_step_s > 1e7) {
    return absl::InvalidArgumentError(absl::StrCat(
        "DriftingGroundingParams: table_step_s ", table_step_s, " > 0 and table_max_ttg_s ",
        table_max_ttg_s, " >= 0 with at most 1e7 entries"));
  }
  return absl::OkStatus();
}

StatusOr<DriftingGroundingModel> DriftingGroundingModel::Create(
    const DriftingGroundingParams& params) {
  SEAPLAN_RETURN_IF_ERROR(params.Validate());
  DriftingGroundingModel m(params);
  for (int i = 0; i < kNumRecoveryEvents; ++i) {
    SEAPLAN_ASSIGN_OR_RETURN(m.cdf_[i], ShiftedLognormal::Create(params.events[i], params.reading));
  }
  for (int c = 0; c < kNumComponents; ++c) {
    // 1 - exp(-x) without cancellation for the tiny x = lambda dt.
    m.trigger_p_[c] = -std::expm1(-params.failure_rate_per_s[c] * params.risk_interval_s);
  }
  const int n = static_cast<int>(std::ceil(params.table_max_ttg_s / params.table_step_s)) + 1;
  m.table_.resize(n);
  m.inv_step_ = 1.0 / params.table_step_s;
  for (int k = 0; k < n; ++k) {
    const double t = k * params.table_step_s;
    for (MsoMode mode : ship::kAllMsoModes) {
      m.table_[k][static_cast<int>(mode)] = m.GroundingProbabilityExact(mode, t);
    }
  }
  return m;
}

double DriftingGroundingModel::EventProbability(RecoveryEvent e, double t) const {
  const int i = static_cast<int>(e);
  return params_.events[i].nominal_probability * cdf_[i].Cdf(t);
}

double DriftingGroundingModel::RestoreProbability(const EventTree& tree, double t) const {
  std::array<double, kNumRecoveryEvents> p;
  for (int i = 0; i < kNumRecoveryEvents; ++i) p[i] = EventProbability(static_cast<E>(i), t);
  return TreeProbability(tree, p);
}

double DriftingGroundingModel::ScenarioProbability(const LoppScenario& s) const {
  double p = 1.0;
  for (int i = 0; i < s.num_failures; ++i) p *= trigger_p_[static_cast<int>(s.failures[i])];
  return p;
}

double DriftingGroundingModel::Exact(MsoMode mode,
                                     const std::array<double, kNumRecoveryEvents>& event_p) const {
  const ModeScenarios& ms = ScenariosOf(mode);
  // 1 - prod(1 - a_s) through log1p/expm1: the a_s are ~1e-6, and the naive
  // form would lose about half of the double's digits to cancellation.
  double log_no_grounding = 0.0;
  for (int i = 0; i < ms.size; ++i) {
    const LoppScenario& s = ms.scenarios[i];
    log_no_grounding +=
        std::log1p(-ScenarioProbability(s) * (1.0 - TreeProbability(s.recovery, event_p)));
  }
  return -std::expm1(log_no_grounding);
}

double DriftingGroundingModel::GroundingProbabilityExact(MsoMode mode, double ttg_s) const {
  if (!(ttg_s > 0.0)) ttg_s = 0.0;
  std::array<double, kNumRecoveryEvents> p;
  for (int i = 0; i < kNumRecoveryEvents; ++i) p[i] = EventProbability(static_cast<E>(i), ttg_s);
  return Exact(mode, p);
}

double DriftingGroundingModel::GroundingProbability(MsoMode mode, double ttg_s) const {
  if (!(ttg_s > 0.0)) ttg_s = 0.0;  // negative or NaN: no time to recover
  const int m = static_cast<int>(mode);
  const double x = ttg_s * inv_step_;
  const double last = static_cast<double>(table_.size() - 1);
  if (x >= last) return x == last ? table_.back()[m] : GroundingProbabilityExact(mode, ttg_s);
  const size_t k = static_cast<size_t>(x);
  const double f = x - static_cast<double>(k);
  return table_[k][m] + f * (table_[k + 1][m] - table_[k][m]);
}

ModeProbabilities DriftingGroundingModel::GroundingProbabilities(double ttg_s) const {
  ModeProbabilities out;
  for (MsoMode mode : ship::kAllMsoModes)
    out.p[static_cast<int>(mode)] = GroundingProbability(mode, ttg_s);
  return out;
}

}  // namespace seaplan::risk
