// The first admin token: created at the first start (when the database has
// no usable admin token), written to <data dir>/admin.token with mode 0600, or
// taken from a file the operator names (--admin-token-file).
#pragma once

#include <filesystem>
#include <string>

#include "server/auth/authenticator.h"

namespace seaplan::server::auth {

inline constexpr char kAdminTokenFileName[] = "admin.token";

struct BootstrapResult {
  // Set when a token was created now: the token (print it once) and its file.
  std::string created_bearer;
  std::filesystem::path created_file;
};

// `admin_token_file` non-empty: import the token it holds (see
// Authenticator::ImportAdmin). Otherwise, when no admin token is usable
// (none yet, or all revoked or expired), issue one and write it to data_dir/admin.token (0600;
// replaced atomically).
absl::StatusOr<BootstrapResult> EnsureAdminToken(const Authenticator& auth,
                                                 storage::TokenRepository& tokens,
                                                 const std::string& admin_token_file,
                                                 const std::filesystem::path& data_dir);

// Reads a token file: its first line, trimmed. NotFound / InvalidArgument
// saying which file.
absl::StatusOr<std::string> ReadTokenFile(const std::filesystem::path& path);

}  // namespace seaplan::server::auth
