// Host and Origin checks (request_checks.h).
#include "web/server/request_checks.h"

#include <unistd.h>

#include <algorithm>
#include <boost/asio/ip/address.hpp>
#include <cctype>

namespace xr::web {

namespace {

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

// "name:8080" -> "name", "[fe80::1]:80" -> "fe80::1"; a trailing dot of a
// fully qualified name goes too.
std::string_view hostName(std::string_view host) {
  if (host.starts_with('[')) {
    const auto end = host.find(']');
    return end == std::string_view::npos ? std::string_view{} : host.substr(1, end - 1);
  }
  host = host.substr(0, host.find(':'));
  if (host.ends_with('.')) host.remove_suffix(1);
  return host;
}

}  // namespace

std::string_view hostHeaderProblem(std::size_t count, std::string_view value, unsigned httpVersion) {
  if (count > 1) return "more than one Host header";
  if (count == 1 && value.find_first_not_of(" \t") == std::string_view::npos) return "empty Host header";
  if (count == 0 && httpVersion >= 11) return "no Host header";
  return {};
}

bool hostAllowed(std::string_view host, const std::vector<std::string>& allowedHosts,
                 std::string_view machineName) {
  if (host.empty()) return true;
  const std::string_view name = hostName(host);
  if (name.empty()) return false;
  boost::system::error_code ec;
  boost::asio::ip::make_address(std::string(name), ec);
  if (!ec) return true;  // an address typed by hand cannot be rebound
  if (iequals(name, "localhost")) return true;
  if (!machineName.empty()) {
    const std::string_view shortName = machineName.substr(0, machineName.find('.'));
    for (std::string_view own : {machineName, shortName})
      if (iequals(name, own) || (name.size() == own.size() + 6 && iequals(name.substr(0, own.size()), own) &&
                                 iequals(name.substr(own.size()), ".local")))
        return true;
  }
  return std::any_of(allowedHosts.begin(), allowedHosts.end(),
                     [&](const std::string& h) { return iequals(name, hostName(h)); });
}

bool originAllowed(std::string_view origin, std::string_view host,
                   const std::vector<std::string>& allowedOrigins) {
  if (origin.empty()) return true;
  for (const auto& o : allowedOrigins)
    if (iequals(origin, o)) return true;
  // We serve plain HTTP; https is a TLS proxy in front. Any other scheme
  // (or "null" from a sandboxed frame) is not this dashboard.
  std::string_view rest;
  if (origin.size() > 7 && iequals(origin.substr(0, 7), "http://"))
    rest = origin.substr(7);
  else if (origin.size() > 8 && iequals(origin.substr(0, 8), "https://"))
    rest = origin.substr(8);
  else
    return false;
  return !host.empty() && iequals(rest, host);
}

const std::string& machineHostname() {
  static const std::string name = [] {
    char buf[256] = {};
    if (::gethostname(buf, sizeof buf - 1) != 0) return std::string();
    return std::string(buf);
  }();
  return name;
}

}  // namespace xr::web
