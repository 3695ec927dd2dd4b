// The token a client (seaplan, seaplan-sim) presents to the server. No gRPC
// here (the `seaplan` CLI links this without it); token_channel.h makes a
// channel that presents it.
#pragma once

#include <string>

#include "seaplan/common/status.h"

namespace seaplan::client {
// The first given of: `token` (--token), the first line of `token_file`
// (--token-file), env SEAPLAN_TOKEN, the first line of env
// SEAPLAN_TOKEN_FILE's file. Empty when none is given (the server then
// answers UNAUTHENTICATED, saying how to give one). InvalidArgument when a
// named file cannot be read or is empty.
absl::StatusOr<std::string> ResolveToken(const std::string& token, const std::string& token_file);

}  // namespace seaplan::client
