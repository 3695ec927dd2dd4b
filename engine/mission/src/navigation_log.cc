#include "seaplan/mission/navigation_log.h"

#include "absl/strings/str_cat.h"

namespace seaplan::mission {

std::string TaskStartedMessage(TaskKind kind) {
  return absl::StrCat(std::string(TaskKindName(kind)), " task started");
}
std::string TaskCompletedMessage(TaskKind kind) {
  return absl::StrCat(std::string(TaskKindName(kind)), " task completed");
}
std::string TaskFailedMessage(TaskKind kind) {
  return absl::StrCat("task ", std::string(TaskKindName(kind)), " failed, need re-planning");
}

void NavigationLog::Add(double mission_time_s, std::string_view message, std::string_view source) {
  entries_.push_back({mission_time_s, std::string(source), std::string(message)});
}

int NavigationLog::Find(std::string_view message) const {
  for (size_t i = 0; i < entries_.size(); ++i) {
    if (entries_[i].message == message) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace seaplan::mission
