// Fuel in the simulation client.
//
//  * kPercentage: the paper's executor model (paper 000 case C): a move costs
//    15 % of the tank, a load or unload 10 %, a repair 10 %, a refuel fills
//    the tank to 100 %, each charged when the task completes. Other tasks
//    cost nothing.
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
  double cargo_fraction = 0.10;   // load / unload
  double repair_fraction = 0.10;
  double tank_capacity_kg = 2000.0;  // kMachinery
};

class FuelTank {
 public:
  FuelTank(const FuelOptions& options, double initial_fraction)
      : options_(options), fraction_(initial_fraction) {}

  // Charges a completed task (percentage model; refuel fills in both models).
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
