// Seeded generator of fjord missions scaled up from examples/fjord: several
// ships, ports along a fjord, containers to deliver, repair and refuelling
// teams, written as a PDDL problem for the domain `fjord` (examples/fjord/
// domain.pddl) or `fjord-fuel` (domain-fuel.pddl).
//
// The same spec always gives the same text (the generator draws from its own
// splitmix64 stream, not from the standard library's distributions, whose
// output differs between implementations). Every generated problem is
// solvable: the route graph is connected, each ship has at most one
// `(loaded ?c ?v)` goal, and in `fjord-fuel` every port has a route to a
// refuelling port for `move-fueling-ship`. The ships start at different ports
// and have their own goals, so a good plan sails them at the same time.
#pragma once

#include <cstdint>
#include <string>

#include "absl/status/statusor.h"

namespace seaplan::bench {

enum class FjordDomain {
  kFjord,      // domain.pddl: ships start with (no_fuel), some must refuel
  kFjordFuel,  // domain-fuel.pddl: some ships start without fuel and must reach a charger first
};

struct FjordMissionSpec {
  FjordDomain domain = FjordDomain::kFjord;
  int ships = 3;        // 1..26
  int ports = 12;       // 2..99, at least `ships`
  int containers = 12;  // 1..99
  std::uint64_t seed = 1;
  // Routes (both ways) from each port to this many nearest ports, besides the
  // route to the next port along the fjord that keeps the graph connected.
  int nearest_routes = 3;

  absl::Status Validate() const;
};

// "fjord-s3-p12-c12-seed1" (or "fjord-fuel-..."): also the problem's name.
std::string FjordMissionName(const FjordMissionSpec& spec);

// The domain's name as its file declares it: "fjord" or "fjord-fuel".
const char* FjordDomainName(FjordDomain domain);

// The PDDL problem text, or InvalidArgument when the spec is out of range.
absl::StatusOr<std::string> GenerateFjordMission(const FjordMissionSpec& spec);

}  // namespace seaplan::bench
