#include "client_token.h"

#include <cstdlib>
#include <fstream>

#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"

namespace seaplan::client {
namespace {

absl::StatusOr<std::string> ReadTokenFile(const std::string& path, const char* what) {
  std::ifstream in(path);
  std::string line;
  if (!in || !std::getline(in, line)) {
    return absl::InvalidArgumentError(
        absl::StrCat(what, ": cannot read a token from '", path, "'"));
  }
  std::string token(absl::StripAsciiWhitespace(line));
  if (token.empty()) {
    return absl::InvalidArgumentError(absl::StrCat(what, ": '", path, "' is empty"));
  }
  return token;
}

}  // namespace

absl::StatusOr<std::string> ResolveToken(const std::string& token, const std::string& token_file) {
  if (!token.empty()) return std::string(absl::StripAsciiWhitespace(token));
  if (!token_file.empty()) return ReadTokenFile(token_file, "--token-file");
  if (const char* env = std::getenv("SEAPLAN_TOKEN"); env != nullptr && *env != '\0') {
    return std::string(absl::StripAsciiWhitespace(env));
  }
  if (const char* env = std::getenv("SEAPLAN_TOKEN_FILE"); env != nullptr && *env != '\0') {
    return ReadTokenFile(env, "SEAPLAN_TOKEN_FILE");
  }
  return std::string();
}

}  // namespace seaplan::client
