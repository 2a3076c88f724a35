// BatteryMonitor's health figures (docs/batteries.md "Measured capacity",
// "Internal resistance"): the points of known state of charge the capacity
// is measured between, and the resistance from the current steps.
#include <cmath>

#include "battery/battery_monitor.h"
#include "battery/monitor_helpers.h"
#include "core/freshness.h"
#include "params/constants.h"

namespace xr {

using namespace battery_detail;

namespace {
// A rested voltage is a point of known SoC for lead-acid after this long at
// rest: the slow polarisation decays over hours (docs/sources.md P3.5 asks
// for 6 h or more; after 4 h what is left is ~1 % of SoC for an AGM bank,
// docs/batteries.md). The voltage is the mean of the last hour of it.
constexpr double kHealthRestS = 4.0 * 3600.0;
constexpr double kHealthRestAverageS = 3600.0;
// "At rest" for this point is wider than the first-start estimate's: a
// fridge compressor on a boat draws 4 to 6 A while it runs, 2 to 3 % of C,
// and the bank rests only with it. Any second within kHealthRestPeakC
// (discharge) or kHealthRestChargeC (charge) counts, with the alternator
// off; the hour the voltage is averaged over must average within
// kHealthRestMeanC, and what still flows is taken off with the measured
// resistance (docs/batteries.md "Measured capacity").
constexpr double kHealthRestPeakC = 0.05, kHealthRestChargeC = 0.02, kHealthRestMeanC = 0.02;
}  // namespace

void BatteryMonitor::trackHealth(const Inputs& in, double dt_s, double amps, double volts,
                                 double altAmps) noexcept {
  // The battery temperature counts while the temperature rules count it (BATTERY_TEMP_STALE_MS).
  const double tempC = fresh::batteryTemp(in.batteryTempC, in.now) ? in.batteryTempC.value : kNoValue;
  if (resistance_.update(dt_s, amps, volts, tempC, p_.BatteryCapacity_Ah)) telemetryStale_ = true;
  const double c = p_.BatteryCapacity_Ah;
  // leadAcidAtRest with no current: a lead-acid bank, a voltage, the alternator off.
  const bool resting = leadAcidAtRest(0.0, volts, altAmps) && std::isfinite(amps) &&
                       amps <= kHealthRestChargeC * c && amps >= -kHealthRestPeakC * c;
  restedVoltagePoint(dt_s, amps, volts, tempC, resting);
  const bool bmsFresh =
      std::isfinite(in.bms.socPct) && in.bms.stamp != 0 && fresh::bms(in.bms.stamp, in.now, p_.BmsStaleS);
  bmsSocPct_ = bmsFresh ? in.bms.socPct : kNoValue;
}

void BatteryMonitor::restedVoltagePoint(double dt_s, double amps, double volts, double tempC,
                                        bool resting) noexcept {
  if (!resting) {
    healthRest_s_ = healthRestV_s_ = healthRestA_s_ = healthRestAvg_s_ = 0.0;
    healthRestTaken_ = false;
    return;
  }
  if (!(dt_s > 0.0) || healthRestTaken_) return;
  healthRest_s_ += dt_s;
  if (healthRest_s_ > kHealthRestS - kHealthRestAverageS) {
    healthRestV_s_ += volts * dt_s;
    healthRestA_s_ += amps * dt_s;
    healthRestAvg_s_ += dt_s;
  }
  if (healthRest_s_ < kHealthRestS || !(healthRestAvg_s_ > 0.0)) return;
  healthRestTaken_ = true;
  // The open-circuit voltage: the terminal voltage less what the small rest
  // current drops across the bank (when its resistance is known).
  const double r = resistance_.ohmsAt(tempC);
  const double a = healthRestA_s_ / healthRestAvg_s_;
  if (std::fabs(a) > kHealthRestMeanC * p_.BatteryCapacity_Ah) return;  // not a rest on average
  const double ocv = healthRestV_s_ / healthRestAvg_s_ - (std::isfinite(r) ? a * r : 0.0);
  pendingRestSocPct_ = socFromRestVolts(ocv);
}

void BatteryMonitor::capacityPoint(TimeNs now, double socPct, bool full, EventBatch& ev) noexcept {
  const CapacityPointResult r = capacity_.knownSoc(socPct, full, p_.BatteryCapacity_Ah);
  if (r != CapacityPointResult::Measured) return;
  telemetryStale_ = true;
  ev.push(makeEvent(now, EventLevel::Info, EventCode::CapacityMeasured, capacity_.lastSampleAh(),
                    capacity_.lastSwingPct(), capacity_.cycles()));
}

}  // namespace xr
