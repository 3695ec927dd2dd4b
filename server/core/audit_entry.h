// The audit row of an audited call (auth::MethodRule::audited): who
// (ctx.caller: token id, role, vessel), what (ctx.method), on what (a
// mission, chart or token id) and when. A handler builds it before its write
// and hands it to storage, which appends it in the write's own transaction
// (storage/repositories.h, "Audited writes"): the change and its row exist
// together or not at all.
#pragma once

#include <optional>
#include <string>

#include "seaplan/storage/repositories.h"
#include "server/core/call_context.h"

namespace seaplan::server {

// nullopt when ctx.method is not audited or the call is the server's own
// work (no token).
std::optional<storage::AuditRecord> AuditEntry(const CallContext& ctx, std::string target,
                                               std::string detail = "");

// The record to pass to a storage write (nullptr when none).
inline const storage::AuditRecord* AuditPointer(const std::optional<storage::AuditRecord>& entry) {
  return entry ? &*entry : nullptr;
}

}  // namespace seaplan::server
