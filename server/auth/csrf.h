// The operator console's session, without server-side state: the cookie
// carries the token itself (HttpOnly, so the page's scripts cannot read it;
// SameSite=Strict, so other sites' pages do not send it), and a request
// that relies on the cookie must also carry the CSRF token derived from it
// in a header. A page of another site can neither read the cookie nor
// compute the CSRF token, so it cannot forge a call; any replica can check
// it (nothing is kept in memory), and revoking the token ends the session.
#pragma once

#include <string>
#include <string_view>

namespace seaplan::server::auth {

// base64url(HMAC-SHA256(key = the token, "seaplan console csrf v1")): 43
// characters.
std::string CsrfTokenFor(std::string_view bearer);

// Whether `presented` is the CSRF token of `bearer` (constant time).
bool CsrfTokenMatches(std::string_view bearer, std::string_view presented);

}  // namespace seaplan::server::auth
