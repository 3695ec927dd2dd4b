#include "server/core/access_handlers.h"

#include "absl/strings/str_cat.h"
#include "server/core/audit_entry.h"
#include "server/core/convert.h"

namespace seaplan::server {
namespace {

std::optional<auth::Role> RoleFromProto(v1::Role role) {
  switch (role) {
    case v1::ROLE_ADMIN:
      return auth::Role::kAdmin;
    case v1::ROLE_OPERATOR:
      return auth::Role::kOperator;
    case v1::ROLE_VIEWER:
      return auth::Role::kViewer;
    case v1::ROLE_VESSEL:
      return auth::Role::kVessel;
    default:
      return std::nullopt;
  }
}

v1::Role RoleNameToProto(const std::string& name) {
  const std::optional<auth::Role> role = auth::ParseRole(name);
  return role ? RoleToProto(*role) : v1::ROLE_UNSPECIFIED;
}

v1::TokenInfo TokenToProto(const storage::TokenRecord& t) {
  v1::TokenInfo out;
  out.set_token_id(t.id);
  out.set_role(RoleNameToProto(t.role));
  out.set_vessel_id(t.vessel_id);
  out.set_description(t.description);
  out.set_created_by(t.created_by);
  out.set_created_at_ms(t.created_at_ms);
  out.set_expires_at_ms(t.expires_at_ms);
  out.set_revoked_at_ms(t.revoked_at_ms);
  return out;
}

}  // namespace

v1::Role RoleToProto(auth::Role role) {
  switch (role) {
    case auth::Role::kAdmin:
      return v1::ROLE_ADMIN;
    case auth::Role::kOperator:
      return v1::ROLE_OPERATOR;
    case auth::Role::kViewer:
      return v1::ROLE_VIEWER;
    case auth::Role::kVessel:
      return v1::ROLE_VESSEL;
  }
  return v1::ROLE_UNSPECIFIED;
}

absl::StatusOr<v1::WhoAmIResponse> AccessHandlers::WhoAmI(const v1::WhoAmIRequest&,
                                                          const CallContext& ctx) {
  v1::WhoAmIResponse out;
  out.set_token_id(ctx.caller.token_id);
  out.set_role(RoleToProto(ctx.caller.role));
  out.set_vessel_id(ctx.caller.vessel_id);
  return out;
}

absl::StatusOr<v1::CreateTokenResponse> AccessHandlers::CreateToken(
    const v1::CreateTokenRequest& request, const CallContext& ctx) {
  const std::optional<auth::Role> role = RoleFromProto(request.role());
  if (!role) {
    return absl::InvalidArgumentError(
        "role: give ROLE_ADMIN, ROLE_OPERATOR, ROLE_VIEWER or ROLE_VESSEL");
  }
  if (request.expires_in_s() < 0 || request.expires_in_s() > std::int64_t{100} * 365 * 86400) {
    return absl::InvalidArgumentError("expires_in_s: 0 (never) or up to 100 years");
  }
  SEAPLAN_ASSIGN_OR_RETURN(
      auth::Authenticator::NewToken created,
      auth_.Issue(*role, request.vessel_id(), request.description(), request.expires_in_s() * 1000,
                  ctx.caller.token_id, AuditEntry(ctx, "")));
  v1::CreateTokenResponse out;
  *out.mutable_token() = TokenToProto(created.record);
  out.set_bearer(std::move(created.bearer));
  return out;
}

absl::StatusOr<v1::ListTokensResponse> AccessHandlers::ListTokens(const v1::ListTokensRequest&,
                                                                  const CallContext&) {
  SEAPLAN_ASSIGN_OR_RETURN(std::vector<storage::TokenRecord> tokens, tokens_.List());
  v1::ListTokensResponse out;
  for (const auto& t : tokens) *out.add_tokens() = TokenToProto(t);
  return out;
}

absl::StatusOr<v1::RevokeTokenResponse> AccessHandlers::RevokeToken(
    const v1::RevokeTokenRequest& request, const CallContext& ctx) {
  if (request.token_id().empty()) return absl::InvalidArgumentError("token_id is empty");
  const auto audit = AuditEntry(ctx, request.token_id());
  SEAPLAN_ASSIGN_OR_RETURN(storage::TokenRecord revoked,
                           tokens_.Revoke(request.token_id(), auth_.Now(), AuditPointer(audit)));
  v1::RevokeTokenResponse out;
  *out.mutable_token() = TokenToProto(revoked);
  return out;
}

absl::StatusOr<v1::ListAuditEventsResponse> AccessHandlers::ListAuditEvents(
    const v1::ListAuditEventsRequest& request, const CallContext&) {
  const int page_size = request.page_size() == 0 ? 100 : request.page_size();
  if (page_size < 1 || page_size > 1000) {
    return absl::InvalidArgumentError("page_size must be 1..1000 (0: 100)");
  }
  SEAPLAN_ASSIGN_OR_RETURN(std::int64_t after, ParsePageToken(request.page_token()));
  SEAPLAN_ASSIGN_OR_RETURN(storage::Page<storage::AuditRecord> page,
                           audit_.ListAudit(page_size, after));
  v1::ListAuditEventsResponse out;
  for (const auto& r : page.items) {
    v1::AuditEvent* e = out.add_events();
    e->set_seq(r.seq);
    e->set_time_ms(r.time_ms);
    e->set_token_id(r.token_id);
    e->set_role(RoleNameToProto(r.role));
    e->set_vessel_id(r.vessel_id);
    e->set_action(r.action);
    e->set_target(r.target);
    e->set_detail(r.detail);
  }
  out.set_next_page_token(MakePageToken(page.next_after));
  return out;
}

}  // namespace seaplan::server
