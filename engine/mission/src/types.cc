#include "seaplan/mission/types.h"

#include <cmath>

namespace seaplan::mission {

std::string_view MsoModeName(MsoMode mode) {
  switch (mode) {
    case MsoMode::kPto:
      return "PTO";
    case MsoMode::kMec:
      return "MEC";
    case MsoMode::kPti:
      return "PTI";
    case MsoMode::kUnspecified:
      break;
  }
  return "-";
}

std::vector<ModeScheduleEntry> ModeSchedule(const Route& route) {
  std::vector<ModeScheduleEntry> out;
  const auto& w = route.waypoints;
  for (size_t i = 0; i + 1 < w.size(); ++i) {
    if (!out.empty() && out.back().mode == w[i].mode) {
      out.back().to_waypoint = static_cast<int>(i + 1);
      out.back().duration_s = w[i + 1].eta_s - out.back().start_s;
      continue;
    }
    out.push_back({static_cast<int>(i), static_cast<int>(i + 1), w[i].mode, w[i].eta_s,
                   w[i + 1].eta_s - w[i].eta_s});
  }
  return out;
}

std::string_view TaskKindName(TaskKind kind) {
  switch (kind) {
    case TaskKind::kMove:
      return "move";
    case TaskKind::kLoad:
      return "load";
    case TaskKind::kUnload:
      return "unload";
    case TaskKind::kRepair:
      return "repair";
    case TaskKind::kRefuel:
      return "refuel";
    case TaskKind::kOther:
      break;
  }
  return "other";
}

TaskKind TaskKindOfAction(std::string_view name) {
  auto has = [&](std::string_view s) { return name.find(s) != std::string_view::npos; };
  if (has("move")) return TaskKind::kMove;
  if (has("unload")) return TaskKind::kUnload;
  if (has("load")) return TaskKind::kLoad;
  if (has("repair")) return TaskKind::kRepair;
  if (has("fuel")) return TaskKind::kRefuel;
  return TaskKind::kOther;
}

}  // namespace seaplan::mission
