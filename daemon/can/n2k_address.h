#pragma once
// ISO 11783-5 address claim for our NMEA 2000 node (PGN 60928), pure.
// We claim `preferred` at start. When another node claims our address, the
// smaller NAME keeps it: if ours is smaller we claim again (they move); if
// theirs is, we move to the next free address and claim that. A request for
// address claims (PGN 59904 asking for 60928) is answered with our claim.
// With no address left we stop sending (the "cannot claim" state, 254).
#include <array>
#include <cstdint>
#include <optional>

#include "can/n2k_codec.h"

namespace xr::can {

class N2kAddressClaimer {
 public:
  N2kAddressClaimer(const N2kName& name, std::uint8_t preferred);

  // The claim to send now (at start).
  N2kMessage start();
  // A received message; returns our claim to send in answer, if any.
  std::optional<N2kMessage> onMessage(const N2kMessage& m);

  std::uint8_t address() const { return address_; }
  bool claimed() const { return address_ != kCannotClaim; }
  std::uint32_t conflicts() const { return conflicts_; }
  static constexpr std::uint8_t kCannotClaim = 254;

 private:
  std::uint64_t name_;
  N2kName fields_;
  std::uint8_t address_;
  std::array<bool, 252> taken_{};  // addresses other nodes hold (0..251)
  std::uint32_t conflicts_ = 0;
};

}  // namespace xr::can
