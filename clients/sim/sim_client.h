// The gRPC side of seaplan-sim: MissionService (CreateMission, GetMission,
// WatchMission, ReportFeedback, ReportVesselState) and ChartService (UploadChart). Nothing else
// of the server is used: the simulation talks to it only over gRPC.
//
// Watching runs on its own thread and survives a broken stream or a shore
// outage: it reconnects with (after_version, after_event_id) of the last
// event seen, so nothing is missed and nothing is seen twice.
//
// Feedback goes through the uplink: each report gets the next sequence
// number, is written to the on-disk journal (fsync'd) and queued; a sender
// thread posts the queue in order, retrying transient errors (UNAVAILABLE,
// DEADLINE_EXCEEDED, RESOURCE_EXHAUSTED, ABORTED) with the SAME sequence
// number (the server deduplicates by vessel and sequence number) with
// exponential backoff and jitter, for as long as it runs. The caller keeps
// executing meanwhile: a shore outage delays reports, it does not stop the
// ship. Reports an earlier run left unacknowledged in the journal go first.
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
#include "feedback_journal.h"
#include "seaplan/v1/chart.grpc.pb.h"
#include "seaplan/v1/mission.grpc.pb.h"

namespace seaplan::sim {

absl::Status FromGrpc(const grpc::Status& s);

// A report the shore acknowledged, with its answer.
struct FeedbackAck {
  v1::ReportFeedbackRequest request;
  v1::ReportFeedbackResponse response;
};

class SimClient {
 public:
  // `credentials`: plaintext or TLS (clients/common/tls_channel.h);
  // `token`: presented on every call (empty: none).
  SimClient(const std::string& address,
            const std::shared_ptr<grpc::ChannelCredentials>& credentials,
            const std::string& token = "");
  ~SimClient();

  absl::StatusOr<v1::Mission> CreateMission(const v1::MissionSpec& spec,
                                            const std::string& request_id);
  absl::StatusOr<v1::Mission> GetMission(const std::string& mission_id);
  absl::StatusOr<v1::Chart> UploadChart(const std::string& name, const std::string& file_name,
                                        const std::string& bytes);
  // Opens the feedback journal at `journal_path` and starts the sender
  // thread (which first re-sends what an earlier run left unacknowledged).
  absl::Status StartUplink(const std::string& journal_path);
  // Numbers the reports (their sequence_number is overwritten), journals
  // them durably, then queues them for sending in order.
  absl::Status Send(std::vector<v1::ReportFeedbackRequest> reports);
  // Waits until every queued report is acknowledged (true), or returns
  // false at `timeout` or as soon as the shore is found unreachable.
  bool WaitSent(std::chrono::milliseconds timeout);
  // Acknowledgements received since the last call, in sending order.
  std::vector<FeedbackAck> TakeAcks();
  // The first report of this mission the server refused for good (neither
  // transient nor "mission already finished"); OK when none.
  absl::Status uplink_error() const;
  // The last send failed with a transient error and none succeeded since.
  bool shore_unreachable() const { return shore_unreachable_.load(); }
  // Reports journaled but not yet acknowledged.
  size_t backlog() const;
  void StopUplink();

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
  void UplinkLoop();
  // Posts one report once (deadline 5 s, times kWallClockScale).
  grpc::Status PostFeedback(const v1::ReportFeedbackRequest& request,
                            v1::ReportFeedbackResponse* response);

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

  // The uplink: journal, queue and sender thread.
  mutable std::mutex uplink_mu_;
  std::condition_variable uplink_cv_;
  std::optional<FeedbackJournal> journal_;  // guarded by uplink_mu_
  std::deque<v1::ReportFeedbackRequest> outbox_;
  std::vector<FeedbackAck> acks_;
  absl::Status uplink_error_;
  std::int64_t next_sequence_ = 0;
  std::int64_t replayed_until_ = 0;  // reports up to this number came from an earlier run
  bool uplink_stop_ = false;
  std::atomic<bool> shore_unreachable_{false};
  std::thread uplink_;
};

}  // namespace seaplan::sim
