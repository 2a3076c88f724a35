#include "web/server/auth.h"

#include <cctype>

namespace xr::web {

bool constantTimeEquals(std::string_view a, std::string_view b) {
  // Walk the expected length whatever the input; fold the length difference in.
  unsigned diff = a.size() == b.size() ? 0u : 1u;
  const std::size_t n = b.size();
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char ca = i < a.size() ? static_cast<unsigned char>(a[i]) : 0;
    diff |= ca ^ static_cast<unsigned char>(b[i]);
  }
  return diff == 0 && !b.empty();
}

std::string_view bearerToken(std::string_view authorization) {
  constexpr std::string_view kScheme = "bearer ";
  if (authorization.size() < kScheme.size()) return {};
  for (std::size_t i = 0; i < kScheme.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(authorization[i])) != kScheme[i]) return {};
  std::string_view token = authorization.substr(kScheme.size());
  while (!token.empty() && token.front() == ' ') token.remove_prefix(1);
  while (!token.empty() && token.back() == ' ') token.remove_suffix(1);
  return token;
}

AuthResult checkBearer(std::string_view authorization, std::string_view queryToken,
                       std::string_view expected) {
  std::string_view token;
  if (!authorization.empty()) {
    token = bearerToken(authorization);
    if (token.empty()) return AuthResult::Forbidden;
  } else if (!queryToken.empty()) {
    token = queryToken;
  } else {
    return AuthResult::Missing;
  }
  return constantTimeEquals(token, expected) ? AuthResult::Ok : AuthResult::Forbidden;
}

}  // namespace xr::web
