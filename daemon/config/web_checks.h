#pragma once
// Checks of [web] values that the loader makes, so that a value the web
// server could not use is a configuration error with its key and line, not a
// failure when the daemon is already running (docs/security.md).
#include <cstddef>
#include <string>
#include <string_view>

namespace xr {

// A configured token shorter than this is refused: it could be guessed from
// the marina Wi-Fi. The generated token has 64 hex characters.
inline constexpr std::size_t kMinTokenLength = 16;

// True for an IPv4 or IPv6 address literal ("127.0.0.1", "::", "fe80::1").
// Host names are not resolved: the server binds the address it is given.
bool isNumericListenAddress(std::string_view text);

// Empty when text is a usable --http ADDR:PORT: ADDR an address literal
// (the check [web] listen gets: isNumericListenAddress), "[v6]" for IPv6,
// or empty for every interface; PORT 0..65535. Otherwise the reason.
std::string checkHttpListenText(std::string_view text);

// True for the wildcard addresses that listen on every interface.
bool isEveryInterface(std::string_view listen);

// Empty when token is acceptable in [web] token: empty (generated at first
// start) or at least kMinTokenLength printable ASCII characters without
// spaces (it travels in an HTTP header). Otherwise the reason.
std::string checkTokenText(std::string_view token);

// A short fingerprint of a token for the journal (8 hex digits): enough to
// tell which token a phone has, useless for guessing the token itself.
std::string tokenFingerprint(std::string_view token);

// A warning when token is set and configPath is readable by every user of
// the machine (0644): the token is then no secret. Empty when fine.
std::string tokenFileWarning(const std::string& configPath, std::string_view token);

}  // namespace xr
