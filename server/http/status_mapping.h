// The one absl::Status -> HTTP mapping of the gateway, and the JSON error
// body: {"code": "INVALID_ARGUMENT", "message": "...", "details": [...]},
// where details holds the attached DiagnosticList (core/status_details.h)
// in canonical JSON with an "@type" member.
#pragma once

#include <string>

#include "seaplan/common/status.h"

namespace seaplan::server {

// 200 OK, 400 INVALID_ARGUMENT / OUT_OF_RANGE, 401, 403, 404 NOT_FOUND,
// 409 ALREADY_EXISTS / ABORTED, 412 FAILED_PRECONDITION, 429
// RESOURCE_EXHAUSTED, 499 CANCELLED (client closed request), 501
// UNIMPLEMENTED, 503 UNAVAILABLE, 504 DEADLINE_EXCEEDED, 500 otherwise.
int ToHttpStatus(absl::StatusCode code);

std::string ErrorJson(const absl::Status& status);

}  // namespace seaplan::server
