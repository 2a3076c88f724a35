// EnergyCounter (docs/batteries.md "Energy and averages").
#include "battery/energy_counter.h"

#include <cmath>

#include "battery/monitor_helpers.h"
#include "params/constants.h"

namespace xr {

using namespace battery_detail;

void EnergyCounter::integrate(const EnergySample& s) noexcept {
  const double dt = s.dt_s;
  if (s.ampsOk && s.voltsOk) {
    const double wh = s.volts * s.amps * dt / 3600.0;
    if (wh > 0.0)
      intChargeWh_ += wh;
    else
      intDischargeWh_ -= wh;
  }
  if (s.alternatorOn) {
    intAltOn_s_ += dt;
    if (s.voltsOk) intAltWh_ += s.volts * s.altAmps * dt / 3600.0;
  }
  if (s.solarW > 0.0) intSolarWh_ += s.solarW * dt / 3600.0;
}

void EnergyCounter::commitTo(EnergyTotal& e, double delta_Wh) noexcept {
  if (!(delta_Wh > 0.0)) return;
  e.session_Wh += delta_Wh;
  e.lifetimeFraction_Wh += delta_Wh;
  if (e.lifetimeFraction_Wh >= 1.0) {
    const double whole = std::floor(e.lifetimeFraction_Wh);
    e.lifetimeWhole_Wh += whole;
    e.lifetimeFraction_Wh -= whole;
  }
}

// Fuel for the alternator's energy: 30 % engine x 50 % alternator efficiency.
void EnergyCounter::commitFuel() noexcept {
  if (intAltWh_ > 0.0) {
    const double energyJoules = intAltWh_ * 3600.0;
    const double fuelEnergyUsed_J =
        energyJoules / (k::FUEL_ENGINE_EFFICIENCY * k::FUEL_ALTERNATOR_EFFICIENCY);
    const double fuelUsed_L = fuelEnergyUsed_J / k::DIESEL_J_PER_ML / 1000.0;
    fuelFraction_L_ += fuelUsed_L;
    // Roll whole hundredths of a litre, keep the rest.
    const double hundredths = std::floor(fuelFraction_L_ * 100.0) / 100.0;
    if (hundredths > 0.0) {
      fuel_L_ += hundredths;
      fuelAllTime_L_ += hundredths;
      fuelFraction_L_ -= hundredths;
    }
  }
}

void EnergyCounter::commit() noexcept {
  commitTo(charged_, intChargeWh_);
  commitTo(discharged_, intDischargeWh_);
  commitTo(alternator_, intAltWh_);
  commitTo(solar_, intSolarWh_);
  onTime_s_ += intAltOn_s_;
  onTimeAllTime_s_ += intAltOn_s_;
  commitFuel();
  intChargeWh_ = intDischargeWh_ = intAltWh_ = intSolarWh_ = intAltOn_s_ = 0.0;
}

void EnergyCounter::toLedger(BatteryLedger& l) const noexcept {
  // Whole + retained fraction: the store keeps the exact total.
  l.ChargedEnergy_AllTime_Wh = charged_.lifetime();
  l.DischargedEnergy_AllTime_Wh = discharged_.lifetime();
  l.AlternatorChargedEnergy_AllTime_Wh = alternator_.lifetime();
  l.SolarChargedEnergy_AllTime_Wh = solar_.lifetime();
  l.AlternatorFuelUsed_AllTime_L = fuelAllTime_L_;
  l.AlternatorOnTime_AllTime_s = onTimeAllTime_s_;
}

void EnergyCounter::restore(const BatteryLedger& l) noexcept {
  const double big = 1e15;
  auto nonNeg = [&](double v) { return clampFinite(v, 0.0, big, 0.0); };
  // Split each lifetime energy back into whole Wh + retained fraction.
  auto split = [&](double total, EnergyTotal& e) {
    const double t = nonNeg(total);
    const double w = std::floor(t);
    e.lifetimeFraction_Wh = t - w;
    e.lifetimeWhole_Wh = w;
  };
  split(l.ChargedEnergy_AllTime_Wh, charged_);
  split(l.DischargedEnergy_AllTime_Wh, discharged_);
  split(l.AlternatorChargedEnergy_AllTime_Wh, alternator_);
  split(l.SolarChargedEnergy_AllTime_Wh, solar_);
  fuelAllTime_L_ = nonNeg(l.AlternatorFuelUsed_AllTime_L);
  onTimeAllTime_s_ = nonNeg(l.AlternatorOnTime_AllTime_s);
}

}  // namespace xr
