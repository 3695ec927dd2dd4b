#include "fuel.h"

#include <algorithm>

namespace seaplan::sim {

void FuelTank::Take(double f) {
  fraction_ -= f;
  if (fraction_ <= 0) {
    ran_dry_ = ran_dry_ || fraction_ < -1e-9;
    fraction_ = std::max(0.0, fraction_);
  }
}

void FuelTank::OnTaskStarted(mission::TaskKind kind) {
  using mission::TaskKind;
  if (options_.kind != FuelModelKind::kPercentage) return;
  switch (kind) {
    case TaskKind::kLoad:
    case TaskKind::kUnload:
      Take(options_.cargo_fraction);
      break;
    case TaskKind::kRepair:
      Take(options_.repair_fraction);
      break;
    default:
      break;
  }
}

void FuelTank::OnTaskCompleted(mission::TaskKind kind) {
  if (kind == mission::TaskKind::kRefuel) {
    fraction_ = 1.0;
    return;
  }
  if (options_.kind == FuelModelKind::kPercentage && kind == mission::TaskKind::kMove) {
    Take(options_.move_fraction);
  }
}

void FuelTank::Burn(double kg) {
  if (options_.kind != FuelModelKind::kMachinery || options_.tank_capacity_kg <= 0) return;
  Take(kg / options_.tank_capacity_kg);
}

}  // namespace seaplan::sim
