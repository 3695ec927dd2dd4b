#include "server/auth/bootstrap.h"

#include <sys/stat.h>

#include <cstdlib>
#include <fstream>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "seaplan/common/file_replace.h"
#include "seaplan/common/log.h"

namespace seaplan::server::auth {

absl::StatusOr<std::string> ReadTokenFile(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) return absl::NotFoundError(absl::StrCat("cannot read token file ", path.string()));
  std::string line;
  std::getline(in, line);
  const std::string token(absl::StripAsciiWhitespace(line));
  if (token.empty()) {
    return absl::InvalidArgumentError(absl::StrCat("token file ", path.string(), " is empty"));
  }
  return token;
}

absl::StatusOr<BootstrapResult> EnsureAdminToken(const Authenticator& auth,
                                                 storage::TokenRepository& tokens,
                                                 const std::string& admin_token_file,
                                                 const std::filesystem::path& data_dir) {
  BootstrapResult result;
  if (!admin_token_file.empty()) {
    SEAPLAN_ASSIGN_OR_RETURN(std::string token, ReadTokenFile(admin_token_file));
    struct stat st {};
    if (::stat(admin_token_file.c_str(), &st) == 0 && (st.st_mode & 077) != 0) {
      log::Warn("admin token file {} is readable by others (mode {:o}); chmod 600 it",
                admin_token_file, st.st_mode & 0777);
    }
    absl::Status imported = auth.ImportAdmin(token, "from --admin-token-file");
    if (!imported.ok()) {
      return absl::Status(imported.code(),
                          absl::StrCat(admin_token_file, ": ", imported.message()));
    }
    return result;
  }
  // One transaction checks for a usable admin token and stores the new one:
  // of servers starting at once on one database, one creates it.
  SEAPLAN_ASSIGN_OR_RETURN(std::optional<Authenticator::NewToken> created,
                           auth.IssueFirstAdmin("first admin token"));
  if (!created) return result;
  std::error_code ec;
  std::filesystem::create_directories(data_dir, ec);
  result.created_file = data_dir / kAdminTokenFileName;
  // Owner-only from creation, flushed: a crash must not leave a token file
  // that is empty or readable by others.
  if (absl::Status written = ReplaceFile(result.created_file, created->bearer + "\n",
                                         {.owner_only = true, .durable = true});
      !written.ok()) {
    // Nobody could ever present it: revoke it, so the next start makes another.
    (void)tokens.Revoke(created->record.id, auth.Now());
    return written;
  }
  result.created_bearer = std::move(created->bearer);
  return result;
}

}  // namespace seaplan::server::auth
