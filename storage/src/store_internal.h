// What the SQLite and PostgreSQL backends share: the schema history (one
// numbering for both), the encoding of completed tasks, argument checks, the
// clock, and the in-process change feed. Not part of the public API.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "seaplan/storage/repositories.h"

namespace seaplan::storage::internal {

// One entry per schema version, in order. Each backend has its own SQL for
// every entry (the dialects differ) under the same number and description;
// a released entry is never edited, a change is a new entry.
struct SchemaStep {
  int version;
  const char* description;
};
std::span<const SchemaStep> SchemaHistory();

// Completed task ids are stored as one text, '\n'-separated.
std::string JoinTasks(const std::vector<std::string>& tasks);
std::vector<std::string> SplitTasks(const std::string& text);

absl::Status CheckPageSize(int page_size);
absl::Status CheckLeaseArguments(const std::string& holder, std::chrono::milliseconds ttl);

// Milliseconds since the Unix epoch on this process's clock.
TimestampMs NowMs();
// The latest event time, or `fallback` when later (or there are no events).
TimestampMs LatestTime(const std::vector<NewLogEvent>& events, TimestampMs fallback);

// "<what> '<id>' not found".
std::string NotFoundMessage(const std::string& what, const std::string& id);

// The in-process ChangeFeed: a generation per mission plus an epoch that
// BumpAll() moves for every mission at once. The SQLite store bumps it after
// each commit; the PostgreSQL store's listener thread bumps it for every
// notification. Thread-safe.
class LocalChangeFeed final : public ChangeFeed {
 public:
  std::uint64_t Generation(const std::string& mission_id) override;
  std::uint64_t Wait(const std::string& mission_id, std::uint64_t seen,
                     std::chrono::milliseconds timeout) override;
  void Bump(const std::string& mission_id);
  void BumpAll();
  // Wakes every waiter; later waits return at once.
  void Close();

 private:
  std::uint64_t GenerationLocked(const std::string& mission_id);
  std::mutex mu_;
  std::condition_variable cv_;
  std::unordered_map<std::string, std::uint64_t> generation_;
  std::uint64_t epoch_ = 0;
  bool closed_ = false;
};

}  // namespace seaplan::storage::internal
