#include "server/auth/csrf.h"

#include <openssl/evp.h>
#include <openssl/hmac.h>

#include <array>

#include "absl/strings/escaping.h"
#include "server/auth/token.h"

namespace seaplan::server::auth {

std::string CsrfTokenFor(std::string_view bearer) {
  static constexpr std::string_view kPurpose = "seaplan console csrf v1";
  std::array<unsigned char, EVP_MAX_MD_SIZE> mac{};
  unsigned int length = 0;
  HMAC(EVP_sha256(), bearer.data(), static_cast<int>(bearer.size()),
       reinterpret_cast<const unsigned char*>(kPurpose.data()), kPurpose.size(), mac.data(),
       &length);
  return absl::WebSafeBase64Escape(
      absl::string_view(reinterpret_cast<const char*>(mac.data()), length));
}

bool CsrfTokenMatches(std::string_view bearer, std::string_view presented) {
  return !bearer.empty() && EqualConstantTime(CsrfTokenFor(bearer), presented);
}

}  // namespace seaplan::server::auth
