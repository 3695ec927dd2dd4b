// Traffic vessels on scripted tracks (the paper's ferry, high-speed craft and
// leisure yacht on AIS-derived tracks). A track is a list of timed points;
// the vessel moves linearly between them, holds its first point before the
// first time and continues with its last velocity after the last (so it
// never vanishes in the middle of an encounter). Traffic does not react to
// the own ship: it is the stand-on party by construction, which is what
// makes the own ship's COLREG handling testable.
#pragma once

#include <string>
#include <vector>

#include "seaplan/colav/geometry.h"

namespace seaplan::sim {

using colav::Kinematics;

struct TrackPoint {
  double time_s = 0.0;
  EastNorth position;
};

struct TrafficVessel {
  int id = 0;
  std::string name;  // "ferry", "hsc", "yacht" ...
  std::string kind;
  std::vector<TrackPoint> track;  // sorted by time, >= 1 point

  Kinematics At(double time_s) const;
};

}  // namespace seaplan::sim
