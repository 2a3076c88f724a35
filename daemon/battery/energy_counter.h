#pragma once
// EnergyCounter: the energy in and out of the bank, the alternator's and
// solar's share, the alternator's running time and the diesel it cost
// (docs/batteries.md "Energy and averages"). Each tick adds to the interval's integrals;
// each SoC interval commits them to the session and lifetime totals. A
// lifetime total is kept as whole Wh plus a retained fraction, so a 50 mW
// draw is never rounded away against megawatt-hours. Pure: no clock, no I/O.
#include "battery/ledger.h"

namespace xr {

// One tick's sample (zero-order hold over dt).
struct EnergySample {
  double dt_s = 0.0;
  double volts = 0.0, amps = 0.0;  // battery voltage and current (+ = charging)
  bool voltsOk = false, ampsOk = false;
  bool alternatorOn = false;  // alternator current above CurrentThreshold
  double altAmps = 0.0;       // the alternator's current while on
  double solarW = 0.0;        // fresh solar power (NaN: none)
};

// One energy total: this session, and the lifetime as whole Wh + fraction.
struct EnergyTotal {
  double session_Wh = 0.0;           // since the daemon started
  double lifetimeWhole_Wh = 0.0;     // the bank's life, whole Wh
  double lifetimeFraction_Wh = 0.0;  // below one Wh, not yet in lifetimeWhole_Wh
  double lifetime() const noexcept { return lifetimeWhole_Wh + lifetimeFraction_Wh; }
};

class EnergyCounter {
 public:
  // Every tick with dt > 0.
  void integrate(const EnergySample& s) noexcept;
  // Each SoC interval: the interval's integrals into the totals.
  void commit() noexcept;

  const EnergyTotal& charged() const noexcept { return charged_; }
  const EnergyTotal& discharged() const noexcept { return discharged_; }
  const EnergyTotal& alternator() const noexcept { return alternator_; }
  const EnergyTotal& solar() const noexcept { return solar_; }
  double alternatorOnTime_s() const noexcept { return onTime_s_; }
  double alternatorOnTimeAllTime_s() const noexcept { return onTimeAllTime_s_; }
  double fuelUsed_L() const noexcept { return fuel_L_; }
  double fuelUsedAllTime_L() const noexcept { return fuelAllTime_L_; }

  void toLedger(BatteryLedger& l) const noexcept;
  // Restores the lifetime totals; NaN or negative values restart at 0.
  void restore(const BatteryLedger& l) noexcept;

 private:
  static void commitTo(EnergyTotal& e, double delta_Wh) noexcept;
  void commitFuel() noexcept;

  double intChargeWh_ = 0.0;      // this interval: V*I where > 0
  double intDischargeWh_ = 0.0;   // this interval: |V*I| where < 0
  double intAltWh_ = 0.0;         // this interval: V * alternator current while it is on
  double intSolarWh_ = 0.0;       // this interval: solar power
  double intAltOn_s_ = 0.0;       // this interval: seconds the alternator was on
  EnergyTotal charged_;           // into the bank
  EnergyTotal discharged_;        // out of the bank
  EnergyTotal alternator_;        // from the alternator
  EnergyTotal solar_;             // from solar (VE.Direct PPV)
  double onTime_s_ = 0.0;         // alternator on, this session
  double onTimeAllTime_s_ = 0.0;  // alternator on, lifetime
  double fuel_L_ = 0.0;           // diesel for the alternator's energy, this session (0.01 L steps)
  double fuelAllTime_L_ = 0.0;    // the same, lifetime
  double fuelFraction_L_ = 0.0;   // below one 0.01 L step, not yet committed
};

}  // namespace xr
