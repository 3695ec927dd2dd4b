// API tokens: their format, generation and hashing.
//
// A token reads `seaplan_<id>_<secret>`: `id` is 16 hex digits (64 random
// bits, public: it names the token in lists and the audit log), `secret` is
// 43 base64url characters (256 random bits from the OS's CSPRNG through
// OpenSSL). Storage keeps only the hex SHA-256 of the secret; a presented
// token is found by its id and its secret's hash compared in constant time.
#pragma once

#include <string>
#include <string_view>

#include "seaplan/common/status.h"

namespace seaplan::server::auth {

struct GeneratedToken {
  std::string id;
  std::string secret_hash;  // hex SHA-256 of the secret
  std::string bearer;       // the whole token, shown once to its owner
};

struct ParsedToken {
  std::string id;
  std::string secret;
};

// A new random token. Internal when the CSPRNG fails.
absl::StatusOr<GeneratedToken> GenerateToken();

// Splits a presented token. Unauthenticated (saying what is wrong, never
// echoing the secret) when it is not of the format above.
absl::StatusOr<ParsedToken> ParseToken(std::string_view token);

// Hex SHA-256 of `secret` (64 characters).
std::string HashSecret(std::string_view secret);

// `a` == `b` in time that depends only on the lengths.
bool EqualConstantTime(std::string_view a, std::string_view b);

}  // namespace seaplan::server::auth
