#pragma once
// A day's and a charge's summary (docs/dashboard.md "History"), as the store
// keeps them and the API sends them; store/charge_tally.h makes them.
#include <cmath>
#include <cstdint>
#include <string>

namespace xr {

struct DaySummary {
  std::string day;
  double altAh = 0.0, altWh = 0.0;                      // from the alternator, field on
  double batteryAhIn = 0.0, batteryAhOut = 0.0;         // through the battery shunt
  double batteryWhIn = 0.0;                             // into the bank, by the shunt and its voltage
  double bulkS = 0.0, absorptionS = 0.0, floatS = 0.0;  // field on, by stage
  double idleS = 0.0;                                   // resting after a full charge
  double fieldOnS = 0.0;
  double peakAltTempC = NAN, minSocPct = NAN, maxSocPct = NAN;
  double minBatteryV = NAN, maxBatteryV = NAN;
  double socStartPct = NAN, socEndPct = NAN;  // the first and last known SoC of the day
  double engineS = NAN;                       // engine running (NaN: a row older than the count)
};

struct ChargeSummary {
  std::int64_t id = 0;  // the store's row, 0 until saved
  std::int64_t startMs = 0, endMs = 0;
  double bulkS = 0.0, absorptionS = 0.0, floatS = 0.0;
  double altAh = 0.0, altWh = 0.0;
  double startSocPct = NAN, endSocPct = NAN;
  std::string endReason;  // a Reason's name (REASON_RPM_LOW, ...), or "" while open
  bool open = true;
};

}  // namespace xr
