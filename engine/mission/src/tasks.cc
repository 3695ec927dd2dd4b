#include "seaplan/mission/tasks.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"

namespace seaplan::mission {

std::vector<Task> ParseTasks(const RefinedPlan& refined, const LocationTable& locations,
                             const MoveRecognition& recognition, int version) {
  std::vector<Task> tasks;
  tasks.reserve(refined.plan.steps.size());
  for (size_t i = 0; i < refined.plan.steps.size(); ++i) {
    const validate::PlanStep& step = refined.plan.steps[i];
    Task t;
    t.id = absl::StrCat("v", version, "-t", i + 1);
    t.start_s = step.start_s;
    t.duration_s = step.duration_s;
    t.action = step;
    const std::optional<Route>& route =
        i < refined.routes.size() ? refined.routes[i] : std::nullopt;
    if (std::optional<MoveLeg> leg = RecognizeMove(step, locations, recognition); leg && route) {
      t.kind = TaskKind::kMove;
      t.from_location = leg->from;
      t.to_location = leg->to;
      t.route = route;
    } else {
      t.kind = TaskKindOfAction(step.name);
      if (t.kind == TaskKind::kMove) t.kind = TaskKind::kOther;  // a move we could not route
      for (const std::string& a : step.args) {
        if (locations.contains(a)) {
          t.to_location = a;
          break;
        }
      }
    }
    tasks.push_back(std::move(t));
  }
  return tasks;
}

double CrossTrackDistance(const Route& route, EastNorth p) {
  const auto& w = route.waypoints;
  if (w.empty()) return std::numeric_limits<double>::infinity();
  if (w.size() == 1) return Distance(w[0].position, p);
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i + 1 < w.size(); ++i) {
    EastNorth a = w[i].position, b = w[i + 1].position;
    double dx = b.east_m - a.east_m, dy = b.north_m - a.north_m;
    double len2 = dx * dx + dy * dy;
    double t = len2 > 0 ? ((p.east_m - a.east_m) * dx + (p.north_m - a.north_m) * dy) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    best = std::min(best, Distance(p, {a.east_m + t * dx, a.north_m + t * dy}));
  }
  return best;
}

}  // namespace seaplan::mission
