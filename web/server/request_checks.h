#pragma once
// Checks on who a request claims to be for, before any route sees it
// (issue 26, item 12: DNS rebinding).
//
// DNS rebinding: a page on evil.example makes its own name resolve to the
// boat's board, so the owner's browser sends the page's requests here as
// "same origin". The Host header then still says evil.example: only names
// this machine answers to are accepted. Origin: on /ws and every write, a
// browser's Origin must be http(s):// plus the Host (or a configured origin).
#include <string>
#include <string_view>
#include <vector>

namespace xr::web {

// host: the Host header value (may carry :port). Empty is allowed (HTTP/1.0
// tools). machineName: gethostname() (tests pass their own).
bool hostAllowed(std::string_view host, const std::vector<std::string>& allowedHosts,
                 std::string_view machineName);

// origin: the Origin header (empty: not a browser, allowed); host: the Host header.
bool originAllowed(std::string_view origin, std::string_view host,
                   const std::vector<std::string>& allowedOrigins);

// This machine's hostname, read once.
const std::string& machineHostname();

}  // namespace xr::web
