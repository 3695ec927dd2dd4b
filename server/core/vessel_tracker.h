// The live picture of each mission's vessel: ReportVesselState keeps the
// latest state and traffic per mission (in memory, not stored) and publishes
// at most one update per mission per `min_interval`; a report inside the
// interval is kept and published when the interval is over, so the newest
// state always arrives. WatchMission streams interleave the published
// updates with the coordinator's versions, log events and state changes.
//
// Updates are a picture, not a history: a watcher gets the latest one (the
// first with the track published so far), never a backlog, and nothing
// survives a server restart. A mission's entry (its latest update and at
// most max_track_points positions) is kept while the server runs.
//
// Thread-safety: all methods may be called from any thread.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "seaplan/storage/repositories.h"
#include "seaplan/v1/mission.pb.h"
#include "server/core/call_context.h"
#include "server/core/mission_coordinator.h"

namespace seaplan::server {

class VesselTracker {
 public:
  struct Options {
    std::chrono::milliseconds min_interval{1000};  // per mission
    std::size_t max_track_points = 10000;          // oldest dropped beyond
  };

  VesselTracker(storage::MissionRepository& repo, Options options);
  explicit VesselTracker(storage::MissionRepository& repo) : VesselTracker(repo, Options{}) {}

  absl::StatusOr<v1::ReportVesselStateResponse> ReportVesselState(
      const v1::ReportVesselStateRequest& request, const CallContext& ctx);

  // The newest published update of `mission_id` with a sequence above
  // `after_sequence`, waiting up to `timeout` for one; `with_track` fills
  // its track. nullopt on timeout or after Close().
  std::optional<v1::VesselUpdate> Next(const std::string& mission_id, std::int64_t after_sequence,
                                       bool with_track, std::chrono::milliseconds timeout);

  // MissionCoordinator::WatchMission with this tracker's updates
  // interleaved; ends when the coordinator's stream ends.
  absl::Status WatchMission(MissionCoordinator& missions, const v1::WatchMissionRequest& request,
                            const CallContext& ctx, const StreamSink<v1::MissionEvent>& sink);

  // Wakes and ends every Next() (server shutdown).
  void Close();

 private:
  struct Entry {
    std::string vessel_id;  // of the mission (reports from another vessel are refused)
    std::optional<v1::VesselUpdate> published;
    std::optional<v1::VesselUpdate> pending;  // newer than published, inside the interval
    std::chrono::steady_clock::time_point published_at{};
    std::int64_t sequence = 0;
    std::deque<v1::LatLon> track;
  };
  // Publishes entry's pending update if the interval is over. Needs mu_.
  void PublishIfDue(Entry& entry, std::chrono::steady_clock::time_point now);

  storage::MissionRepository& repo_;
  Options options_;
  std::mutex mu_;
  std::condition_variable cv_;
  std::map<std::string, Entry> entries_;  // by mission id
  bool closed_ = false;
};

}  // namespace seaplan::server
