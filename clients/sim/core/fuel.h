// Fuel in the simulation client.
//
//  * kPercentage: the paper's executor model (paper 000 case C): a move costs
//    15 % of the tank, a load or unload 10 %, a repair 10 %, a refuel fills
//    the tank to 100 % when it completes. Other tasks cost nothing.
//    A port operation is charged when it starts, a move when it completes.
//    Why: a port operation may overlap a refuel at the same port (the
//    numeric domain plans "unload while refuelling"); the planner takes its
//    cost at its start, before the refill, so charging it at completion,
//    after the refill, drained 10 % the plan never counted (case C numeric
//    ended at -5 %). A move never overlaps a refuel of the same
//    ship (both need the ship), so its order against the refill is the same
//    either way; at completion, a move a replan abandons (the new plan starts
//    where the ship is) is not charged twice.
//  * kMachinery: the fuel the machinery model burns (seaplan::ship fuel
//    rates of the MSO mode at the commanded load) against a tank capacity;
//    port operations burn the hotel load only (ignored here: small) and a
//    refuel fills the tank.
// The fraction never goes below 0 (a dry tank is recorded, not hidden).
#pragma once

#include <string_view>

#include "seaplan/mission/types.h"

namespace seaplan::sim {

enum class FuelModelKind { kPercentage, kMachinery };

struct FuelOptions {
  FuelModelKind kind = FuelModelKind::kPercentage;
  double move_fraction = 0.15;
  double cargo_fraction = 0.10;  // load / unload
  double repair_fraction = 0.10;
  double tank_capacity_kg = 2000.0;  // kMachinery
};

class FuelTank {
 public:
  FuelTank(const FuelOptions& options, double initial_fraction)
      : options_(options), fraction_(initial_fraction) {}

  // Charges a port operation that starts (percentage model).
  void OnTaskStarted(mission::TaskKind kind);
  // Charges a completed move (percentage model); a refuel fills the tank in
  // both models.
  void OnTaskCompleted(mission::TaskKind kind);
  // Burns fuel of the machinery model (kMachinery only; ignored otherwise).
  void Burn(double kg);

  double fraction() const { return fraction_; }
  bool ran_dry() const { return ran_dry_; }
  const FuelOptions& options() const { return options_; }

 private:
  void Take(double fraction);
  FuelOptions options_;
  double fraction_;
  bool ran_dry_ = false;
};

}  // namespace seaplan::sim
