#include "seaplan/route/grounding_risk.h"

namespace seaplan::route {

ModeArray DriftingGroundingAdapter::Probabilities(double ttg_s) const {
  ModeArray out;
  for (int m = 0; m < kModeCount; ++m) {
    out[m] = model_->GroundingProbabilityExact(static_cast<MsoMode>(m), ttg_s);
  }
  return out;
}

}  // namespace seaplan::route
