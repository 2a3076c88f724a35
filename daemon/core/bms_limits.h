#pragma once
// BmsLimits: what a battery management system says the bank may take, in the
// core's vocabulary. One struct for every source (a BMS on CAN, a Victron GX
// relaying one, ...): the source's decoder fills it off the RT thread and
// posts it through a hand-off like the other slow sensors; the control law
// follows it (docs/integrations.md "CAN"):
//   cvlV          charge voltage limit: a ceiling on the voltage target
//   cclA          charge current limit: a cap on BATTERY current (INA228),
//                 so house loads are still served
//   chargeAllowed false = the BMS asks for no charge (field off, REASON_BMS_DISABLED)
//   warnings      a raised flag ramps the charge down before the BMS opens
// `stamp` is when the limits (CVL/CCL, frame 0x351 on CAN) last arrived: a
// stamp older than BmsStaleS is stale and the law falls back to
// BmsFallbackCapA (REASON_BMS_STALE). Values a source does not send stay NaN.
#include <cstdint>
#include <limits>
#include <string_view>

#include "core/time.h"

namespace xr {

enum class BmsSource : std::uint8_t { None, Can, VictronGx, Sim };

// Warning flags (bit set = the BMS warns). Protocols map their own bits here.
namespace bmswarn {
inline constexpr std::uint32_t HighVoltage = 1u << 0;  // cell or pack voltage high
inline constexpr std::uint32_t LowVoltage = 1u << 1;
inline constexpr std::uint32_t HighTemp = 1u << 2;  // charge or cell temperature high
inline constexpr std::uint32_t LowTemp = 1u << 3;   // too cold to charge fully
inline constexpr std::uint32_t HighChargeCurrent = 1u << 4;
inline constexpr std::uint32_t HighDischargeCurrent = 1u << 5;
inline constexpr std::uint32_t CellImbalance = 1u << 6;
inline constexpr std::uint32_t Internal = 1u << 7;  // BMS internal / communication fault
// The warnings that ask a charger to back off (the others are shown only).
inline constexpr std::uint32_t ChargeRampDown =
    HighVoltage | HighTemp | LowTemp | HighChargeCurrent | Internal;
}  // namespace bmswarn

// Why a decoder dropped a frame (the BmsBadFrames event's detail).
enum class BmsReject : std::uint8_t {
  None,
  ShortDlc,
  CvlRange,
  CclRange,
  DclRange,
  SocRange,
  VoltageRange,
  TempRange,
  CellVoltageRange,
};
constexpr std::string_view bmsRejectText(BmsReject r) {
  switch (r) {
    case BmsReject::None:
      return "none";
    case BmsReject::ShortDlc:
      return "short DLC";
    case BmsReject::CvlRange:
      return "CVL out of range";
    case BmsReject::CclRange:
      return "CCL out of range";
    case BmsReject::DclRange:
      return "DCL out of range";
    case BmsReject::SocRange:
      return "SoC/SoH out of range";
    case BmsReject::VoltageRange:
      return "voltage out of range";
    case BmsReject::TempRange:
      return "temperature out of range";
    case BmsReject::CellVoltageRange:
      return "cell voltage out of range";
  }
  return "?";
}

inline constexpr double kBmsNoValue = std::numeric_limits<double>::quiet_NaN();

struct BmsLimits {
  double cvlV = kBmsNoValue;    // charge voltage limit, V
  double cclA = kBmsNoValue;    // charge current limit, A (battery current)
  double dclA = kBmsNoValue;    // discharge current limit, A (shown only)
  double socPct = kBmsNoValue;  // state of charge, %
  double sohPct = kBmsNoValue;  // state of health, %
  double tempC = kBmsNoValue;   // battery temperature, degC (feeds the battery-temperature input)
  double voltageV = kBmsNoValue, currentA = kBmsNoValue;  // as the BMS measures them (shown only)
  // The highest and lowest cell voltage, V (REC's 0x373): a high cell ramps
  // the charge down before the pack reaches CVL (BmsCellHighV); the rest
  // of that frame (lowest cell, cell temperatures) is shown only.
  double cellMaxV = kBmsNoValue, cellMinV = kBmsNoValue;
  double cellTempMaxC = kBmsNoValue, cellTempMinC = kBmsNoValue;
  bool chargeAllowed = true;
  std::uint32_t warnings = 0;  // bmswarn flags
  std::uint32_t alarms = 0;    // bmswarn flags the BMS raised as alarms (it is about to open)
  BmsSource source = BmsSource::None;
  TimeNs stamp = 0;  // when CVL/CCL last arrived (0 = never)
};

}  // namespace xr
