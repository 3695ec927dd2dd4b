#include "encounter_suite.h"

#include <cmath>

#include "absl/strings/str_format.h"

namespace seaplan::colav::suite {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kSpeed = 9.0;           // own ship, m/s
constexpr double kLegM = 9000.0;         // open-water leg, north from the origin
constexpr double kChannelHalfM = 400.0;  // channel: banks at x = -400 and x = +400
constexpr double kLaneM = 80.0;          // own ship's track: 80 m east of the axis

// A vessel on `course_deg` at `speed` that would meet the own ship sailing
// its track (north along x = track_x at kSpeed) at time t_meet, `miss_m`
// east of it (0 = collision course).
EncounterVessel Meeting(int id, std::string name, double course_deg, double speed, double t_meet,
                        double miss_m = 0.0, double track_x = 0.0) {
  const EastNorth meet{track_x + miss_m, kSpeed * t_meet};
  const EastNorth v = VelocityOf(course_deg * kDeg, speed);
  return {id, std::move(name), meet - v * t_meet, v};
}

// A vessel ahead (or astern, ahead_m < 0) on the own ship's course.
EncounterVessel SameCourse(int id, std::string name, double speed, double ahead_m,
                           double offset_m = 0.0, double track_x = 0.0) {
  return {id, std::move(name), {track_x + offset_m, ahead_m}, VelocityOf(0.0, speed)};
}

Situation Open(std::string name, std::string description, std::vector<EncounterVessel> traffic,
               std::vector<Expectation> expected, const CollisionAvoidanceOptions& o) {
  Situation s;
  s.name = std::move(name);
  s.description = std::move(description);
  s.setup.path = {{0, 0}, {0, kLegM}};
  s.setup.cruise_speed_mps = kSpeed;
  s.setup.traffic = std::move(traffic);
  s.setup.avoidance = o;
  s.setup.max_time_s = 2.0 * kLegM / kSpeed;
  s.expected = std::move(expected);
  return s;
}

// A channel between banks at x = -half_m and x = +half_m, the own ship's
// track at x = lane_m.
Situation Channel(std::string name, std::string description, std::vector<EncounterVessel> traffic,
                  std::vector<Expectation> expected, const CollisionAvoidanceOptions& o,
                  double half_m = kChannelHalfM, double lane_m = kLaneM) {
  Situation s =
      Open(std::move(name), std::move(description), std::move(traffic), std::move(expected), o);
  s.setup.path = {{lane_m, 0}, {lane_m, kLegM}};
  const double y0 = -2000, y1 = kLegM + 2000;
  s.setup.land = {{{-3000, y0}, {-half_m, y0}, {-half_m, y1}, {-3000, y1}},
                  {{half_m, y0}, {3000, y0}, {3000, y1}, {half_m, y1}}};
  return s;
}

const Expectation kHeadOn{Role::kHeadOn, Side::kPort, true, false};
const Expectation kGiveWay{Role::kCrossingGiveWay, Side::kPort, true, false};
const Expectation kStandOnPort{Role::kCrossingStandOn, Side::kEither, true, true};
const Expectation kOvertaking{Role::kOvertaking, Side::kEither, false, false};
const Expectation kOvertaken{Role::kOvertaken, Side::kEither, false, true};
const Expectation kStill{Role::kNone, Side::kEither, false, false};
// A vessel that is no encounter at first but may become one as the ship
// manoeuvres for another: keep clear of it, whatever the role.
// Give-way once under way; lying still it has no role, and keeping clear
// of it may take the ship to port. With a minute's warning no side is
// asked: passing astern of it at the safety distance is out of reach.
const Expectation kGiveWayAfterStill{Role::kCrossingGiveWay, Side::kEither, false, false};
const Expectation kKeepClear{Role::kNone, Side::kEither, false, false, false};

}  // namespace

std::string_view SideName(Side s) {
  switch (s) {
    case Side::kPort:
      return "port";
    case Side::kStarboard:
      return "starboard";
    case Side::kEither:
      return "either";
  }
  return "either";
}

std::vector<Situation> Situations(const CollisionAvoidanceOptions& o) {
  std::vector<Situation> v;
  // Open water, one vessel.
  v.push_back(Open("head-on", "reciprocal course, same speed, collision in 400 s",
                   {Meeting(1, "A", 180, 9, 400)}, {kHeadOn}, o));
  v.push_back(Open("head-on-port-offset", "reciprocal course, would pass 80 m on our port side",
                   {Meeting(1, "A", 180, 9, 400, -80)}, {kHeadOn}, o));
  v.push_back(Open("head-on-slow", "nearly reciprocal (175 deg), 5 m/s",
                   {Meeting(1, "A", 175, 5, 450)}, {kHeadOn}, o));
  v.push_back(Open("crossing-starboard-90", "from starboard, on course 270, 9 m/s",
                   {Meeting(1, "A", 270, 9, 400)}, {kGiveWay}, o));
  v.push_back(Open("crossing-starboard-bow", "from the starboard bow, on course 225, 8 m/s",
                   {Meeting(1, "A", 225, 8, 400)}, {kGiveWay}, o));
  v.push_back(Open("crossing-starboard-aft", "from abaft the starboard beam, on course 315, 12 m/s",
                   {Meeting(1, "A", 315, 12, 400)}, {kGiveWay}, o));
  v.push_back(Open("crossing-starboard-fast", "from starboard, on course 260, 14 m/s",
                   {Meeting(1, "A", 260, 14, 380)}, {kGiveWay}, o));
  v.push_back(Open("crossing-port-90", "from port, on course 090, 9 m/s (stand-on)",
                   {Meeting(1, "A", 90, 9, 400)}, {kStandOnPort}, o));
  v.push_back(Open("crossing-port-bow", "from the port bow, on course 135, 8 m/s (stand-on)",
                   {Meeting(1, "A", 135, 8, 400)}, {kStandOnPort}, o));
  Situation overtake = Open("overtaking", "a vessel 1.5 km ahead at 40 % of our speed",
                            {SameCourse(1, "A", 0.4 * kSpeed, 1500)}, {kOvertaking}, o);
  overtake.max_time_lost = 0.10;
  v.push_back(overtake);
  Situation overtake_offset =
      Open("overtaking-offset", "a vessel 1 km ahead at 40 % of our speed, 60 m to starboard",
           {SameCourse(1, "A", 0.4 * kSpeed, 1000, 60)}, {kOvertaking}, o);
  overtake_offset.max_time_lost = 0.10;
  v.push_back(overtake_offset);
  v.push_back(Open("overtaken", "a vessel 1.2 km astern at 14 m/s on our track (stand-on)",
                   {SameCourse(1, "A", 14, -1200)}, {kOvertaken}, o));
  v.push_back(Open("still-vessel", "a vessel lying still on our track 2.5 km ahead",
                   {SameCourse(1, "A", 0, 2500)}, {kStill}, o));
  // Open water, two and three vessels.
  v.push_back(Open("head-on-and-crossing-starboard", "head-on and from starboard at the same time",
                   {Meeting(1, "A", 180, 9, 420), Meeting(2, "B", 270, 8, 450, 300)},
                   {kHeadOn, kGiveWay}, o));
  v.push_back(Open("crossing-both-sides", "from starboard and from port at once",
                   {Meeting(1, "A", 270, 9, 400), Meeting(2, "B", 90, 9, 420)},
                   {kGiveWay, kStandOnPort}, o));
  Situation three = Open("overtaking-with-head-on-and-crossing",
                         "a slow vessel ahead, a head-on vessel beyond it, one from starboard",
                         {SameCourse(1, "A", 0.4 * kSpeed, 1200), Meeting(2, "B", 180, 9, 600),
                          Meeting(3, "C", 250, 9, 380)},
                         {kOvertaking, kHeadOn, kGiveWay}, o);
  v.push_back(three);
  v.push_back(Open(
      "crossing-port-while-overtaken",
      "stand-on twice: overtaken from astern at 13 m/s while a vessel crosses from port",
      {SameCourse(1, "A", 13, -1300), Meeting(2, "B", 90, 8, 380)}, {kOvertaken, kStandOnPort}, o));
  v.push_back(Open("head-on-with-vessel-to-starboard",
                   "head-on while a faster vessel on a parallel course 300 m to starboard boxes "
                   "us in",
                   {Meeting(1, "A", 180, 9, 400), SameCourse(2, "B", 9.5, 150, 300)},
                   {kHeadOn, kKeepClear}, o));
  // Rule 13: coming up from more than 22.5 deg abaft its beam makes us the
  // overtaking vessel although its course crosses ours from port.
  v.push_back(Open("overtaking-crossing-course",
                   "a vessel on course 030 at 3 m/s ahead on our port bow, we come from abaft "
                   "its beam",
                   {Meeting(1, "A", 30, 3, 400)}, {kOvertaking}, o));
  // A vessel lying still 360 m east of the track gets under way westwards
  // at 6 m/s 60 s before it would cross the track in front of us: seen on
  // its present velocity, it is no conflict until then.
  EncounterVessel departing = Meeting(1, "A", 270, 6, 400);
  departing.still_until_s = 340;
  departing.position = departing.position + departing.velocity * 340;
  v.push_back(Open("departing-across-starboard",
                   "a vessel lying still 360 m to starboard of the track gets under way across "
                   "it at 6 m/s 60 s before it would reach us",
                   {departing}, {kGiveWayAfterStill}, o));
  v.push_back(Open("two-crossing-starboard", "two vessels from starboard, 150 s apart",
                   {Meeting(1, "A", 270, 9, 350), Meeting(2, "B", 240, 9, 500)},
                   {kGiveWay, kGiveWay}, o));
  // Narrow channel: banks 800 m apart, own track 80 m east of the axis.
  v.push_back(Channel("channel-head-on", "a vessel on the axis, southbound",
                      {Meeting(1, "A", 180, 8, 400, -kLaneM, kLaneM)}, {kHeadOn}, o));
  Situation ch_overtake =
      Channel("channel-overtaking", "a vessel at 40 % of our speed, 1.2 km ahead on our track",
              {SameCourse(1, "A", 0.4 * kSpeed, 1200, 0, kLaneM)}, {kOvertaking}, o);
  ch_overtake.max_time_lost = 0.10;
  v.push_back(ch_overtake);
  v.push_back(Channel("channel-overtaken", "a vessel 1 km astern at 13 m/s on our track",
                      {SameCourse(1, "A", 13, -1000, 0, kLaneM)}, {kOvertaken}, o));
  v.push_back(Channel("channel-crossing-starboard",
                      "a ferry crossing the channel from the east bank",
                      {Meeting(1, "A", 270, 5, 300, 0, kLaneM)}, {kGiveWay}, o));
  v.push_back(Channel("channel-two-head-on", "two southbound vessels on the axis, 1.5 km apart",
                      {Meeting(1, "A", 180, 8, 350, -kLaneM, kLaneM),
                       Meeting(2, "B", 180, 8, 450, -kLaneM, kLaneM)},
                      {kHeadOn, kHeadOn}, o));
  v.push_back(Channel("channel-overtaking-with-head-on",
                      "a slow vessel ahead on our track while a vessel comes down the axis",
                      {SameCourse(1, "A", 0.4 * kSpeed, 1000, 0, kLaneM),
                       Meeting(2, "B", 180, 8, 500, -kLaneM, kLaneM)},
                      {kOvertaking, kHeadOn}, o));
  // A narrower channel, banks 700 m apart, the own track 200 m from the
  // starboard bank (rule 9): a starboard turn soon meets the land, and
  // what the avoidance may do there depends on how much water it has.
  constexpr double kNarrowHalfM = 350.0, kNarrowLaneM = 150.0;
  v.push_back(Channel("narrow-crossing-starboard",
                      "a ferry crossing from the near starboard bank, 200 m off our track",
                      {Meeting(1, "A", 270, 5, 260, 0, kNarrowLaneM)}, {kGiveWay}, o, kNarrowHalfM,
                      kNarrowLaneM));
  v.push_back(Channel("narrow-head-on", "a vessel coming down the channel's axis",
                      {Meeting(1, "A", 180, 8, 420, -kNarrowLaneM, kNarrowLaneM)}, {kHeadOn}, o,
                      kNarrowHalfM, kNarrowLaneM));
  v.push_back(Channel("narrow-crossing-port", "a ferry crossing from the port bank (stand-on)",
                      {Meeting(1, "A", 90, 5, 400, 0, kNarrowLaneM)}, {kStandOnPort}, o,
                      kNarrowHalfM, kNarrowLaneM));
  Situation narrow_overtake =
      Channel("narrow-overtaking", "a vessel at 40 % of our speed, 1 km ahead on our track",
              {SameCourse(1, "A", 0.4 * kSpeed, 1000, 0, kNarrowLaneM)}, {kOvertaking}, o,
              kNarrowHalfM, kNarrowLaneM);
  narrow_overtake.max_time_lost = 0.10;
  v.push_back(narrow_overtake);
  // A passage 430 m wide, the own track 180 m from the starboard bank, and
  // a vessel lying still 100 m to starboard of it, 80 m off that bank (a
  // ferry at its berth): the planning distance fits between it and the port
  // bank, its growing margin does not. The room given to it must not come
  // out of the room kept from the port bank.
  constexpr double kPassageHalfM = 215.0, kPassageLaneM = 35.0;
  Situation passage = Channel(
      "still-vessel-narrow-passage",
      "a vessel lying still 100 m to starboard of the track, 80 m off the starboard bank, in a "
      "passage 430 m wide",
      {SameCourse(1, "A", 0, 2500, 100, kPassageLaneM)}, {kStill}, o, kPassageHalfM, kPassageLaneM);
  passage.min_land_clearance_m = 60.0;  // the land cost's band
  v.push_back(passage);
  return v;
}

StatusOr<Result> Run(const Situation& s) {
  Result r;
  SEAPLAN_ASSIGN_OR_RETURN(r.outcome, SimulateEncounter(s.setup));
  EncounterSetup free = s.setup;
  free.traffic.clear();
  SEAPLAN_ASSIGN_OR_RETURN(EncounterOutcome alone, SimulateEncounter(free));
  r.time_lost = alone.arrival_time_s > 0
                    ? (r.outcome.arrival_time_s - alone.arrival_time_s) / alone.arrival_time_s
                    : 0.0;
  const EncounterOutcome& o = r.outcome;
  const CollisionAvoidanceOptions& opt = s.setup.avoidance;
  auto fail = [&](std::string what) { r.failures.push_back(std::move(what)); };
  if (!o.arrived) fail("did not reach the end of the path");
  if (o.aground_s > 0 || (!s.setup.land.empty() && o.min_land_clearance_m < 0)) {
    fail(absl::StrFormat("aground %.0f s", o.aground_s));
  }
  bool port_turn_ruled_out = false;
  for (size_t i = 0; i < s.expected.size() && i < o.vessels.size(); ++i) {
    const Expectation& e = s.expected[i];
    const VesselOutcome& v = o.vessels[i];
    const std::string& name = s.setup.traffic[i].name;
    if (v.min_distance_m < opt.safety_distance_m) {
      fail(absl::StrFormat("%s: CPA %.0f m < %.0f m", name, v.min_distance_m,
                           opt.safety_distance_m));
    }
    if (e.role_checked && v.role != Role::kNone && v.role != e.role) {
      fail(absl::StrFormat("%s: role %s, expected %s", name, RoleName(v.role), RoleName(e.role)));
    }
    const Side side = v.bearing_rad < 0 ? Side::kPort : Side::kStarboard;
    if (e.side != Side::kEither && side != e.side) {
      fail(absl::StrFormat("%s: passed on our %s side, expected %s", name, SideName(side),
                           SideName(e.side)));
    }
    if (e.stand_on && v.first_manoeuvre_s >= 0 &&
        v.tcpa_at_first_manoeuvre_s > opt.rule17_time_s + 2 * opt.decision_interval_s) {
      fail(absl::StrFormat("%s: stand-on ship manoeuvred %.0f s before the CPA (rule 17: %.0f s)",
                           name, v.tcpa_at_first_manoeuvre_s, opt.rule17_time_s));
    }
    port_turn_ruled_out = port_turn_ruled_out || e.no_port_turn;
  }
  if (port_turn_ruled_out && o.max_port_offset_rad > 1 * kDeg) {
    fail(absl::StrFormat("turned %.0f deg to port", o.max_port_offset_rad / kDeg));
  }
  int small = 0;
  const EncounterOutcome::Manoeuvre* first_small = nullptr;
  for (const EncounterOutcome::Manoeuvre& m : o.manoeuvre_extents) {
    if (m.max_offset_rad < 25 * kDeg && m.min_speed_factor > 0.6) {
      if (small++ == 0) first_small = &m;
    }
  }
  if (first_small != nullptr) {
    fail(absl::StrFormat(
        "%d manoeuvre(s) not readily apparent, the first at %.0f s: course offset of %.0f deg "
        "at most, speed %.0f %%",
        small, first_small->start_s, first_small->max_offset_rad / kDeg,
        first_small->min_speed_factor * 100));
  }
  if (s.min_land_clearance_m >= 0 && !s.setup.land.empty() &&
      o.min_land_clearance_m < s.min_land_clearance_m) {
    fail(absl::StrFormat("land clearance %.0f m < %.0f m", o.min_land_clearance_m,
                         s.min_land_clearance_m));
  }
  if (s.max_time_lost >= 0 && r.time_lost > s.max_time_lost) {
    fail(absl::StrFormat("time lost %.1f %% > %.0f %%", r.time_lost * 100, s.max_time_lost * 100));
  }
  return r;
}

}  // namespace seaplan::colav::suite
