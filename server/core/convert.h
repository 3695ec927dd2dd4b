// Small translations between engine values and seaplan.v1 messages shared
// by several handlers. Engine-specific translations live in their handler.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "google/protobuf/duration.pb.h"
#include "google/protobuf/timestamp.pb.h"
#include "seaplan/common/status.h"
#include "seaplan/pddl/diagnostic.h"
#include "seaplan/v1/common.pb.h"

namespace seaplan::server {

v1::Diagnostic ToProto(const pddl::Diagnostic& d);
v1::DiagnosticList ToProto(const std::vector<pddl::Diagnostic>& diagnostics);

// Milliseconds since the epoch <-> Timestamp.
google::protobuf::Timestamp ToTimestamp(std::int64_t ms);
std::int64_t NowMs();

// Seconds of a Duration; InvalidArgument naming `field` when negative.
absl::StatusOr<double> DurationSeconds(const google::protobuf::Duration& d, const char* field);

// Page tokens are the decimal storage cursor; "" is the first page.
absl::StatusOr<std::int64_t> ParsePageToken(const std::string& token);
std::string MakePageToken(std::int64_t after);
// page_size 0 -> default 50; negative -> InvalidArgument; above 1000 -> 1000.
absl::StatusOr<int> PageSize(int requested);

// A new random id with `prefix` ("m-", "c-"), 16 hex digits.
std::string NewId(const char* prefix);

}  // namespace seaplan::server
