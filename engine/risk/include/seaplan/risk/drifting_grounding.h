// Drifting-grounding probability per MSO mode (paper 002 eq. 4–10; MISSION.md
// §3.5 Tables 2–4; SHIP_MODEL.md §7; DGRM/AMM risk_model.py and events.py).
//
// Given the time to grounding t (s) after a loss of propulsion power (LOPP):
//
//  * Triggering events: component c fails in the risk interval dt with
//    P_c = 1 - exp(-lambda_c dt) (Table 3: ME 3e-9, DG1 6e-9, DG2 6e-9,
//    HSG 2e-9 per second; dt = risk_interval_s, AMM 600 s). A LOPP scenario is
//    an AND of failures: P(S) = prod P_c.
//  * Recovery events: e succeeds in time with P_e(t) = p_nom,e * F_e(t),
//    F_e the CDF of its lognormal start-up duration with a minimum time
//    (Table 4; see LognormalReading for how mean/std/min are read).
//  * Event trees (success paths, SHIP_MODEL.md §7), per scenario:
//      PTO, "ME stops":  R_ME | !R_ME & S_DG1 & S_HSG | !R_ME & !S_DG1 & S_DG2 & S_HSG
//      MEC, "ME stops":  R_ME | !R_ME & S_HSG
//      PTI, "DG1 & DG2 stop": S_ME | !S_ME & R_DG1 | !S_ME & !R_DG1 & R_DG2
//           (the public code repeats R_DG1 in the last path; fixed here)
//      PTI, "HSG stops": S_ME | !S_ME & R_HSG
//    P(restore) = sum over paths of prod(p if occurs else 1 - p).
//    (R = restart, S = start.)
//  * Mode: P(G) = 1 - prod_s (1 - P(S_s) (1 - P_restore,s(t))). The public
//    code computes 1 - (1 - sum_s ...), equal to first order (the products of
//    two ~1e-6 terms it drops are ~1e-12).
//
// Speed: the public Python builds 8 scipy lognormal objects per evaluation
// (68 % of its 9.4 ms). Here each event's CDF is 0.5 erfc(-(ln(t - shift) -
// mu)/(s sqrt 2)) with mu, 1/(s sqrt 2) precomputed, each event is evaluated
// once per call (not once per path element), and P(G | mode) is tabulated on
// a 0.25 s grid up to table_max_ttg_s (7201 x 3 doubles, 173 kB): the TTG
// simulation returns multiples of dt, so with dt a multiple of 0.25 s the
// lookup is exact; between grid points linear interpolation is within 3.5e-10
// absolute (0.02 % of P(LOPP), measured in drifting_grounding_test).
//
// Thread-safety: DriftingGroundingModel is immutable after Create.
#pragma once

#include <array>
#include <string_view>
#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/ship/machinery.h"

namespace seaplan::risk {

using ship::MsoMode;

// How Table 4's (mean, std, min) define the start-up duration D.
enum class LognormalReading {
  // The public code (DGRM/AMM events.py): scipy lognorm(s = sqrt(std),
  // scale = mean, loc = min), i.e. ln(D - min) ~ N(ln(mean), std) — `std` is
  // used as the VARIANCE of ln(D - min) and `mean` is the MEDIAN of D - min.
  // Default: it reproduces the published results.
  kScipyCode,
  // Literal reading: D = min + X with X lognormal and E[D] = mean,
  // SD[D] = std in seconds. Needs mean > min. sigma^2 = ln(1 + std^2/(mean -
  // min)^2), mu = ln(mean - min) - sigma^2/2. With Table 4's small stds this
  // makes start-up times nearly deterministic.
  kDurationMoments,
};
std::string_view LognormalReadingName(LognormalReading r);

struct RecoveryEventParams {
  double nominal_probability = 1.0;  // p_nom
  double mean_s = 0.0;
  double std = 0.0;         // see LognormalReading for its unit/meaning
  double min_time_s = 0.0;  // shift / minimum start-up time
};

// Precomputed lognormal-with-shift CDF: F(t) = 0 for t <= shift, else
// Phi((ln(t - shift) - mu) / sigma).
class ShiftedLognormal {
 public:
  static StatusOr<ShiftedLognormal> Create(const RecoveryEventParams& p, LognormalReading reading);
  // Direct construction from ln-space parameters (sigma > 0; unchecked).
  ShiftedLognormal(double mu, double sigma, double shift)
      : mu_(mu),
        sigma_(sigma),
        shift_(shift),
        inv_sigma_sqrt2_(1.0 / (sigma * 1.4142135623730951)) {}
  double Cdf(double t_s) const;
  double mu() const { return mu_; }
  double sigma() const { return sigma_; }
  double shift_s() const { return shift_; }

 private:
  double mu_, sigma_, shift_, inv_sigma_sqrt2_;
};

enum class Component { kMainEngine = 0, kDieselGenerator1, kDieselGenerator2, kHsg, kCount };

enum class RecoveryEvent {
  kStartMe = 0,
  kRestartMe,
  kStartDg1,
  kStartDg2,
  kRestartDg1,
  kRestartDg2,
  kStartHsg,
  kRestartHsg,
  kCount
};
inline constexpr int kNumRecoveryEvents = static_cast<int>(RecoveryEvent::kCount);
inline constexpr int kNumComponents = static_cast<int>(Component::kCount);
std::string_view RecoveryEventName(RecoveryEvent e);

// Event-tree structure (fixed capacity, no heap).
struct PathElement {
  RecoveryEvent event;
  bool occurs;
};
struct EventTreePath {
  std::array<PathElement, 4> elements{};
  int size = 0;
};
struct EventTree {
  std::array<EventTreePath, 3> paths{};
  int size = 0;
};
struct LoppScenario {
  std::array<Component, 2> failures{};  // AND of these
  int num_failures = 0;
  EventTree recovery;
};
struct ModeScenarios {
  std::array<LoppScenario, 2> scenarios{};
  int size = 0;
};
// The trees of SHIP_MODEL.md §7 (see header comment).
const ModeScenarios& ScenariosOf(MsoMode mode);

struct DriftingGroundingParams {
  // Table 3 failure rates [1/s], indexed by Component.
  std::array<double, kNumComponents> failure_rate_per_s = {3e-9, 6e-9, 6e-9, 2e-9};
  // Table 4, indexed by RecoveryEvent. ME std is the public code's 1.2; the
  // paper's Table 4 says 1.4.
  std::array<RecoveryEventParams, kNumRecoveryEvents> events = {{
      {1.0, 50, 1.2, 20},  // start ME
      {0.4, 50, 1.2, 20},  // restart ME
      {1.0, 35, 1.0, 14},  // start DG1
      {1.0, 35, 1.0, 14},  // start DG2
      {0.5, 35, 1.0, 14},  // restart DG1
      {0.5, 35, 1.0, 14},  // restart DG2
      {1.0, 12, 1.0, 3},   // start HSG
      {0.8, 12, 1.0, 3},   // restart HSG
  }};
  LognormalReading reading = LognormalReading::kScipyCode;
  // Exposure interval of the triggering events (AMM time_interval 600 s).
  double risk_interval_s = 600.0;
  // P(G | mode) table: grid step and extent. Times above the extent are
  // computed exactly.
  double table_step_s = 0.25;
  double table_max_ttg_s = 1800.0;
  Status Validate() const;
};

struct ModeProbabilities {
  std::array<double, 3> p{};  // indexed by MsoMode
  double operator[](MsoMode m) const { return p[static_cast<int>(m)]; }
};

class DriftingGroundingModel {
 public:
  static StatusOr<DriftingGroundingModel> Create(const DriftingGroundingParams& params = {});

  // P(grounding in the risk interval | mode, TTG), table lookup. ttg_s < 0 or
  // NaN is treated as 0 (no time to recover: P = P(LOPP), the worst case);
  // +inf gives the fully recovered limit.
  double GroundingProbability(MsoMode mode, double ttg_s) const;
  ModeProbabilities GroundingProbabilities(double ttg_s) const;
  // Same, computed directly (no table).
  double GroundingProbabilityExact(MsoMode mode, double ttg_s) const;

  // Building blocks (exact).
  double EventProbability(RecoveryEvent e, double ttg_s) const;  // p_nom * F(t)
  double RestoreProbability(const EventTree& tree, double ttg_s) const;
  double ScenarioProbability(const LoppScenario& s) const;  // P(LOPP scenario)

  const DriftingGroundingParams& params() const { return params_; }

 private:
  explicit DriftingGroundingModel(const DriftingGroundingParams& p) : params_(p) {}
  double Exact(MsoMode mode, const std::array<double, kNumRecoveryEvents>& event_p) const;
  DriftingGroundingParams params_;
  std::array<ShiftedLognormal, kNumRecoveryEvents> cdf_{
      {{0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}}};
  std::array<double, kNumComponents> trigger_p_{};
  std::vector<std::array<double, 3>> table_;  // [k] = P(G | mode) at t = k * step
  double inv_step_ = 1.0;
};

}  // namespace seaplan::risk
