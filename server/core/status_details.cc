#include "server/core/status_details.h"

#include "absl/strings/cord.h"
#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "server/core/call_context.h"

namespace seaplan::server {

absl::Status WithDiagnostics(absl::Status status, const v1::DiagnosticList& diagnostics) {
  if (status.ok() || diagnostics.diagnostics_size() == 0) return status;
  status.SetPayload(kDiagnosticListTypeUrl, absl::Cord(diagnostics.SerializeAsString()));
  return status;
}

std::optional<v1::DiagnosticList> GetDiagnostics(const absl::Status& status) {
  auto payload = status.GetPayload(kDiagnosticListTypeUrl);
  if (!payload) return std::nullopt;
  v1::DiagnosticList list;
  if (!list.ParseFromString(std::string(*payload))) return std::nullopt;
  return list;
}

absl::Status WithRetryAfter(absl::Status status, std::chrono::milliseconds retry_after) {
  if (status.ok()) return status;
  status.SetPayload(kRetryAfterTypeUrl, absl::Cord(absl::StrCat(retry_after.count())));
  return status;
}

std::optional<std::chrono::milliseconds> GetRetryAfter(const absl::Status& status) {
  auto payload = status.GetPayload(kRetryAfterTypeUrl);
  if (!payload) return std::nullopt;
  long long ms = 0;
  if (!absl::SimpleAtoi(std::string(*payload), &ms) || ms < 0) return std::nullopt;
  return std::chrono::milliseconds(ms);
}

absl::Status StopStatus(const StopToken& stop, bool shutting_down, const std::string& what) {
  if (shutting_down)
    return absl::UnavailableError(absl::StrCat(what, " stopped: the server is shutting down"));
  if (stop.Reason() == StopReason::kDeadline) {
    return absl::DeadlineExceededError(
        absl::StrCat(what, " stopped: the client's deadline was reached"));
  }
  return absl::CancelledError(absl::StrCat(what, " cancelled: the client went away"));
}

}  // namespace seaplan::server
