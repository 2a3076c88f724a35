#pragma once
// DVCC: a Victron GX's charge voltage and current for this charger
// (/Link/ChargeVoltage, /Link/ChargeCurrent on our GX service, relayed by
// venus/dbus-xregulator through POST /api/dvcc). They go the BMS limits'
// way (core/bms_limits.h): the same limiter, the same BmsStaleS, the same
// fallback. They sit BESIDE a BMS's limits (CAN, or the GX's battery over
// MQTT): each tick the lower of each limit wins, so DVCC can only lower
// what a BMS allows and never raises our own limits (docs/integrations.md
// "Victron GX").
#include <algorithm>
#include <cmath>
#include <string_view>

#include "core/bms_limits.h"

namespace xr {

// The plausible range of each DVCC value: the BMS decoders' own (a 48 V
// class pack charges to ~58 V; 2000 A is MaximumAllowedBatteryAmps' ceiling).
inline constexpr double kDvccMinV = 8.0;
inline constexpr double kDvccMaxV = 70.0;
inline constexpr double kDvccMaxA = 2000.0;

// Why a DVCC value is refused; empty = acceptable. NaN here means "the GX
// did not send it", which is allowed (it is then not a limit).
constexpr std::string_view dvccVoltageRefusal(double v) {
  if (v != v) return {};
  if (!(v >= kDvccMinV && v <= kDvccMaxV)) return "ChargeVoltage outside 8 to 70 V";
  return {};
}
constexpr std::string_view dvccCurrentRefusal(double a) {
  if (a != a) return {};
  if (!(a >= 0.0 && a <= kDvccMaxA)) return "ChargeCurrent outside 0 to 2000 A";
  return {};
}

// The BMS's limits with DVCC's beside them (control thread, each tick).
//   - no DVCC yet: the BMS's, unchanged
//   - no BMS: DVCC's alone (a missing ChargeCurrent then means
//     BmsFallbackCapA, as for a BMS that sends no CCL)
//   - both: the lower voltage, the lower current (a BMS without a CCL keeps
//     the fallback cap: DVCC never lifts it), the BMS's other fields, and the
//     older stamp, so either source going silent makes the pair stale.
inline BmsLimits withDvcc(BmsLimits b, const BmsLimits& d) noexcept {
  if (d.source == BmsSource::None) return b;
  if (b.source == BmsSource::None) return d;
  if (std::isnan(b.cvlV) || (!std::isnan(d.cvlV) && d.cvlV < b.cvlV)) b.cvlV = d.cvlV;
  if (!std::isnan(b.cclA) && !std::isnan(d.cclA)) b.cclA = std::min(b.cclA, d.cclA);
  b.stamp = (b.stamp == 0 || d.stamp == 0) ? 0 : std::min(b.stamp, d.stamp);
  return b;
}

}  // namespace xr
