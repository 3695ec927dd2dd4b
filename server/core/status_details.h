// Structured error details that travel inside an absl::Status.
//
// The core attaches a seaplan.v1.DiagnosticList to an error (e.g. malformed
// PDDL: INVALID_ARGUMENT with file, line and column of every problem) as an
// absl::Status payload under kDiagnosticListTypeUrl, serialized in the
// protobuf binary format. The transports expose it:
//   gRPC: grpc::Status::error_details() holds the serialized
//         seaplan.v1.DiagnosticList (binary trailer grpc-status-details-bin).
//         Note: this is the DiagnosticList itself, not a google.rpc.Status
//         wrapper; clients parse it with DiagnosticList::ParseFromString.
//   HTTP: the error body's "details" array holds it in canonical JSON with
//         an "@type" member naming the type URL.
#pragma once

#include <chrono>
#include <optional>

#include "seaplan/common/status.h"
#include "seaplan/v1/common.pb.h"

namespace seaplan::server {

inline constexpr char kDiagnosticListTypeUrl[] = "type.googleapis.com/seaplan.v1.DiagnosticList";

// Returns `status` with `diagnostics` attached (no-op for OK or an empty list).
absl::Status WithDiagnostics(absl::Status status, const v1::DiagnosticList& diagnostics);
// The diagnostics attached to `status`, if any.
std::optional<v1::DiagnosticList> GetDiagnostics(const absl::Status& status);

// When a refused call (RESOURCE_EXHAUSTED) may be tried again. The
// transports expose it: gRPC as the trailing metadata "retry-after-ms"
// (milliseconds), HTTP as the header "Retry-After" (whole seconds, rounded up).
inline constexpr char kRetryAfterTypeUrl[] = "type.seaplan/retry-after-ms";
absl::Status WithRetryAfter(absl::Status status, std::chrono::milliseconds retry_after);
std::optional<std::chrono::milliseconds> GetRetryAfter(const absl::Status& status);

}  // namespace seaplan::server
