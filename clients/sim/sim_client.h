// The gRPC side of seaplan-sim: MissionService (CreateMission, GetMission,
// WatchMission, ReportFeedback, ReportVesselState) and ChartService (UploadChart). Nothing else
// of the server is used: the simulation talks to it only over gRPC.
//
// Watching runs on its own thread and survives a broken stream: it
// reconnects with (after_version, after_event_id) of the last event seen,
// so nothing is missed and nothing is seen twice. Feedback retries transient
// errors (UNAVAILABLE, DEADLINE_EXCEEDED, RESOURCE_EXHAUSTED, ABORTED) with
// the SAME sequence number, which the server deduplicates.
#pragma once

#include <grpcpp/grpcpp.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"
#include "seaplan/v1/chart.grpc.pb.h"
#include "seaplan/v1/mission.grpc.pb.h"

namespace seaplan::sim {

absl::Status FromGrpc(const grpc::Status& s);

class SimClient {
 public:
  explicit SimClient(const std::string& address);
  ~SimClient();

  absl::StatusOr<v1::Mission> CreateMission(const v1::MissionSpec& spec,
                                            const std::string& request_id);
  absl::StatusOr<v1::Mission> GetMission(const std::string& mission_id);
  absl::StatusOr<v1::Chart> UploadChart(const std::string& name, const std::string& file_name,
                                        const std::string& bytes);
  // Posts one report; retries transient errors with the same sequence
  // number up to `attempts` times.
  absl::StatusOr<v1::ReportFeedbackResponse> Report(const v1::ReportFeedbackRequest& request,
                                                    int attempts = 8);

  // Posts the live picture once (no retry: the next one replaces it).
  absl::Status ReportVesselState(const v1::ReportVesselStateRequest& request);

  // Starts the watch thread for `mission_id`.
  void StartWatch(const std::string& mission_id);
  void StopWatch();

  // Waits for a plan version > `after_version`, or a terminal mission state,
  // up to `timeout`. Returns the version, or nullopt (check terminal_state()).
  std::optional<v1::PlanVersion> WaitForVersion(int after_version,
                                                std::chrono::milliseconds timeout);
  // A version > after_version if one already arrived (no waiting).
  std::optional<v1::PlanVersion> PollVersion(int after_version);
  // Log events received since the last call.
  std::vector<v1::LogEvent> TakeLogEvents();
  // The mission state last seen on the stream (UNSPECIFIED when none).
  v1::MissionState terminal_state() const;
  int reconnects() const { return reconnects_.load(); }

 private:
  void WatchLoop(std::string mission_id);

  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::MissionService::Stub> missions_;
  std::unique_ptr<v1::ChartService::Stub> charts_;

  mutable std::mutex mu_;
  std::condition_variable cv_;
  std::deque<v1::PlanVersion> versions_;
  std::vector<v1::LogEvent> log_events_;
  v1::MissionState state_ = v1::MISSION_STATE_UNSPECIFIED;
  int last_version_ = 0;
  int64_t last_event_id_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<int> reconnects_{0};
  std::unique_ptr<grpc::ClientContext> watch_context_;  // guarded by mu_
  std::thread watcher_;
};

}  // namespace seaplan::sim
