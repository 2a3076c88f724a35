#pragma once
// Bearer-token checks for the web API (docs/security.md).
#include <string_view>

namespace xr::web {

// Compares in time that depends only on the lengths, never on where the first
// difference is, so a LAN attacker cannot guess the token byte by byte.
bool constantTimeEquals(std::string_view a, std::string_view b);

enum class AuthResult {
  Ok,         // token matches
  Missing,    // no Authorization header (or not "Bearer ..."): 401
  Forbidden,  // a token that does not match: 403
};

// authorization: the Authorization header value (may be empty);
// queryToken: ?token=... (WebSocket upgrades from browsers cannot set headers).
// The token of an "Authorization: Bearer <token>" value; empty when absent.
std::string_view bearerToken(std::string_view authorization);

AuthResult checkBearer(std::string_view authorization, std::string_view queryToken,
                       std::string_view expected);

}  // namespace xr::web
