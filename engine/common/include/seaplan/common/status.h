// Status values used across every seaplan library boundary.
//
// Libraries return absl::Status / absl::StatusOr<T>; nothing throws across an
// API. Results that are not errors (no plan exists, time limit reached) are
// values of the result types, not statuses. The server maps these codes to
// gRPC and HTTP in one place (server/core/status_mapping).
#pragma once

#include "absl/status/status.h"
#include "absl/status/statusor.h"

namespace seaplan {

using absl::Status;
using absl::StatusOr;

}  // namespace seaplan

#define SEAPLAN_STATUS_CONCAT_INNER_(a, b) a##b
#define SEAPLAN_STATUS_CONCAT_(a, b) SEAPLAN_STATUS_CONCAT_INNER_(a, b)

// Returns from the current function if `expr` yields a non-OK status.
#define SEAPLAN_RETURN_IF_ERROR(expr)                  \
  do {                                                 \
    ::absl::Status seaplan_status_ = (expr);           \
    if (!seaplan_status_.ok()) return seaplan_status_; \
  } while (false)

// `SEAPLAN_ASSIGN_OR_RETURN(auto x, Compute());` binds the value or returns the error.
#define SEAPLAN_ASSIGN_OR_RETURN(lhs, rexpr) \
  SEAPLAN_ASSIGN_OR_RETURN_IMPL_(SEAPLAN_STATUS_CONCAT_(seaplan_statusor_, __LINE__), lhs, rexpr)
#define SEAPLAN_ASSIGN_OR_RETURN_IMPL_(tmp, lhs, rexpr) \
  auto tmp = (rexpr);                                   \
  if (!tmp.ok()) return tmp.status();                   \
  lhs = std::move(tmp).value()
