#include "server/grpc/status_mapping.h"

#include "server/core/status_details.h"

namespace seaplan::server {

grpc::Status ToGrpcStatus(const absl::Status& status) {
  if (status.ok()) return grpc::Status::OK;
  const auto code = static_cast<grpc::StatusCode>(static_cast<int>(status.code()));
  std::string message(status.message());
  if (auto diagnostics = GetDiagnostics(status)) {
    return grpc::Status(code, message, diagnostics->SerializeAsString());
  }
  return grpc::Status(code, message);
}

}  // namespace seaplan::server
