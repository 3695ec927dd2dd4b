// Drifting-grounding risk as the route optimiser needs it (MISSION.md 3.5,
// SHIP_MODEL.md 7): P(G) per MSO mode from the time to grounding (TTG).
//
// The optimiser sees the machinery only through `ModeGroundingModel`
// (TTG -> P(G) for every mode) so that engine/risk's model can be plugged in
// when it lands; `EventTreeGroundingModel` is the paper's Table 2-4 model
// (TODO(#5): replace by an adapter over engine/risk once it is public).
//
// Reading of Table 4 (the paper is silent): like the public code, the
// recovery time is lognormal with log-scale sigma = sqrt(std), median
// scale = mean, shifted by the minimum time (scipy
// lognorm(s=sqrt(std), scale=mean, loc=min)); P(event) = p_nom * CDF(TTG).
// The PTI "both DGs stop" tree uses Restart DG2 where the public code
// repeats DG1. P(G) of a mode = 1 - prod_s (1 - P(S) (1 - P(recovery | S))).
#pragma once

#include <array>

#include "seaplan/common/status.h"

namespace seaplan::route {

enum class MsoMode : int { kPto = 0, kMec = 1, kPti = 2 };
inline constexpr int kModeCount = 3;
const char* MsoModeName(MsoMode mode);  // "PTO", "MEC", "PTI"

using ModeArray = std::array<double, kModeCount>;

class ModeGroundingModel {
 public:
  virtual ~ModeGroundingModel() = default;
  // P(G) of each mode when grounding follows `ttg_s` seconds after a loss of
  // propulsion. Must be const and thread-safe.
  virtual ModeArray Probabilities(double ttg_s) const = 0;
};

struct RecoveryEvent {
  double nominal_probability = 1.0;
  double mean_s = 50.0;   // lognormal scale (median above the shift)
  double std = 1.0;       // the paper's "std"; log-scale sigma = sqrt(std)
  double min_s = 20.0;    // shift
  double Probability(double available_s) const;
};

struct EventTreeParameters {
  // Table 3, failures per second.
  double main_engine_failure_rate = 3e-9;
  double genset1_failure_rate = 6e-9;
  double genset2_failure_rate = 6e-9;
  double hsg_failure_rate = 2e-9;
  // Exposure interval for the triggering events, seconds (public code: 600).
  double risk_interval_s = 600.0;
  // Table 4.
  RecoveryEvent start_main_engine{1.0, 50.0, 1.4, 20.0};
  RecoveryEvent restart_main_engine{0.4, 50.0, 1.4, 20.0};
  RecoveryEvent start_genset1{1.0, 35.0, 1.0, 14.0};
  RecoveryEvent start_genset2{1.0, 35.0, 1.0, 14.0};
  RecoveryEvent restart_genset1{0.5, 35.0, 1.0, 14.0};
  RecoveryEvent restart_genset2{0.5, 35.0, 1.0, 14.0};
  RecoveryEvent start_hsg{1.0, 12.0, 1.0, 3.0};
  RecoveryEvent restart_hsg{0.8, 12.0, 1.0, 3.0};

  absl::Status Validate() const;
};

class EventTreeGroundingModel final : public ModeGroundingModel {
 public:
  explicit EventTreeGroundingModel(const EventTreeParameters& p = {}) : p_(p) {}
  ModeArray Probabilities(double ttg_s) const override;
  const EventTreeParameters& parameters() const { return p_; }

 private:
  EventTreeParameters p_;
};

}  // namespace seaplan::route
