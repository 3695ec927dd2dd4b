// Turns a ship can sail: the sharp corners of a route replaced by polygons
// round a circle of the ship's turning radius (fillets), placed clear of the
// obstacles.
//
// Why: a Level-1 path turns at the (dilated) hull vertices of the obstacles,
// often by 70-90 deg. A hull that turns on a circle of radius R cannot sail
// such a corner: started early, its arc cuts R (sec(theta / 2) - 1) towards
// the obstacle it turns round; started late, it overshoots outwards and
// swings back across the next leg. A route whose corners are already arcs
// of radius R (a polygon circumscribed about the circle, at most
// max_step_rad of course change per vertex) is sailed as drawn.
//
// Per corner (course change theta >= min_turn_rad) the fillet needs
// R tan(theta / 2) of each adjacent leg. Where a leg is too short for it
// (a path rounding an obstacle through several vertices tens of metres
// apart), the vertices that turn the same way are taken as one corner at
// the intersection of the lines of the first and the last leg. The corner
// is then moved outwards along its bisector, first by R (sec(theta / 2) - 1)
// so that the arc passes where the corner was (the clearance the path had
// there), then by other amounts; a candidate is kept when none of its new
// segments touches an obstacle (exact test on the field) and, preferably,
// its arc keeps `clearance_m` from them (sampled signed distance): the
// first such candidate, else the one with the largest clearance. A corner
// with no clear candidate (water too narrow for the circle, or legs too
// short) stays as it was and is reported as unsailable.
//
// Frame: local metric frame (EastNorth). Thread-safety: a pure function.
#pragma once

#include <vector>

#include "seaplan/common/east_north.h"
#include "seaplan/common/status.h"
#include "seaplan/route/obstacle_field.h"

namespace seaplan::route {

struct TurnFilletOptions {
  // Radius of the fillet circle, metres.
  double radius_m = 300.0;
  // Course change per vertex of the fillet polygon.
  double max_step_rad = 15.0 * M_PI / 180.0;
  // Corners turning less are left as they are (the path follower's own
  // wheel-over sails them; the arc cuts R (sec(theta/2) - 1) ~ 2.6 m at
  // 15 deg and 300 m).
  double min_turn_rad = 15.0 * M_PI / 180.0;
  // Arcs that keep this much from the obstacles are preferred (the Level-1
  // path keeps its margin from the dilated hulls; sampling step 10 m).
  double clearance_m = 50.0;
  // Vertices merged into one corner turn together by less than this.
  double max_group_turn_rad = 150.0 * M_PI / 180.0;
  // A corner no candidate on radius_m clears is tried on smaller circles
  // down to this radius (0: radius_m only), e.g. the hull's own circle at
  // full rudder when radius_m keeps a margin over it: a tighter turn the
  // hull can still make beats a corner it cannot. Such corners count in
  // FilletRoute::tightened.
  double min_radius_m = 0.0;

  absl::Status Validate() const;
};

struct FilletPoint {
  EastNorth position;
  int source = -1;  // index of the input point it is; -1: a vertex of a fillet
};

struct UnsailableTurn {
  EastNorth corner;         // the route's vertex (the first of a merged group)
  double turn_rad = 0.0;    // course change of the corner (the group's sum)
  int first = 0, last = 0;  // input indices of the corner's vertices
  // Why: no fillet fitted the legs either side (on any circle tried), or
  // those that did all touched an obstacle (the water too narrow).
  bool legs_too_short = false;
};

struct FilletRoute {
  std::vector<FilletPoint> points;  // start .. goal
  int filleted = 0;                 // corners replaced by a fillet
  int merged_vertices = 0;          // input vertices absorbed into a merged corner's fillet
  int tightened = 0;                // filleted on a circle smaller than radius_m
  std::vector<UnsailableTurn> unsailable;
};

// `route`: start .. goal, >= 2 points. Start and goal are kept; a corner's
// vertices are replaced by its fillet. Errors: InvalidArgument for bad
// options or a route with < 2 points or non-finite coordinates.
StatusOr<FilletRoute> FilletTurns(const ObstacleField& field, const std::vector<EastNorth>& route,
                                  const TurnFilletOptions& options);

// Course change at route[k] (signed, counter-clockwise positive), radians.
double TurnAngle(EastNorth a, EastNorth b, EastNorth c);

}  // namespace seaplan::route
