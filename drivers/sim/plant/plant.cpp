#include "drivers/sim/plant/plant.h"

#include <algorithm>
#include <cmath>

namespace xr::sim {

Plant::Plant(const PlantConfig& c)
    : cfg_(c),
      bat_(c.battery),
      alt_(c.alternator),
      solar_(c.solar, c.battery.nominal_v),
      charger_(c.charger, c.battery.nominal_v),
      rpm_(c.rpm),
      ambientF_(c.alternator.ambient_f),
      tvs_(c.tvs_clamp_v > 0.0 ? c.tvs_clamp_v : 2.5 * c.battery.nominal_v) {
  setHouseAmps(c.house_a);
  fridgeG_ = c.fridge_a / (12.8 * c.battery.nominal_v / 12.0);
  busV_ = bat_.terminalVolts(0.0);
  alt_.step(0.0, busV_, rpm_, ambientF_, 0.0);  // speed and temperature caches
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
    // rise and the TVS clamp resolved.
    const int n = std::max(1, int(std::ceil(dt / 50e-6)));
    for (int i = 0; i < n; ++i) subStep(fieldCmd, dt / n);
  }
  refreshTruth();
}

void Plant::subStep(double fieldCmd, double dt) noexcept {
  // The field is fed from the bus (the regulator's supply): duty x bus volts.
  // A slipping belt loses speed with the load it carries (the last current).
  const double rated = std::isnan(cfg_.alternator.rated_a) ? 100.0 : cfg_.alternator.rated_a;
  slipNow_ = beltSlip_ > 0.0 ? beltSlip_ * std::clamp(alt_.amps() / rated, 0.0, 1.0) : 0.0;
  alt_.step(fieldCmd, busV_, rpm_ * (1.0 - slipNow_), ambientF_, dt);
  // The alternator sees the bus plus its cable drop at the last current.
  const double cable = alt_.amps() * cfg_.alternator.wiring_ohm;
  // The fridge's compressor runs the first fridge_duty of each period.
  t_ += dt;
  const bool fridgeOn =
      fridgeG_ > 0.0 && std::fmod(t_, cfg_.fridge_period_s) < cfg_.fridge_duty * cfg_.fridge_period_s;
  const double g = houseG_ + (fridgeOn ? fridgeG_ : 0.0);
  // Other chargers: constant within the step (their loops are slower than it).
  const double src = solar_.amps() + charger_.amps();
  if (bmsConnected_) {
    // Node: I_alt(V + cable) + I_src = V·G_house + (V − E)/R. The battery is linear
    // within the step and stiff (R of milliohms), so Newton from the last
    // voltage settles in two iterations.
    const double e = bat_.emf();
    const double gb = 1.0 / bat_.seriesR();
    double v = busV_;
    double ia = 0.0;
    for (int k = 0; k < 2; ++k) {
      double d = 0.0;
      ia = alt_.outputAt(v + cable, &d);
      const double r = ia + src - v * g - (v - e) * gb;
      v -= r / (d - g - gb);
    }
    ia = alt_.outputAt(v + cable);
    alt_.setOutput(ia);
    batA_ = (v - e) * gb;
    busV_ = v;
    bat_.step(batA_, dt);
  } else {
    batA_ = 0.0;
    bat_.step(0.0, dt);
    // C dV/dt = I_alt(V) − G·V, backward Euler linearised at V (stable for
    // any C: the machine's output falls as the bus rises).
    double d = 0.0;
    const double ia = alt_.outputAt(busV_ + cable, &d);
    const double f = ia + src - busV_ * g;
    const double k = dt / std::max(1e-6, cfg_.bus_capacitance_f);
    busV_ += k * f / (1.0 - k * (d - g));
    busV_ = std::clamp(busV_, 0.0, tvs_);  // the TVS absorbs the rest
    alt_.setOutput(alt_.outputAt(busV_ + cable));
    truth_.peak_disconnected_v = std::max(truth_.peak_disconnected_v, busV_);
  }
  solar_.step(busV_, dt);
  charger_.step(busV_, dt);
  houseNowG_ = g;
  truth_.peak_bus_v = std::max(truth_.peak_bus_v, busV_);
}

void Plant::refreshTruth() noexcept {
  truth_.battery_v = busV_;
  truth_.battery_a = batA_;
  truth_.alt_a = alt_.amps();
  truth_.alt_terminal_v = busV_ + alt_.amps() * cfg_.alternator.wiring_ohm;
  truth_.alt_temp_f = alt_.tempF();
  truth_.alt_stator_c = alt_.statorC();
  truth_.house_a = busV_ * houseNowG_;
  truth_.solar_a = solar_.amps();
  truth_.charger_a = charger_.amps();
  truth_.soc_pct = bat_.socPct();
  truth_.field = alt_.field();
  truth_.field_a = alt_.fieldAmps();
  truth_.battery_temp_c = bat_.tempC();
  truth_.bms_connected = bmsConnected_;
}

}  // namespace xr::sim
