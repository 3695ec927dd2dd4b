// Test helpers shared by the mission tests: the fjord test domain, case A
// problem and plan, and positions that make straight-line times easy to check.
#pragma once

#include <filesystem>
#include <string>

#include "seaplan/mission/types.h"
#include "seaplan/testing/shared_data.h"
#include "seaplan/validate/plan.h"

namespace seaplan::mission::testing {

inline std::string ReadTestData(const std::string& name) {
  return seaplan::testing::ReadFile(std::filesystem::path(SEAPLAN_MISSION_TESTDATA) / name);
}

// A-B 1000 m, B-C 1500 m, C-D 500 m, D-E 2000 m.
inline LocationTable CaseALocations() {
  return {{"port-a", {0, 0}},
          {"port-b", {1000, 0}},
          {"port-c", {1000, 1500}},
          {"port-d", {1000, 2000}},
          {"port-e", {3000, 2000}}};
}

inline validate::Plan CaseAPlan() {
  auto p = validate::ParsePlan(ReadTestData("case-a.plan"));
  return p.ok() ? *p : validate::Plan{};
}

}  // namespace seaplan::mission::testing
