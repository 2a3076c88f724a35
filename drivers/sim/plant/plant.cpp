#include "drivers/sim/plant/plant.h"

#include <algorithm>
#include <cmath>

namespace xr::sim {

Plant::Plant(const PlantConfig& c)
    : cfg_(c),
      bat_(c.battery),
      alt_(c.alternator),
      rpm_(c.rpm),
      ambientF_(c.alternator.ambient_f),
      tvs_(c.tvs_clamp_v > 0.0 ? c.tvs_clamp_v : 2.5 * c.battery.nominal_v) {
  setHouseAmps(c.house_a);
  busV_ = bat_.terminalVolts(0.0);
  refreshTruth();
  truth_.peak_bus_v = busV_;
}

void Plant::setHouseAmps(double a) noexcept {
  // Resistive at the nominal charging-system voltage (12.8 V per 12 V).
  const double vn = 12.8 * cfg_.battery.nominal_v / 12.0;
  houseG_ = a > 0.0 ? a / vn : 0.0;
}

void Plant::setBmsConnected(bool c) noexcept { bmsConnected_ = c; }

void Plant::step(double fieldCmd, double dt) noexcept {
  if (bmsConnected_) {
    subStep(fieldCmd, dt);
  } else {
    // Without the battery the bus is a capacitor: ~50 µs steps keep the
    // rise (hundreds of V/s per amp) and the TVS clamp resolved.
    const int n = std::max(1, int(std::ceil(dt / 50e-6)));
    for (int i = 0; i < n; ++i) subStep(fieldCmd, dt / n);
  }
  refreshTruth();
}

void Plant::subStep(double fieldCmd, double dt) noexcept {
  alt_.step(fieldCmd, rpm_, ambientF_, dt);
  const double ia = alt_.amps();
  if (bmsConnected_) {
    // Node: the battery takes what the alternator gives minus the house load.
    // The house load is resistive, so solve V = E + R (Ia - V/Rh) for V.
    const double e0 = bat_.terminalVolts(0.0);
    const double r = bat_.seriesR();
    double v = (e0 + r * ia) / (1.0 + r * houseG_);
    // Refinement so the charge overpotential sees the real current (the
    // linear solve above is already exact without one).
    for (int k = 0; k < 2 && bat_.hasOverpotential(); ++k) {
      const double ib = ia - v * houseG_;
      v = bat_.terminalVolts(ib);
    }
    batA_ = ia - v * houseG_;
    busV_ = v;
    bat_.step(batA_, dt);
  } else {
    batA_ = 0.0;
    bat_.step(0.0, dt);
    const double ih = busV_ * houseG_;
    busV_ += (ia - ih) * dt / std::max(1e-6, cfg_.bus_capacitance_f);
    busV_ = std::clamp(busV_, 0.0, tvs_);  // the TVS absorbs the rest
    truth_.peak_disconnected_v = std::max(truth_.peak_disconnected_v, busV_);
  }
  truth_.peak_bus_v = std::max(truth_.peak_bus_v, busV_);
}

void Plant::refreshTruth() noexcept {
  truth_.battery_v = busV_;
  truth_.battery_a = batA_;
  truth_.alt_a = alt_.amps();
  truth_.alt_terminal_v = busV_ + alt_.amps() * cfg_.alternator.wiring_ohm;
  truth_.alt_temp_f = alt_.tempF();
  truth_.house_a = busV_ * houseG_;
  truth_.soc_pct = bat_.socPct();
  truth_.field = alt_.field();
  truth_.bms_connected = bmsConnected_;
}

}  // namespace xr::sim
