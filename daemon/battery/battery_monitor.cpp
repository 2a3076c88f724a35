// BatteryMonitor, the coordinator (docs/batteries.md, docs/architecture.md
// "Battery monitor"). See battery_monitor.h for the call order
// Regulator::step follows. This file holds construction, the sources of
// truth, the auto-zero's inputs, commands, the ledger and telemetry; one
// tick of the SoC parts is in battery_monitor_tick.cpp.
#include "battery/battery_monitor.h"

#include "battery/monitor_helpers.h"
#include "core/alternator_temperature.h"
#include "params/constants.h"

namespace xr {

using namespace battery_detail;

BatteryMonitor::BatteryMonitor(const Params& p) : p_(p), soc_(p.BatteryCapacity_Ah) {}

void BatteryMonitor::setParams(const Params& p) noexcept {
  p_ = p;
  telemetryStale_ = true;
  soc_.clampTo(p_.BatteryCapacity_Ah);
}

void BatteryMonitor::startTimers(TimeNs now) noexcept {
  started_ = true;
  lastTick_ = now;
  lastSocUpdate_ = now;
  lastChargeTimes_ = now;
  autoZero_.begin(now);  // the hourly timer starts at the first tick
}

// ---------------------------------------------------------------- sources of truth

double BatteryMonitor::getBatteryVoltage(const Inputs& in) const noexcept { return in.IBV.value; }

bool BatteryMonitor::usingVictronCurrent(const Inputs& in) const noexcept {
  return p_.BatteryCurrentSource == 3 && usable(in.VictronCurrent, in.now, k::VICTRON_STALE_MS);
}

double BatteryMonitor::getBatteryCurrent(const Inputs& in) const noexcept {
  if (usingVictronCurrent(in)) return in.VictronCurrent.value;
  return correctedBcur(in.Bcur.value);
}

// ---------------------------------------------------------------- auto-zero

AutoZeroInput BatteryMonitor::autoZeroInput(const Inputs& in) const noexcept {
  AutoZeroInput a;
  a.now = in.now;
  a.enabled = p_.AutoAltCurrentZero;
  a.tempF = alternatorTemperature(in, p_.TempSource).value;
  a.rpm = in.rpm.value;
  a.altCurrentRaw = in.altCurrentRaw;
  return a;
}

void BatteryMonitor::checkAutoZeroTriggers(const Inputs& in, EventBatch& ev) noexcept {
  if (!started_) startTimers(in.now);
  if (autoZero_.checkTriggers(autoZeroInput(in), ev)) telemetryStale_ = true;
}

bool BatteryMonitor::processActiveAutoZero(const Inputs& in, EventBatch& ev) noexcept {
  const bool active = autoZero_.update(autoZeroInput(in), ev);
  if (!active) telemetryStale_ = true;  // the window ended: a new zero
  return active;
}

// ---------------------------------------------------------------- commands

void BatteryMonitor::resetSocGain() noexcept {
  gain_.reset();
  telemetryStale_ = true;
}

void BatteryMonitor::resetAltZero() noexcept {
  autoZero_.reset();
  telemetryStale_ = true;
}

bool BatteryMonitor::setSoc(double pct) noexcept {
  if (!finite(pct) || pct < 0.0 || pct > 100.0) return false;
  soc_.setByOperator(pct, p_.BatteryCapacity_Ah);
  telemetryStale_ = true;
  return true;
}

// ---------------------------------------------------------------- persistence

BatteryLedger BatteryMonitor::ledger() const noexcept {
  BatteryLedger l;
  soc_.toLedger(l);
  l.DynamicShuntGainFactor = gain_.factor();
  l.DynamicAltCurrentZero = autoZero_.zero();
  energy_.toLedger(l);
  averages_.toLedger(l);
  health_.toLedger(l);
  l.valid = true;
  return l;
}

void BatteryMonitor::restoreLedger(const BatteryLedger& l) noexcept {
  soc_.restore(l, p_.BatteryCapacity_Ah);
  gain_.restore(l.DynamicShuntGainFactor);
  autoZero_.restore(l.DynamicAltCurrentZero);
  energy_.restore(l);
  averages_.restore(l);
  health_.restore(l);
  telemetryStale_ = true;
}

// ---------------------------------------------------------------- outputs

void BatteryMonitor::updateTelemetry(BatteryTelemetry& t) noexcept {
  if (telemetryStale_) {
    fillTelemetry(t);
    telemetryStale_ = false;
    return;
  }
  // The fields updateBatterySoc() rewrites on every tick (socKnown turns
  // true at a detected full charge, which happens inside it).
  t.batteryCurrentForSoC = batteryCurrentForSoC_;
  t.usingVictronCurrent = usingVictron_;
  t.socKnown = socKnown();
  t.socSource = socSource();
}

void BatteryMonitor::fillTelemetry(BatteryTelemetry& t) const noexcept {
  t.SOC_percent = socPercent();
  t.socKnown = socKnown();
  t.socSource = socSource();
  t.CoulombCount_Ah = soc_.countAh();
  t.batteryCurrentForSoC = batteryCurrentForSoC_;
  t.FullChargeDetected = soc_.fullDetected();
  t.ChargedEnergy_Wh = energy_.charged().session_Wh;
  t.DischargedEnergy_Wh = energy_.discharged().session_Wh;
  t.AlternatorChargedEnergy_Wh = energy_.alternator().session_Wh;
  t.SolarChargedEnergy_Wh = energy_.solar().session_Wh;
  t.AlternatorOnTime_s = energy_.alternatorOnTime_s();
  t.AlternatorFuelUsed_L = energy_.fuelUsed_L();
  const double capWh = p_.BatteryCapacity_Ah * nominalVoltage_;
  t.ChargeCycles = capWh > 0.0 ? energy_.charged().session_Wh / capWh : 0.0;
  t.ChargeCycles_AllTime = capWh > 0.0 ? chargedEnergyLifetimeWh() / capWh : 0.0;
  t.AvgSOC = averages_.avgSoc();
  t.AvgSOC_AllTime = averages_.avgSocAllTime();
  t.AvgVoltage_AllTime = averages_.avgVoltageAllTime();
  t.timeToFullChargeMin = soc_.timeToFullMin();
  t.timeToFullDischargeMin = soc_.timeToEmptyMin();
  t.DynamicShuntGainFactor = gain_.factor();
  t.DynamicAltCurrentZero = autoZero_.zero();
  t.autoZeroActive = autoZero_.active();
  t.ChargedEnergy_AllTime_Wh = chargedEnergyLifetimeWh();
  t.DischargedEnergy_AllTime_Wh = energy_.discharged().lifetime();
  t.AlternatorChargedEnergy_AllTime_Wh = alternatorChargedEnergyLifetimeWh();
  t.SolarChargedEnergy_AllTime_Wh = energy_.solar().lifetime();
  t.AlternatorFuelUsed_AllTime_L = energy_.fuelUsedAllTime_L();
  t.AlternatorOnTime_AllTime_s = energy_.alternatorOnTimeAllTime_s();
  t.nominalVoltage = nominalVoltage_;
  t.usingVictronCurrent = usingVictron_;
  t.capacity_measured_ah = health_.capacity().measuredAh();
  t.capacity_cycles = health_.capacity().cycles();
  t.battery_r_mohm = health_.resistance().medianMohm();
  t.battery_r_spread_mohm = health_.resistance().spreadMohm();
  t.battery_r_samples = health_.resistance().samples();
}

}  // namespace xr
