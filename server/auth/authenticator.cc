#include "server/auth/authenticator.h"

#include <chrono>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"

namespace seaplan::server::auth {
namespace {

// (Debian's Abseil string helpers take its own string_view, not std's.)
std::string_view Trim(std::string_view s) {
  while (!s.empty() && absl::ascii_isspace(static_cast<unsigned char>(s.front())))
    s.remove_prefix(1);
  while (!s.empty() && absl::ascii_isspace(static_cast<unsigned char>(s.back())))
    s.remove_suffix(1);
  return s;
}

bool StartsWithIgnoreCase(std::string_view text, std::string_view prefix) {
  if (text.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    if (absl::ascii_tolower(static_cast<unsigned char>(text[i])) !=
        absl::ascii_tolower(static_cast<unsigned char>(prefix[i]))) {
      return false;
    }
  }
  return true;
}

}  // namespace

Authenticator::Authenticator(storage::TokenRepository& tokens, Clock now)
    : tokens_(tokens), now_(std::move(now)) {
  if (!now_) {
    now_ = [] {
      return std::chrono::duration_cast<std::chrono::milliseconds>(
                 std::chrono::system_clock::now().time_since_epoch())
          .count();
    };
  }
}

absl::StatusOr<Caller> Authenticator::Authenticate(std::string_view authorization) const {
  authorization = Trim(authorization);
  if (authorization.empty()) {
    return absl::UnauthenticatedError(
        "no credentials: send the header 'Authorization: Bearer <token>' (the seaplan CLI and "
        "seaplan-sim: --token, --token-file or SEAPLAN_TOKEN)");
  }
  constexpr std::string_view kScheme = "Bearer ";
  if (authorization.size() <= kScheme.size() || !StartsWithIgnoreCase(authorization, kScheme)) {
    return absl::UnauthenticatedError("the Authorization header must read 'Bearer <token>'");
  }
  return AuthenticateToken(Trim(authorization.substr(kScheme.size())));
}

absl::StatusOr<Caller> Authenticator::AuthenticateToken(std::string_view token) const {
  SEAPLAN_ASSIGN_OR_RETURN(ParsedToken parsed, ParseToken(token));
  absl::StatusOr<storage::TokenRecord> record = tokens_.Get(parsed.id);
  if (absl::IsNotFound(record.status())) {
    return absl::UnauthenticatedError(absl::StrCat("unknown token '", parsed.id, "'"));
  }
  if (!record.ok()) {
    // The database failed: say so rather than "unauthenticated".
    return absl::UnavailableError(
        absl::StrCat("cannot check the token: ", record.status().message()));
  }
  if (!EqualConstantTime(HashSecret(parsed.secret), record->secret_hash)) {
    return absl::UnauthenticatedError(absl::StrCat("wrong secret for token '", parsed.id, "'"));
  }
  // The rule a stored first admin token is checked by too
  // (storage::internal::UsableAdminTokenQuery): keep the two alike.
  if (record->revoked_at_ms != 0) {
    return absl::UnauthenticatedError(absl::StrCat("token '", parsed.id, "' was revoked"));
  }
  if (record->expires_at_ms != 0 && now_() >= record->expires_at_ms) {
    return absl::UnauthenticatedError(absl::StrCat("token '", parsed.id, "' has expired"));
  }
  const std::optional<Role> role = ParseRole(record->role);
  if (!role) {
    return absl::InternalError(
        absl::StrCat("token '", parsed.id, "' has an unknown role '", record->role, "'"));
  }
  return Caller{record->id, *role, record->vessel_id};
}

absl::StatusOr<Caller> Authenticator::Check(std::string_view method,
                                            std::string_view authorization) const {
  SEAPLAN_ASSIGN_OR_RETURN(Caller caller, Authenticate(authorization));
  SEAPLAN_RETURN_IF_ERROR(Authorize(caller, method));
  return caller;
}

absl::StatusOr<Authenticator::NewToken> Authenticator::Generate(
    Role role, const std::string& vessel_id, const std::string& description,
    std::int64_t expires_in_ms, const std::string& created_by) const {
  if ((role == Role::kVessel) != !vessel_id.empty()) {
    return absl::InvalidArgumentError(role == Role::kVessel
                                          ? "a vessel token needs the vessel id it is bound to"
                                          : "only a vessel token is bound to a vessel id");
  }
  if (expires_in_ms < 0) {
    return absl::InvalidArgumentError("a token's lifetime must not be negative");
  }
  SEAPLAN_ASSIGN_OR_RETURN(GeneratedToken generated, GenerateToken());
  NewToken out;
  storage::TokenRecord& r = out.record;
  r.id = generated.id;
  r.secret_hash = generated.secret_hash;
  r.role = std::string(RoleName(role));
  r.vessel_id = vessel_id;
  r.description = description;
  r.created_by = created_by;
  r.created_at_ms = now_();
  r.expires_at_ms = expires_in_ms == 0 ? 0 : r.created_at_ms + expires_in_ms;
  out.bearer = std::move(generated.bearer);
  return out;
}

absl::StatusOr<Authenticator::NewToken> Authenticator::Issue(
    Role role, const std::string& vessel_id, const std::string& description,
    std::int64_t expires_in_ms, const std::string& created_by,
    std::optional<storage::AuditRecord> audit) const {
  SEAPLAN_ASSIGN_OR_RETURN(NewToken out,
                           Generate(role, vessel_id, description, expires_in_ms, created_by));
  if (audit) audit->target = out.record.id;
  SEAPLAN_RETURN_IF_ERROR(tokens_.Insert(out.record, audit ? &*audit : nullptr));
  return out;
}

absl::StatusOr<std::optional<Authenticator::NewToken>> Authenticator::IssueFirstAdmin(
    const std::string& description) const {
  SEAPLAN_ASSIGN_OR_RETURN(NewToken out, Generate(Role::kAdmin, "", description, 0, ""));
  SEAPLAN_ASSIGN_OR_RETURN(bool stored, tokens_.InsertFirstAdmin(out.record, now_()));
  if (!stored) return std::nullopt;
  return out;
}

absl::Status Authenticator::ImportAdmin(std::string_view bearer,
                                        const std::string& description) const {
  absl::StatusOr<ParsedToken> parsed = ParseToken(Trim(bearer));
  if (!parsed.ok()) {
    return absl::InvalidArgumentError(
        absl::StrCat("admin token: ", parsed.status().message(),
                     " (expected seaplan_<16 hex digits>_<43 base64url characters>)"));
  }
  const std::string hash = HashSecret(parsed->secret);
  absl::StatusOr<storage::TokenRecord> stored = tokens_.Get(parsed->id);
  if (stored.ok()) {
    if (!EqualConstantTime(hash, stored->secret_hash) || stored->role != "admin") {
      return absl::FailedPreconditionError(
          absl::StrCat("admin token: id '", parsed->id,
                       "' is stored with another secret or role; refusing to use it"));
    }
    return absl::OkStatus();
  }
  if (!absl::IsNotFound(stored.status())) return stored.status();
  storage::TokenRecord r;
  r.id = parsed->id;
  r.secret_hash = hash;
  r.role = "admin";
  r.description = description;
  r.created_at_ms = now_();
  absl::Status st = tokens_.Insert(r);
  // Another replica imported it at the same moment.
  if (absl::IsAlreadyExists(st)) return absl::OkStatus();
  return st;
}

}  // namespace seaplan::server::auth
