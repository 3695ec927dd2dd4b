// The navigation log of a mission (paper 000 tables 4, 7, 11): every event
// with its mission time and source. Messages use the paper's wording so
// logs of seaplan and the paper can be read side by side.
//
// Thread-compatible value type (guard it when shared).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "seaplan/mission/types.h"

namespace seaplan::mission {

namespace messages {
inline constexpr std::string_view kComputingPlan = "computing the temporal plan";
inline constexpr std::string_view kRefiningPlan = "refining the plan";
inline constexpr std::string_view kParsingPlan = "parsing the plan";
inline constexpr std::string_view kPotentialCollision = "potential collision situation";
inline constexpr std::string_view kUpdatingProblem = "updating the problem";
inline constexpr std::string_view kReplanDone = "replan and refined done";
inline constexpr std::string_view kMissionCompleted = "mission completed";
}  // namespace messages

// "<kind> task started" ("move task started", "load task started", ...).
std::string TaskStartedMessage(TaskKind kind);
// "<kind> task completed".
std::string TaskCompletedMessage(TaskKind kind);
// "task <kind> failed, need re-planning".
std::string TaskFailedMessage(TaskKind kind);

struct LogEntry {
  double mission_time_s = 0.0;
  std::string source;  // "server" or a vessel id
  std::string message;
};

class NavigationLog {
 public:
  void Add(double mission_time_s, std::string_view message, std::string_view source = "server");
  const std::vector<LogEntry>& entries() const { return entries_; }
  // Index of the first entry whose message equals `message`, -1 when none.
  int Find(std::string_view message) const;

 private:
  std::vector<LogEntry> entries_;
};

}  // namespace seaplan::mission
