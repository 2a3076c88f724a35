#pragma once
// The boat's position on NMEA 2000, for the weather forecast
// (docs/integrations.md "Weather"). Field layouts follow the canboat PGN
// database (canboat/canboat, pgns.json), the same source as n2k_codec.h:
//
//   129025 Position, Rapid Update (single frame): latitude s32 1e-7 deg,
//          longitude s32 1e-7 deg
//   129029 GNSS Position Data (fast packet, 43 bytes with no reference
//          stations): SID u8, date u16 days since 1970, time u32 1e-4 s,
//          latitude s64 1e-16 deg, longitude s64 1e-16 deg, altitude s64
//          1e-6 m, GNSS type (low nibble) and method (high nibble), integrity,
//          satellites u8, HDOP s16 0.01, PDOP s16 0.01, geoidal separation
//          s32 0.01 m, reference stations u8
#include <cstdint>
#include <optional>

#include "can/n2k_codec.h"

namespace xr::can {

struct N2kPosition {
  double latitudeDeg = 0.0;   // north positive
  double longitudeDeg = 0.0;  // east positive
};

// A position from 129025 or 129029; nullopt for other PGNs, a field "not
// available", a value out of range, or a 129029 whose method says there is
// no fix (0, "no GNSS") or a simulated one (8).
std::optional<N2kPosition> decodePosition(const N2kMessage& m);

// The simulated GNSS receiver's messages (and the tests' encoder).
N2kMessage positionRapid(std::uint8_t source, double latitudeDeg, double longitudeDeg);
// method: canboat's GNS_METHOD (1 = GNSS fix).
N2kMessage gnssPosition(std::uint8_t source, std::uint8_t sid, double latitudeDeg, double longitudeDeg,
                        std::uint8_t method = 1);

}  // namespace xr::can
