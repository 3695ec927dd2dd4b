#include "server/core/vessel_tracker.h"

#include <atomic>
#include <cmath>
#include <thread>

#include "absl/strings/str_cat.h"
#include "server/core/caller_limits.h"

namespace seaplan::server {
namespace {

bool ValidLatLon(const v1::LatLon& p) {
  return std::isfinite(p.latitude_deg()) && std::isfinite(p.longitude_deg()) &&
         std::abs(p.latitude_deg()) <= 90 && std::abs(p.longitude_deg()) <= 180;
}

}  // namespace

VesselTracker::VesselTracker(storage::MissionRepository& repo, Options options)
    : repo_(repo), options_(options) {}

absl::StatusOr<v1::ReportVesselStateResponse> VesselTracker::ReportVesselState(
    const v1::ReportVesselStateRequest& request, const CallContext& ctx) {
  if (request.mission_id().empty()) return absl::InvalidArgumentError("mission_id is empty");
  if (!request.has_state() || !request.state().has_position())
    return absl::InvalidArgumentError("state.position is missing");
  if (!ValidLatLon(request.state().position())) {
    return absl::InvalidArgumentError(
        absl::StrCat("state.position: (", request.state().position().latitude_deg(), ", ",
                     request.state().position().longitude_deg(), ") is not a WGS84 position"));
  }
  for (int i = 0; i < request.targets_size(); ++i) {
    if (!ValidLatLon(request.targets(i).position())) {
      return absl::InvalidArgumentError(
          absl::StrCat("targets[", i, "].position is not a WGS84 position"));
    }
  }
  std::string vessel_id;
  {
    std::lock_guard lock(mu_);
    auto it = entries_.find(request.mission_id());
    if (it != entries_.end()) vessel_id = it->second.vessel_id;
  }
  if (vessel_id.empty() || ctx.caller.role == auth::Role::kVessel) {
    // First report (the mission must exist), or a vessel token, whose
    // binding is checked against the stored mission every time.
    SEAPLAN_ASSIGN_OR_RETURN(storage::MissionRecord record, repo_.Get(request.mission_id()));
    SEAPLAN_RETURN_IF_ERROR(auth::CheckVessel(ctx.caller, record.vessel_id, record.id));
    vessel_id = record.vessel_id.empty() ? request.vessel_id() : record.vessel_id;
  }
  SEAPLAN_RETURN_IF_ERROR(CheckVesselCertificate(ctx, vessel_id, request.mission_id()));
  if (!request.vessel_id().empty() && request.vessel_id() != vessel_id) {
    return absl::PermissionDeniedError(absl::StrCat("vessel ", request.vessel_id(),
                                                    " does not sail mission ", request.mission_id(),
                                                    " (", vessel_id, " does)"));
  }
  v1::VesselUpdate update;
  update.set_mission_id(request.mission_id());
  update.set_vessel_id(vessel_id);
  update.set_mission_time_s(request.mission_time_s());
  *update.mutable_state() = request.state();
  *update.mutable_targets() = request.targets();

  v1::ReportVesselStateResponse response;
  std::lock_guard lock(mu_);
  Entry& entry = entries_[request.mission_id()];
  entry.vessel_id = vessel_id;
  entry.pending = std::move(update);
  const auto now = std::chrono::steady_clock::now();
  PublishIfDue(entry, now);
  response.set_published(!entry.pending.has_value());
  return response;
}

void VesselTracker::PublishIfDue(Entry& entry, std::chrono::steady_clock::time_point now) {
  if (!entry.pending) return;
  if (entry.published && now - entry.published_at < options_.min_interval) return;
  entry.pending->set_sequence(++entry.sequence);
  entry.track.push_back(entry.pending->state().position());
  while (entry.track.size() > options_.max_track_points) entry.track.pop_front();
  entry.published = std::move(entry.pending);
  entry.pending.reset();
  entry.published_at = now;
  cv_.notify_all();
}

std::optional<v1::VesselUpdate> VesselTracker::Next(const std::string& mission_id,
                                                    std::int64_t after_sequence, bool with_track,
                                                    std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::unique_lock lock(mu_);
  while (!closed_) {
    const auto now = std::chrono::steady_clock::now();
    auto it = entries_.find(mission_id);
    auto wake = deadline;
    if (it != entries_.end()) {
      Entry& entry = it->second;
      PublishIfDue(entry, now);
      if (entry.published && entry.published->sequence() > after_sequence) {
        v1::VesselUpdate out = *entry.published;
        if (with_track) {
          // The update's own position is the track's last point.
          for (std::size_t i = 0; i + 1 < entry.track.size(); ++i)
            *out.add_track() = entry.track[i];
        }
        return out;
      }
      if (entry.pending) wake = std::min(wake, entry.published_at + options_.min_interval);
    }
    if (now >= deadline) return std::nullopt;
    cv_.wait_until(lock, wake);
  }
  return std::nullopt;
}

absl::Status VesselTracker::WatchMission(MissionCoordinator& missions,
                                         const v1::WatchMissionRequest& request,
                                         const CallContext& ctx,
                                         const StreamSink<v1::MissionEvent>& sink) {
  // Before the live picture starts: it must not reach another vessel's token.
  if (!request.mission_id().empty()) {
    SEAPLAN_RETURN_IF_ERROR(missions.CheckVesselAccess(request.mission_id(), ctx));
  }
  // Two writers (the coordinator's loop and the pusher below) share the sink.
  std::mutex sink_mu;
  bool sink_open = true;
  StreamSink<v1::MissionEvent> shared = [&](const v1::MissionEvent& event) {
    std::lock_guard lock(sink_mu);
    if (!sink_open) return false;
    sink_open = sink(event);
    return sink_open;
  };
  std::atomic<bool> done{false};
  std::thread pusher([&] {
    std::int64_t sent = 0;
    while (!done.load() && !ctx.stop.StopRequested()) {
      auto update = Next(request.mission_id(), sent, sent == 0, std::chrono::milliseconds(200));
      if (!update) {
        std::lock_guard lock(mu_);
        if (closed_) break;
        continue;
      }
      if (done.load()) break;
      sent = update->sequence();
      v1::MissionEvent event;
      *event.mutable_vessel() = std::move(*update);
      if (!shared(event)) break;
    }
  });
  absl::Status status = missions.WatchMission(request, ctx, shared);
  done.store(true);
  {
    std::lock_guard lock(mu_);
    cv_.notify_all();
  }
  pusher.join();
  return status;
}

void VesselTracker::Close() {
  std::lock_guard lock(mu_);
  closed_ = true;
  cv_.notify_all();
}

}  // namespace seaplan::server
