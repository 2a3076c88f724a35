#pragma once
// BatteryAverages: the time-weighted mean state of charge (this session and
// lifetime) and the lifetime mean battery voltage (docs/batteries.md
// "Energy and averages"). Each tick adds its seconds; each SoC interval weighs the
// interval's SoC by them. Pure: no clock, no I/O.
#include "battery/ledger.h"

namespace xr {

class BatteryAverages {
 public:
  // Every tick with dt > 0; `volts` counts only when measured.
  void integrate(double dt_s, double volts, bool voltsOk) noexcept {
    if (voltsOk) {
      intV_s_ += volts * dt_s;
      intVtime_s_ += dt_s;
    }
    intSoc_s_ += dt_s;
  }
  // Each SoC interval, with the SoC after the interval's count.
  void commit(double socPct) noexcept;

  double avgSoc() const noexcept { return socTime_s_ > 0.0 ? socSum_ / socTime_s_ : 0.0; }
  double avgSocAllTime() const noexcept { return socTimeAll_s_ > 0.0 ? socSumAll_ / socTimeAll_s_ : 0.0; }
  double avgVoltageAllTime() const noexcept { return vTimeAll_s_ > 0.0 ? vSumAll_ / vTimeAll_s_ : 0.0; }

  void toLedger(BatteryLedger& l) const noexcept;
  // Restores the lifetime sums; NaN or negative values restart at 0.
  void restore(const BatteryLedger& l) noexcept;

 private:
  double intSoc_s_ = 0.0;      // this interval: seconds
  double intV_s_ = 0.0;        // this interval: voltage integral (V s)
  double intVtime_s_ = 0.0;    // this interval: seconds with a measured voltage
  double socSum_ = 0.0;        // this session: SoC integral (% s)
  double socTime_s_ = 0.0;     // this session: seconds in it
  double socSumAll_ = 0.0;     // lifetime: SoC integral (% s)
  double socTimeAll_s_ = 0.0;  // lifetime: seconds in it
  double vSumAll_ = 0.0;       // lifetime: voltage integral (V s)
  double vTimeAll_s_ = 0.0;    // lifetime: seconds in it
};

}  // namespace xr
