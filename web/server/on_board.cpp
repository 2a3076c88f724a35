#include "web/server/on_board.h"

#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <optional>

namespace xr::web {

namespace ip = boost::asio::ip;

namespace {

unsigned prefixOf(const sockaddr* mask) {
  if (!mask) return 0;
  const unsigned char* bytes = nullptr;
  std::size_t n = 0;
  if (mask->sa_family == AF_INET) {
    bytes = reinterpret_cast<const unsigned char*>(&reinterpret_cast<const sockaddr_in*>(mask)->sin_addr);
    n = 4;
  } else if (mask->sa_family == AF_INET6) {
    bytes = reinterpret_cast<const unsigned char*>(&reinterpret_cast<const sockaddr_in6*>(mask)->sin6_addr);
    n = 16;
  }
  unsigned bits = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (int b = 7; b >= 0; --b) bits += (bytes[i] >> b) & 1u;
  return bits;
}

std::optional<ip::address> addressOf(const sockaddr* sa) {
  if (!sa) return std::nullopt;
  if (sa->sa_family == AF_INET) {
    std::array<unsigned char, 4> b{};
    const auto* in = reinterpret_cast<const sockaddr_in*>(sa);
    std::memcpy(b.data(), &in->sin_addr, 4);
    return ip::address(ip::address_v4(b));
  }
  if (sa->sa_family == AF_INET6) {
    std::array<unsigned char, 16> b{};
    const auto* in6 = reinterpret_cast<const sockaddr_in6*>(sa);
    std::memcpy(b.data(), &in6->sin6_addr, 16);
    return ip::address(ip::address_v6(b, in6->sin6_scope_id));
  }
  return std::nullopt;
}

// The address as bytes, an IPv4-mapped IPv6 one as its IPv4 form.
ip::address plain(const ip::address& a) {
  if (a.is_v6() && a.to_v6().is_v4_mapped()) return ip::make_address_v4(ip::v4_mapped, a.to_v6());
  return a;
}

bool samePrefix(const ip::address& x, const ip::address& y, unsigned bits) {
  if (x.is_v4() != y.is_v4()) return false;
  std::array<unsigned char, 16> a{}, b{};
  std::size_t n = 4;
  if (x.is_v4()) {
    const auto ax = x.to_v4().to_bytes(), by = y.to_v4().to_bytes();
    std::copy(ax.begin(), ax.end(), a.begin());
    std::copy(by.begin(), by.end(), b.begin());
  } else {
    a = x.to_v6().to_bytes();
    b = y.to_v6().to_bytes();
    n = 16;
  }
  if (bits > n * 8) bits = static_cast<unsigned>(n * 8);
  for (std::size_t i = 0; i < n && bits > 0; ++i) {
    const unsigned take = bits >= 8 ? 8 : bits;
    const unsigned char mask = static_cast<unsigned char>(0xFFu << (8 - take));
    if ((a[i] & mask) != (b[i] & mask)) return false;
    bits -= take;
  }
  return true;
}

}  // namespace

std::vector<BoardSubnet> boardSubnets() {
  std::vector<BoardSubnet> out;
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return out;
  std::unique_ptr<ifaddrs, decltype(&freeifaddrs)> guard(list, &freeifaddrs);
  for (const ifaddrs* i = list; i; i = i->ifa_next) {
    if (!(i->ifa_flags & IFF_UP) || (i->ifa_flags & IFF_LOOPBACK)) continue;
    const auto a = addressOf(i->ifa_addr);
    if (!a) continue;
    out.push_back({i->ifa_name ? i->ifa_name : "", *a, prefixOf(i->ifa_netmask)});
  }
  return out;
}

bool onBoard(const ip::address& peerIn, const std::vector<BoardSubnet>& subnets) {
  const ip::address peer = plain(peerIn);
  if (peer.is_loopback()) return true;
  if (peer.is_v4()) {
    const auto b = peer.to_v4().to_bytes();
    if (b[0] == 169 && b[1] == 254) return true;  // RFC 3927 link-local
  } else if (peer.to_v6().is_link_local()) {
    return true;  // fe80::/10: it cannot have crossed a router
  }
  for (const auto& s : subnets)
    if (s.prefixLength > 0 && samePrefix(peer, plain(s.address), s.prefixLength)) return true;
  return false;
}

std::string addressText(const ip::address& a) {
  return a.is_v6() ? "[" + a.to_string() + "]" : a.to_string();
}

std::string hostPortText(const std::string& host, unsigned port) {
  const bool v6 = host.find(':') != std::string::npos && !host.starts_with("[");
  return (v6 ? "[" + host + "]" : host) + ":" + std::to_string(port);
}

std::string subnetsText(const std::vector<BoardSubnet>& subnets) {
  std::string out;
  for (const auto& s : subnets)
    out += (out.empty() ? "" : ", ") + s.interface + " " + s.address.to_string() + "/" +
           std::to_string(s.prefixLength);
  return out.empty() ? "none" : out;
}

}  // namespace xr::web
