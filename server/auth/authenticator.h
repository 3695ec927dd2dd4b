// Turns a presented credential into a Caller, and issues, imports and
// revokes tokens over storage's TokenRepository. The transports only take
// the credential out of their request (gRPC metadata `authorization`, the
// HTTP `Authorization` header) and map the status this returns:
// Unauthenticated (no, malformed, unknown, wrong, expired or revoked token)
// or PermissionDenied (the role may not call the method).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "seaplan/storage/repositories.h"
#include "server/auth/policy.h"
#include "server/auth/token.h"

namespace seaplan::server::auth {

class Authenticator {
 public:
  using Clock = std::function<storage::TimestampMs()>;
  // `now` defaults to the system clock (ms since the epoch).
  explicit Authenticator(storage::TokenRepository& tokens, Clock now = nullptr);

  // `authorization`: the header's value, "Bearer <token>" (empty: none sent).
  absl::StatusOr<Caller> Authenticate(std::string_view authorization) const;
  // Authenticate, then Authorize for `method` ("Service/Method").
  absl::StatusOr<Caller> Check(std::string_view method, std::string_view authorization) const;
  // The caller of an already-presented bare token (no "Bearer ").
  absl::StatusOr<Caller> AuthenticateToken(std::string_view token) const;

  struct NewToken {
    storage::TokenRecord record;
    std::string bearer;  // shown once
  };
  // A new token. `expires_in_ms` 0: never expires. InvalidArgument for a
  // vessel token without a vessel id or another role with one. `audit`
  // (the creating call's row) is stored with the token, in its transaction,
  // naming the new token as its target.
  absl::StatusOr<NewToken> Issue(Role role, const std::string& vessel_id,
                                 const std::string& description, std::int64_t expires_in_ms,
                                 const std::string& created_by,
                                 std::optional<storage::AuditRecord> audit = std::nullopt) const;
  // A new admin token (never expiring, no creator) unless a usable one is
  // stored: nullopt then, and nothing is stored. Servers starting at once
  // on one database create one between them
  // (storage::TokenRepository::InsertFirstAdmin).
  absl::StatusOr<std::optional<NewToken>> IssueFirstAdmin(const std::string& description) const;
  // Stores `bearer` (a token of our format, e.g. read from a file the
  // operator wrote) as an admin token unless its id is stored already; when
  // it is, the stored hash must match (else FailedPrecondition).
  absl::Status ImportAdmin(std::string_view bearer, const std::string& description) const;

  storage::TimestampMs Now() const { return now_(); }

 private:
  // A fresh token's record (not stored) and its bearer form.
  absl::StatusOr<NewToken> Generate(Role role, const std::string& vessel_id,
                                    const std::string& description, std::int64_t expires_in_ms,
                                    const std::string& created_by) const;

  storage::TokenRepository& tokens_;
  Clock now_;
};

}  // namespace seaplan::server::auth
