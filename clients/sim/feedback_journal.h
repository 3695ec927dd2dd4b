// The onboard feedback journal: every report the ship makes, in order, on
// disk before it is sent, and which of them the shore acknowledged. A ship
// keeps reporting while the shore is down and a restarted client re-sends
// what was never acknowledged, so nothing is lost and (the server
// deduplicating by (vessel, sequence number)) nothing is stored twice.
//
// Format: an append-only text file, one record a line:
//   R <sequence> <base64 of the serialized report>   a report, written and
//                                                    fsync'd before sending
//   A <sequence>                                     acknowledged by the shore
// A line cut short by a crash (the last one, without its newline) is
// ignored: its report was never sent. Acknowledgements are flushed with the
// next report's fsync (or at Close): losing one only causes a re-send,
// which the server answers as a duplicate.
//
// Thread-compatible: callers serialise access (SimClient's uplink does).
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace seaplan::sim {

struct JournalEntry {
  std::int64_t sequence = 0;
  std::string payload;  // opaque bytes (a serialized ReportFeedbackRequest)
};

class FeedbackJournal {
 public:
  // Opens (creating if needed) the journal at `path` and reads what an
  // earlier run left unacknowledged.
  static absl::StatusOr<FeedbackJournal> Open(const std::string& path);
  FeedbackJournal(FeedbackJournal&& other) noexcept;
  FeedbackJournal& operator=(FeedbackJournal&& other) noexcept;
  FeedbackJournal(const FeedbackJournal&) = delete;
  FeedbackJournal& operator=(const FeedbackJournal&) = delete;
  ~FeedbackJournal();

  // Appends the reports and makes them durable (fsync) before returning.
  absl::Status Append(const std::vector<JournalEntry>& entries);
  // Records that the shore acknowledged (or definitively refused) `sequence`.
  absl::Status Acknowledge(std::int64_t sequence);

  // Reports of earlier runs never acknowledged, in the order written.
  const std::vector<JournalEntry>& unacknowledged_at_open() const { return recovered_; }
  // The highest sequence number ever written (0 for a new journal).
  std::int64_t max_sequence() const { return max_sequence_; }
  const std::string& path() const { return path_; }

 private:
  FeedbackJournal() = default;
  absl::Status Write(const std::string& text, bool sync);

  std::string path_;
  int fd_ = -1;
  std::vector<JournalEntry> recovered_;
  std::int64_t max_sequence_ = 0;
};

}  // namespace seaplan::sim
