// Position PGNs (see n2k_position.h).
#include "can/n2k_position.h"

#include <cmath>
#include <limits>

#include "can/can_bytes.h"

namespace xr::can {
namespace {

constexpr std::uint32_t kPositionRapid = 129025, kGnssPosition = 129029;
constexpr std::size_t kGnssLength = 43;  // no reference stations
constexpr std::uint8_t kMethodNoFix = 0, kMethodSimulated = 8;
// canboat marks a signed field "not available" with its largest value and
// reserves the next one below for "error".
constexpr std::int32_t kNaS32 = std::numeric_limits<std::int32_t>::max();
constexpr std::int64_t kNaS64 = std::numeric_limits<std::int64_t>::max();

std::optional<N2kPosition> checked(double lat, double lon) {
  if (!std::isfinite(lat) || !std::isfinite(lon) || std::abs(lat) > 90.0 || std::abs(lon) > 180.0)
    return std::nullopt;
  return N2kPosition{lat, lon};
}

std::optional<N2kPosition> rapid(const N2kMessage& m) {
  if (m.data.size() < 8) return std::nullopt;
  const std::int32_t lat = getS32(m.data, 0), lon = getS32(m.data, 4);
  if (lat >= kNaS32 - 1 || lon >= kNaS32 - 1) return std::nullopt;
  return checked(lat * 1e-7, lon * 1e-7);
}

std::optional<N2kPosition> gnss(const N2kMessage& m) {
  if (m.data.size() < 32) return std::nullopt;
  const std::uint8_t method = m.data[31] >> 4;
  if (method == kMethodNoFix || method >= kMethodSimulated) return std::nullopt;
  const std::int64_t lat = getS64(m.data, 7), lon = getS64(m.data, 15);
  if (lat >= kNaS64 - 1 || lon >= kNaS64 - 1) return std::nullopt;
  return checked(static_cast<double>(lat) * 1e-16, static_cast<double>(lon) * 1e-16);
}

}  // namespace

std::optional<N2kPosition> decodePosition(const N2kMessage& m) {
  if (m.id.pgn == kPositionRapid) return rapid(m);
  if (m.id.pgn == kGnssPosition) return gnss(m);
  return std::nullopt;
}

N2kMessage positionRapid(std::uint8_t source, double latitudeDeg, double longitudeDeg) {
  N2kMessage m = blankMessage(kPositionRapid, 2, source, 8);
  putS32(m.data, 0, static_cast<std::int32_t>(std::lround(latitudeDeg * 1e7)));
  putS32(m.data, 4, static_cast<std::int32_t>(std::lround(longitudeDeg * 1e7)));
  return m;
}

N2kMessage gnssPosition(std::uint8_t source, std::uint8_t sid, double latitudeDeg, double longitudeDeg,
                        std::uint8_t method) {
  N2kMessage m = blankMessage(kGnssPosition, 3, source, kGnssLength);
  m.data[0] = sid;
  // Date and time stay "not available": the simulated receiver has no
  // calendar, and the regulator reads only the position.
  putS64(m.data, 7, static_cast<std::int64_t>(std::llround(latitudeDeg * 1e16)));
  putS64(m.data, 15, static_cast<std::int64_t>(std::llround(longitudeDeg * 1e16)));
  m.data[31] = static_cast<std::uint8_t>((method << 4) | 0x0);  // GNSS type 0: GPS
  m.data[32] = 0xFC;        // integrity: no checking (0), reserved bits set
  m.data[33] = 9;           // satellites in use
  putS16(m.data, 34, 90);   // HDOP 0.9
  putS16(m.data, 36, 150);  // PDOP 1.5
  putS32(m.data, 38, 0);    // geoidal separation
  m.data[42] = 0;           // no reference stations
  return m;
}

}  // namespace xr::can
