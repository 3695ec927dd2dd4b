// How much slower than a normal build this build runs: the multiplier of the
// wall-clock budgets the code and its tests set for themselves (never of the
// time limits a user gives). SEAPLAN_WALL_CLOCK_SCALE is a CMake setting,
// above 1 in the sanitizer builds (CMakeLists.txt), where a fixed budget
// buys less work and a fixed test timeout expires before the same work ends.
#pragma once

#include <chrono>
#include <cstdint>

#ifndef SEAPLAN_WALL_CLOCK_SCALE
#define SEAPLAN_WALL_CLOCK_SCALE 1
#endif

namespace seaplan {

inline constexpr double kWallClockScale = SEAPLAN_WALL_CLOCK_SCALE;

// A budget or timeout the code sets for itself, stretched by kWallClockScale.
constexpr std::chrono::milliseconds ScaledWallClock(std::chrono::milliseconds budget) {
  return std::chrono::milliseconds(
      static_cast<std::int64_t>(static_cast<double>(budget.count()) * kWallClockScale));
}

}  // namespace seaplan
