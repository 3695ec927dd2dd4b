// The fjord case A (examples/fjord) as a CreateMission request: five ports
// about 1 km apart along a line of latitude, legs sailed at 5 m/s. Its
// plans and replans take well under a second; for tests that need a real
// mission on a real server. Header-only (the callers link the protos).
#pragma once

#include <string>

#include "seaplan/testing/shared_data.h"
#include "seaplan/v1/mission.pb.h"

namespace seaplan::testing {

inline v1::CreateMissionRequest CaseAMissionRequest(const std::string& name) {
  const auto example = [](const char* file) {
    return ReadFile(SourceDir() / "examples" / "fjord" / file);
  };
  v1::CreateMissionRequest req;
  v1::MissionSpec* spec = req.mutable_spec();
  spec->set_name(name);
  spec->set_domain(example("domain.pddl"));
  spec->set_problem(example("case-a.pddl"));
  spec->set_vessel_id("ship0");
  spec->mutable_ship()->set_service_speed_mps(5.0);
  const char* ports[] = {"port-a", "port-b", "port-c", "port-d", "port-e"};
  for (int i = 0; i < 5; ++i) {
    v1::NamedLocation* l = spec->add_locations();
    l->set_name(ports[i]);
    l->mutable_position()->set_latitude_deg(63.45);
    l->mutable_position()->set_longitude_deg(10.30 + 0.02 * i);
  }
  *spec->mutable_initial_state()->mutable_position() = spec->locations(0).position();
  spec->mutable_initial_state()->set_fuel_fraction(0.9);
  spec->mutable_planner_options()->mutable_time_limit()->set_seconds(20);
  return req;
}

}  // namespace seaplan::testing
