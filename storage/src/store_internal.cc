#include "store_internal.h"

#include <algorithm>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "absl/strings/str_split.h"

namespace seaplan::storage {
namespace internal {

namespace {
constexpr SchemaStep kSchemaHistory[] = {
    {1, "charts, missions, plan versions, feedback, log events"},
    {2, "mission idempotency keys and completed tasks; charts keep the uploaded files"},
    {3, "mission work leases; change notifications"},
    {4, "API tokens (hashes only) and the audit log"},
};
}  // namespace

std::span<const SchemaStep> SchemaHistory() {
  return kSchemaHistory;
}

std::string JoinTasks(const std::vector<std::string>& tasks) {
  return absl::StrJoin(tasks, "\n");
}

std::vector<std::string> SplitTasks(const std::string& text) {
  if (text.empty()) return {};
  return absl::StrSplit(text, '\n');
}

absl::Status CheckPageSize(int page_size) {
  if (page_size < 1 || page_size > 1000) {
    return absl::InvalidArgumentError(absl::StrCat("page size must be 1..1000, got ", page_size));
  }
  return absl::OkStatus();
}

absl::Status CheckLeaseArguments(const std::string& holder, std::chrono::milliseconds ttl) {
  if (holder.empty()) return absl::InvalidArgumentError("a lease holder id must not be empty");
  if (ttl.count() < 1) {
    return absl::InvalidArgumentError(
        absl::StrCat("a lease must last at least 1 ms, got ", ttl.count(), " ms"));
  }
  return absl::OkStatus();
}

TimestampMs NowMs() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

TimestampMs LatestTime(const std::vector<NewLogEvent>& events, TimestampMs fallback) {
  TimestampMs t = fallback;
  for (const auto& e : events) t = std::max(t, e.time_ms);
  return t;
}

std::string NotFoundMessage(const std::string& what, const std::string& id) {
  return absl::StrCat(what, " '", id, "' not found");
}

absl::Status ChartInUseError(const std::string& chart_id,
                             const std::vector<std::string>& missions) {
  return absl::FailedPreconditionError(
      absl::StrCat("chart '", chart_id, "' is used by ", missions.size(),
                   " mission(s) not yet finished (", absl::StrJoin(missions, ", "),
                   "): cancel them or wait until they end, then delete the chart"));
}

std::string SqlIntList(const std::vector<int>& states) {
  if (states.empty()) return "(NULL)";
  return absl::StrCat("(", absl::StrJoin(states, ", "), ")");
}

std::string UsableAdminTokenQuery(const char* now_param) {
  return absl::StrCat(
      "SELECT 1 FROM api_tokens WHERE role = 'admin' AND revoked_at_ms = 0 AND "
      "(expires_at_ms = 0 OR expires_at_ms > ",
      now_param, ") LIMIT 1");
}

absl::Status LostLeaseError(const std::string& mission_id, const WorkFence& fence) {
  return absl::AbortedError(absl::StrCat("the work lease of mission '", mission_id, "' (holder '",
                                         fence.holder, "', token ", fence.token,
                                         ") is no longer held: the write was refused"));
}

absl::StatusOr<std::optional<WorkLease>> WorkLeaseBase::Claim(const std::string& mission_id,
                                                              const std::string& holder,
                                                              std::chrono::milliseconds ttl) {
  SEAPLAN_RETURN_IF_ERROR(CheckLeaseArguments(holder, ttl));
  if (mission_id.empty()) return absl::InvalidArgumentError("a mission id must not be empty");
  SEAPLAN_ASSIGN_OR_RETURN(std::vector<WorkLease> claimed,
                           ClaimPending(mission_id, holder, ttl, 1));
  if (claimed.empty()) return std::optional<WorkLease>();
  return std::optional<WorkLease>(std::move(claimed[0]));
}

absl::StatusOr<std::optional<WorkLease>> WorkLeaseBase::RequestAndClaim(
    const std::string& mission_id, const std::string& reason, const std::string& holder,
    std::chrono::milliseconds ttl) {
  SEAPLAN_RETURN_IF_ERROR(CheckLeaseArguments(holder, ttl));
  if (mission_id.empty()) return absl::InvalidArgumentError("a mission id must not be empty");
  SEAPLAN_ASSIGN_OR_RETURN(std::vector<WorkLease> claimed,
                           RequestAndClaimFree(mission_id, reason, holder, ttl));
  if (claimed.empty()) return std::optional<WorkLease>();
  return std::optional<WorkLease>(std::move(claimed[0]));
}

absl::StatusOr<std::vector<WorkLease>> WorkLeaseBase::ClaimNext(const std::string& holder,
                                                                std::chrono::milliseconds ttl,
                                                                int limit) {
  SEAPLAN_RETURN_IF_ERROR(CheckLeaseArguments(holder, ttl));
  SEAPLAN_RETURN_IF_ERROR(CheckPageSize(limit));
  SEAPLAN_ASSIGN_OR_RETURN(std::vector<WorkLease> claimed, ClaimPending("", holder, ttl, limit));
  // RETURNING gives rows in no particular order.
  std::sort(claimed.begin(), claimed.end(),
            [](const WorkLease& a, const WorkLease& b) { return a.mission_id < b.mission_id; });
  return claimed;
}

absl::StatusOr<WorkLease> WorkLeaseBase::Renew(const WorkLease& lease,
                                               std::chrono::milliseconds ttl) {
  SEAPLAN_RETURN_IF_ERROR(CheckLeaseArguments(lease.holder, ttl));
  return Change(lease, LeaseChange::kRenew, ttl);
}

absl::Status WorkLeaseBase::Release(const WorkLease& lease) {
  return Change(lease, LeaseChange::kRelease, {}).status();
}

absl::StatusOr<bool> WorkLeaseBase::Complete(const WorkLease& lease) {
  SEAPLAN_ASSIGN_OR_RETURN(WorkLease after, Change(lease, LeaseChange::kComplete, {}));
  return after.pending();
}

absl::StatusOr<WorkLease> WorkLeaseBase::Change(const WorkLease& lease, LeaseChange change,
                                                std::chrono::milliseconds ttl) {
  SEAPLAN_ASSIGN_OR_RETURN(std::vector<WorkLease> rows, UpdateHeld(lease, change, ttl));
  if (rows.empty()) {
    return absl::AbortedError(absl::StrCat("the work lease of mission '", lease.mission_id,
                                           "' (token ", lease.token, ") is no longer held by '",
                                           lease.holder, "'"));
  }
  return rows[0];
}

std::string WorkLeaseBase::SetClause(LeaseChange change, const std::string& new_expiry) {
  switch (change) {
    case LeaseChange::kRenew:
      return absl::StrCat("lease_expires_at_ms = ", new_expiry);
    case LeaseChange::kRelease:
      return "holder = NULL, lease_expires_at_ms = NULL";
    case LeaseChange::kComplete:
      return "holder = NULL, lease_expires_at_ms = NULL, done_requests = claimed_requests";
  }
  return "";
}

std::uint64_t LocalChangeFeed::GenerationLocked(const std::string& mission_id) {
  auto it = generation_.find(mission_id);
  return epoch_ + (it == generation_.end() ? 0 : it->second);
}

std::uint64_t LocalChangeFeed::Generation(const std::string& mission_id) {
  std::lock_guard lock(mu_);
  return GenerationLocked(mission_id);
}

std::uint64_t LocalChangeFeed::Wait(const std::string& mission_id, std::uint64_t seen,
                                    std::chrono::milliseconds timeout) {
  std::unique_lock lock(mu_);
  cv_.wait_for(lock, timeout, [&] { return closed_ || GenerationLocked(mission_id) != seen; });
  return GenerationLocked(mission_id);
}

void LocalChangeFeed::Bump(const std::string& mission_id) {
  {
    std::lock_guard lock(mu_);
    ++generation_[mission_id];
  }
  cv_.notify_all();
}

void LocalChangeFeed::BumpAll() {
  {
    std::lock_guard lock(mu_);
    ++epoch_;
  }
  cv_.notify_all();
}

void LocalChangeFeed::Close() {
  {
    std::lock_guard lock(mu_);
    closed_ = true;
  }
  cv_.notify_all();
}

}  // namespace internal

int LatestSchemaVersion() {
  return internal::SchemaHistory().back().version;
}

}  // namespace seaplan::storage
