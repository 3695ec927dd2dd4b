#include "server/http/status_mapping.h"

#include <google/protobuf/util/json_util.h>

#include "seaplan/common/json.h"
#include "server/core/status_details.h"

namespace seaplan::server {

int ToHttpStatus(absl::StatusCode code) {
  switch (code) {
    case absl::StatusCode::kOk:
      return 200;
    case absl::StatusCode::kInvalidArgument:
    case absl::StatusCode::kOutOfRange:
      return 400;
    case absl::StatusCode::kUnauthenticated:
      return 401;
    case absl::StatusCode::kPermissionDenied:
      return 403;
    case absl::StatusCode::kNotFound:
      return 404;
    case absl::StatusCode::kAlreadyExists:
    case absl::StatusCode::kAborted:
      return 409;
    case absl::StatusCode::kFailedPrecondition:
      return 412;
    case absl::StatusCode::kResourceExhausted:
      return 429;
    case absl::StatusCode::kCancelled:
      return 499;
    case absl::StatusCode::kUnimplemented:
      return 501;
    case absl::StatusCode::kUnavailable:
      return 503;
    case absl::StatusCode::kDeadlineExceeded:
      return 504;
    default:
      return 500;
  }
}

std::string ErrorJson(const absl::Status& status) {
  std::string details;
  if (auto diagnostics = GetDiagnostics(status)) {
    std::string json;
    google::protobuf::util::JsonPrintOptions options;
    if (google::protobuf::util::MessageToJsonString(*diagnostics, &json, options).ok() &&
        json.size() >= 2) {
      // {"diagnostics":[...]} -> {"@type":"...","diagnostics":[...]}
      details = std::string("{\"@type\":\"") + kDiagnosticListTypeUrl + "\"" +
                (json == "{}" ? "}" : "," + json.substr(1));
    }
  }
  return "{\"code\":" + JsonString(absl::StatusCodeToString(status.code())) +
         ",\"message\":" + JsonString(std::string(status.message())) + ",\"details\":[" + details +
         "]}";
}

}  // namespace seaplan::server
