// Protobuf messages to and from the gateway's JSON (Protobuf's canonical
// JSON mapping: lowerCamelCase names, unknown fields an error, fields at
// their default printed too). Kept apart from the gateway so the fuzz
// target (tests/fuzz) exercises exactly what a request body goes through.
#pragma once

#include <google/protobuf/message.h>

#include <string>

#include "seaplan/common/status.h"

namespace seaplan::server {

// An empty body is the empty message. InvalidArgument naming the message
// type and the parser's complaint otherwise.
absl::Status MessageFromJson(const std::string& body, google::protobuf::Message* message);

// Internal when the message cannot be printed.
absl::Status MessageToJson(const google::protobuf::Message& message, std::string* out);

}  // namespace seaplan::server
