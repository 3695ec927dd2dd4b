// AccessService (tokens, the audit log) and the audit trail every
// transport writes through after an audited call.
#pragma once

#include <google/protobuf/message.h>

#include <string_view>

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

  // After a successful call of `method`: when the access table marks it
  // audited, appends who (ctx.caller), what (the method), on what (a
  // mission_id of the request or the response, else a chart_id, else a
  // token_id, at the top or one message down) and why (a `reason` field).
  // A failed write is logged, not returned: the call has already happened.
  void RecordIfAudited(std::string_view method, const CallContext& ctx,
                       const google::protobuf::Message& request,
                       const google::protobuf::Message& response);

 private:
  const auth::Authenticator& auth_;
  storage::TokenRepository& tokens_;
  storage::AuditRepository& audit_;
};

v1::Role RoleToProto(auth::Role role);

}  // namespace seaplan::server
