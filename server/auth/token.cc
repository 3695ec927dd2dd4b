#include "server/auth/token.h"

#include <openssl/crypto.h>
#include <openssl/rand.h>
#include <openssl/sha.h>

#include <array>
#include <cstdint>

#include "absl/strings/ascii.h"
#include "absl/strings/escaping.h"
#include "absl/strings/str_cat.h"

namespace seaplan::server::auth {
namespace {

constexpr char kPrefix[] = "seaplan_";
constexpr std::size_t kPrefixChars = sizeof(kPrefix) - 1;
constexpr std::size_t kIdBytes = 8;
constexpr std::size_t kSecretBytes = 32;
constexpr std::size_t kIdChars = 2 * kIdBytes;
// base64url without padding of 32 bytes.
constexpr std::size_t kSecretChars = 43;

bool IsBase64Url(char c) {
  return absl::ascii_isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
}

}  // namespace

absl::StatusOr<GeneratedToken> GenerateToken() {
  std::array<unsigned char, kIdBytes + kSecretBytes> bytes{};
  if (RAND_bytes(bytes.data(), static_cast<int>(bytes.size())) != 1) {
    return absl::InternalError("cannot draw random bytes for a token (OpenSSL RAND_bytes failed)");
  }
  // Debian's Abseil has its own string_view (not std::string_view).
  const absl::string_view raw(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  GeneratedToken t;
  t.id = absl::BytesToHexString(raw.substr(0, kIdBytes));
  const std::string secret = absl::WebSafeBase64Escape(raw.substr(kIdBytes));
  t.secret_hash = HashSecret(secret);
  t.bearer = absl::StrCat(kPrefix, t.id, "_", secret);
  OPENSSL_cleanse(bytes.data(), bytes.size());
  return t;
}

absl::StatusOr<ParsedToken> ParseToken(std::string_view token) {
  if (!token.starts_with(std::string_view(kPrefix, kPrefixChars))) {
    return absl::UnauthenticatedError("malformed token: it does not start with 'seaplan_'");
  }
  token.remove_prefix(kPrefixChars);
  if (token.size() != kIdChars + 1 + kSecretChars || token[kIdChars] != '_') {
    return absl::UnauthenticatedError("malformed token: wrong length or layout");
  }
  ParsedToken p{std::string(token.substr(0, kIdChars)), std::string(token.substr(kIdChars + 1))};
  for (char c : p.id) {
    if (!absl::ascii_isxdigit(static_cast<unsigned char>(c)) || absl::ascii_isupper(c)) {
      return absl::UnauthenticatedError("malformed token: its id is not lower-case hex");
    }
  }
  for (char c : p.secret) {
    if (!IsBase64Url(c))
      return absl::UnauthenticatedError("malformed token: bad secret characters");
  }
  return p;
}

std::string HashSecret(std::string_view secret) {
  std::array<unsigned char, SHA256_DIGEST_LENGTH> digest{};
  SHA256(reinterpret_cast<const unsigned char*>(secret.data()), secret.size(), digest.data());
  return absl::BytesToHexString(
      absl::string_view(reinterpret_cast<const char*>(digest.data()), digest.size()));
}

bool EqualConstantTime(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  return CRYPTO_memcmp(a.data(), b.data(), a.size()) == 0;
}

}  // namespace seaplan::server::auth
