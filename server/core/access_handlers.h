// AccessService: tokens and the audit log. Token creation and revocation
// store their audit row in their own transaction (audit_entry.h).
#pragma once

#include "seaplan/storage/repositories.h"
#include "seaplan/v1/access.pb.h"
#include "server/auth/authenticator.h"
#include "server/core/call_context.h"

namespace seaplan::server {

class AccessHandlers {
 public:
  AccessHandlers(const auth::Authenticator& auth, storage::TokenRepository& tokens,
                 storage::AuditRepository& audit)
      : auth_(auth), tokens_(tokens), audit_(audit) {}

  absl::StatusOr<v1::WhoAmIResponse> WhoAmI(const v1::WhoAmIRequest& request,
                                            const CallContext& ctx);
  absl::StatusOr<v1::CreateTokenResponse> CreateToken(const v1::CreateTokenRequest& request,
                                                      const CallContext& ctx);
  absl::StatusOr<v1::ListTokensResponse> ListTokens(const v1::ListTokensRequest& request,
                                                    const CallContext& ctx);
  absl::StatusOr<v1::RevokeTokenResponse> RevokeToken(const v1::RevokeTokenRequest& request,
                                                      const CallContext& ctx);
  absl::StatusOr<v1::ListAuditEventsResponse> ListAuditEvents(
      const v1::ListAuditEventsRequest& request, const CallContext& ctx);

 private:
  const auth::Authenticator& auth_;
  storage::TokenRepository& tokens_;
  storage::AuditRepository& audit_;
};

v1::Role RoleToProto(auth::Role role);

}  // namespace seaplan::server
