#include "server/http/status_mapping.h"

#include <google/protobuf/util/json_util.h>

#include "server/core/status_details.h"

namespace seaplan::server {
namespace {

std::string JsonString(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (c < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

}  // namespace

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
