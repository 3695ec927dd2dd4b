#include "server/auth/bootstrap.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "seaplan/common/log.h"

namespace seaplan::server::auth {
namespace {

// Writes `content` to `path` readable by the owner only: a temporary file of
// a unique name beside it (mkostemp: created 0600, O_EXCL), fsync'd, then
// renamed over `path`. Processes writing at once each write their own
// temporary file, and a reader sees one whole file or the other.
absl::Status WritePrivateFile(const std::filesystem::path& path, const std::string& content) {
  std::string tmp = (path.parent_path() / ("." + path.filename().string() + ".XXXXXX")).string();
  const int fd = ::mkostemp(tmp.data(), O_CLOEXEC);
  if (fd < 0) {
    return absl::UnavailableError(absl::StrCat("cannot create a temporary file beside ",
                                               path.string(), ": ", std::strerror(errno)));
  }
  const bool written =
      ::write(fd, content.data(), content.size()) == static_cast<ssize_t>(content.size()) &&
      ::fsync(fd) == 0;
  const int saved = errno;
  ::close(fd);
  if (!written || std::rename(tmp.c_str(), path.c_str()) != 0) {
    const int failed = written ? errno : saved;
    ::unlink(tmp.c_str());
    return absl::UnavailableError(
        absl::StrCat("cannot write ", path.string(), ": ", std::strerror(failed)));
  }
  // The rename itself survives a crash once the folder is flushed.
  if (const int dir = ::open(path.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      dir >= 0) {
    (void)::fsync(dir);
    ::close(dir);
  }
  return absl::OkStatus();
}

}  // namespace

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
  if (absl::Status written = WritePrivateFile(result.created_file, created->bearer + "\n");
      !written.ok()) {
    // Nobody could ever present it: revoke it, so the next start makes another.
    (void)tokens.Revoke(created->record.id, auth.Now());
    return written;
  }
  result.created_bearer = std::move(created->bearer);
  return result;
}

}  // namespace seaplan::server::auth
