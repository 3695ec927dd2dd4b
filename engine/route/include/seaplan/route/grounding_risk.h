// Drifting-grounding risk as the route optimiser sees it (MISSION.md 3.5,
// SHIP_MODEL.md 7): P(G) per MSO mode as a function of the time to
// grounding (TTG) after a loss of propulsion.
//
// The optimiser depends only on the narrow `ModeGroundingModel` interface
// (tests inject synthetic models); `DriftingGroundingAdapter` puts
// engine/risk's event-tree model (Tables 2-4, public-code lognormal reading)
// behind it.
#pragma once

#include <array>
#include <string_view>

#include "seaplan/risk/drifting_grounding.h"
#include "seaplan/ship/machinery.h"

namespace seaplan::route {

using ship::MsoMode;
inline constexpr int kModeCount = 3;
using ModeArray = std::array<double, kModeCount>;  // indexed by MsoMode
inline std::string_view MsoModeName(MsoMode mode) {
  return ship::MsoModeName(mode);
}

class ModeGroundingModel {
 public:
  virtual ~ModeGroundingModel() = default;
  // P(G) of each mode when grounding follows `ttg_s` seconds after a loss of
  // propulsion. Must be const and thread-safe.
  virtual ModeArray Probabilities(double ttg_s) const = 0;
};

// engine/risk's DriftingGroundingModel (not owned; must outlive the adapter).
// Evaluates the event trees exactly on every call, not through risk's 0.25 s
// table: kFast tabulates per TTG step itself, and the kExact baseline must
// not use a table.
class DriftingGroundingAdapter final : public ModeGroundingModel {
 public:
  explicit DriftingGroundingAdapter(const risk::DriftingGroundingModel& model) : model_(&model) {}
  ModeArray Probabilities(double ttg_s) const override;

 private:
  const risk::DriftingGroundingModel* model_;
};

}  // namespace seaplan::route
