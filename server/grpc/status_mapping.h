// The one absl::Status -> grpc::Status conversion of the server. Codes map
// one to one (absl and gRPC share the numbering); an attached DiagnosticList
// (core/status_details.h) becomes the status' binary error details.
#pragma once

#include <grpcpp/support/status.h>

#include "seaplan/common/status.h"

namespace seaplan::server {

grpc::Status ToGrpcStatus(const absl::Status& status);

}  // namespace seaplan::server
