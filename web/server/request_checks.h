#pragma once
// Checks on who a request claims to be for, before any route sees it
// (DNS rebinding).
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

// What is wrong with a request's Host header fields, or empty when nothing
// (RFC 9112 3.2: an HTTP/1.1 request has exactly one Host; a field that is
// there names a host, so it is not empty). An HTTP/1.0 request may have none
// (old tools). `count`: how many Host fields; `value`: the first one's.
std::string_view hostHeaderProblem(std::size_t count, std::string_view value, unsigned httpVersion);

// host: the Host header value (may carry :port). Empty is allowed (an
// HTTP/1.0 request without one; hostHeaderProblem refuses the rest). machineName: gethostname() (tests pass
// their own).
bool hostAllowed(std::string_view host, const std::vector<std::string>& allowedHosts,
                 std::string_view machineName);

// origin: the Origin header (empty: not a browser, allowed); host: the Host header.
bool originAllowed(std::string_view origin, std::string_view host,
                   const std::vector<std::string>& allowedOrigins);

// This machine's hostname, read once.
const std::string& machineHostname();

}  // namespace xr::web
