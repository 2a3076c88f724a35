// ISO address claim (see n2k_address.h).
#include "can/n2k_address.h"

namespace xr::can {

N2kAddressClaimer::N2kAddressClaimer(const N2kName& name, std::uint8_t preferred)
    : name_(encodeName(name)), fields_(name), address_(preferred > 251 ? 0 : preferred) {}

N2kMessage N2kAddressClaimer::start() { return addressClaim(address_, fields_); }

std::optional<N2kMessage> N2kAddressClaimer::onMessage(const N2kMessage& m) {
  if (m.id.pgn == 59904 && m.data.size() >= 3) {
    const std::uint32_t asked = m.data[0] | (m.data[1] << 8) | (m.data[2] << 16);
    if (asked == 60928 && claimed() && (m.id.destination == 0xFF || m.id.destination == address_))
      return addressClaim(address_, fields_);
    return std::nullopt;
  }
  if (m.id.pgn != 60928 || m.data.size() < 8) return std::nullopt;
  std::uint64_t theirs = 0;
  for (int i = 7; i >= 0; --i) theirs = theirs << 8 | m.data[i];
  if (m.id.source <= 251) taken_[m.id.source] = theirs != name_;
  if (!claimed() || m.id.source != address_ || theirs == name_) return std::nullopt;
  ++conflicts_;
  if (name_ < theirs) return addressClaim(address_, fields_);  // we keep it
  // We lose: the next address nobody claimed, wrapping once round 0..251.
  for (int step = 1; step <= 252; ++step) {
    const std::uint8_t a = static_cast<std::uint8_t>((address_ + step) % 252);
    if (!taken_[a]) {
      address_ = a;
      return addressClaim(address_, fields_);
    }
  }
  address_ = kCannotClaim;
  return addressClaim(kCannotClaim, fields_);  // "cannot claim" announcement
}

}  // namespace xr::can
