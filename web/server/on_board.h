#pragma once
// Who is on board (docs/security.md "Pairing without a terminal"): a
// code-less pairing window is for a person on the boat, so only a request
// from this machine (loopback), from a link-local address, or from an address
// on one of the board's own subnets may use it. A device on another network
// (a marina's Wi-Fi routed to the boat's) is refused, however it reaches the
// port. A router between two of the boat's own networks makes the second one
// "elsewhere": the owner then pairs with a code.
#include <boost/asio/ip/address.hpp>
#include <string>
#include <vector>

namespace xr::web {

struct BoardSubnet {
  std::string interface;  // "wlan0"
  boost::asio::ip::address address;
  unsigned prefixLength = 0;  // 24 for 255.255.255.0
};

// The addresses and prefixes of the board's interfaces that are up
// (getifaddrs), loopback left out.
std::vector<BoardSubnet> boardSubnets();

// True when peer is loopback, link-local (169.254.0.0/16, fe80::/10) or on
// one of subnets (an IPv4-mapped IPv6 peer counts as its IPv4 address).
bool onBoard(const boost::asio::ip::address& peer, const std::vector<BoardSubnet>& subnets);

// "wlan0 192.168.4.1/24, eth0 fe80::1/64" for the start log; "none" when empty.
std::string subnetsText(const std::vector<BoardSubnet>& subnets);

// "192.168.4.20" or "[::1]": an address as it is written before ":port".
std::string addressText(const boost::asio::ip::address& a);
// "host:port" with an IPv6 literal in brackets ("[::1]:8080").
std::string hostPortText(const std::string& host, unsigned port);

}  // namespace xr::web
