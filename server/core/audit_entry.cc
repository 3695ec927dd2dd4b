#include "server/core/audit_entry.h"

#include "server/auth/policy.h"
#include "server/core/convert.h"

namespace seaplan::server {

std::optional<storage::AuditRecord> AuditEntry(const CallContext& ctx, std::string target,
                                               std::string detail) {
  const auth::MethodRule* rule = auth::FindRule(ctx.method);
  if (rule == nullptr || !rule->audited || ctx.caller.internal()) return std::nullopt;
  storage::AuditRecord record;
  record.time_ms = NowMs();
  record.token_id = ctx.caller.token_id;
  record.role = std::string(auth::RoleName(ctx.caller.role));
  record.vessel_id = ctx.caller.vessel_id;
  record.action = ctx.method;
  record.target = std::move(target);
  record.detail = std::move(detail);
  return record;
}

}  // namespace seaplan::server
