#include "server/http/json_codec.h"

#include <google/protobuf/util/json_util.h>

#include "absl/strings/str_cat.h"

namespace seaplan::server {

absl::Status MessageToJson(const google::protobuf::Message& message, std::string* out) {
  google::protobuf::util::JsonPrintOptions options;
  options.always_print_primitive_fields = true;
  auto st = google::protobuf::util::MessageToJsonString(message, out, options);
  if (!st.ok())
    return absl::InternalError(absl::StrCat("cannot print the response as JSON: ", st.ToString()));
  return absl::OkStatus();
}

absl::Status MessageFromJson(const std::string& body, google::protobuf::Message* message) {
  if (body.empty()) return absl::OkStatus();
  google::protobuf::util::JsonParseOptions options;
  options.ignore_unknown_fields = false;
  auto st = google::protobuf::util::JsonStringToMessage(body, message, options);
  if (!st.ok()) {
    return absl::InvalidArgumentError(absl::StrCat("request body is not a valid ",
                                                   message->GetDescriptor()->full_name(),
                                                   " in JSON: ", std::string(st.message())));
  }
  return absl::OkStatus();
}

}  // namespace seaplan::server
