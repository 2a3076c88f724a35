// BatteryMonitor — docs/batteries.md. See battery_monitor.h for the
// call order Regulator::step follows. This file holds construction, the
// sources of truth, commands, the ledger and telemetry; auto-zero and the SoC
// are in battery_auto_zero.cpp and battery_soc.cpp.
#include "battery/battery_monitor.h"

#include <algorithm>
#include <cmath>

#include "battery/monitor_helpers.h"
#include "params/constants.h"

namespace xr {

using namespace battery_detail;

BatteryMonitor::BatteryMonitor(const Params& p) : p_(p) {
  // A fresh ledger (first start, nothing restored) does not know the SoC.
  // Assume full: with SOC gating (charging_stage rebulkDue) a low guess would
  // force re-bulk "regardless of voltage" until the first full charge, i.e.
  // the charger would never rest; a full guess defers to voltage/current
  // re-bulk once 5 % has been counted out. socKnown() says it is a guess.
  ledger_.CoulombCount_Ah = p_.BatteryCapacity_Ah * kUnknownSocPercent / 100.0;
  ledger_.SocSource = static_cast<double>(SocSource::Unknown);
  ledger_.valid = true;
}

void BatteryMonitor::setParams(const Params& p) noexcept {
  p_ = p;
  telemetryStale_ = true;
  ledger_.CoulombCount_Ah = std::clamp(ledger_.CoulombCount_Ah, 0.0, p_.BatteryCapacity_Ah);
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

// ---------------------------------------------------------------- commands

void BatteryMonitor::resetSocGain() noexcept {
  ledger_.DynamicShuntGainFactor = 1.0;
  telemetryStale_ = true;
}

void BatteryMonitor::resetAltZero() noexcept {
  ledger_.DynamicAltCurrentZero = 0.0;
  telemetryStale_ = true;
}

bool BatteryMonitor::setSoc(double pct) noexcept {
  if (!finite(pct) || pct < 0.0 || pct > 100.0) return false;
  ledger_.CoulombCount_Ah = p_.BatteryCapacity_Ah * pct / 100.0;
  ledger_.coulombAccumulator_Ah = 0.0;
  telemetryStale_ = true;
  // The operator's figure is a reference point for the gain correction.
  gainReferenceValid_ = true;
  unclampedCount_Ah_ = ledger_.CoulombCount_Ah;
  setSocSource(SocSource::Counted);
  return true;
}

// ---------------------------------------------------------------- persistence

BatteryLedger BatteryMonitor::ledger() const noexcept {
  BatteryLedger l = ledger_;
  // Whole + retained fraction: the store keeps the exact total.
  l.ChargedEnergy_AllTime_Wh += charged_.lifetimeFraction_Wh;
  l.DischargedEnergy_AllTime_Wh += discharged_.lifetimeFraction_Wh;
  l.AlternatorChargedEnergy_AllTime_Wh += altCharged_.lifetimeFraction_Wh;
  l.SolarChargedEnergy_AllTime_Wh += solar_.lifetimeFraction_Wh;
  l.capacity = capacity_.ledger();
  l.resistance = resistance_.ledger();
  l.valid = true;
  return l;
}

void BatteryMonitor::restoreLedger(const BatteryLedger& in) noexcept {
  using namespace battery_k;
  BatteryLedger l = in;
  const double cap = p_.BatteryCapacity_Ah;
  const bool countOk = std::isfinite(l.CoulombCount_Ah) && l.valid;
  l.CoulombCount_Ah = clampFinite(l.CoulombCount_Ah, 0.0, cap, cap * kUnknownSocPercent / 100.0);
  // 0, 1 or 2; anything else (a damaged row) is counted as unknown.
  const double src = l.SocSource;
  l.SocSource = countOk && (src == 1.0 || src == 2.0) ? src : 0.0;
  l.coulombAccumulator_Ah = clampFinite(l.coulombAccumulator_Ah, -COULOMB_COMMIT_AH, COULOMB_COMMIT_AH, 0.0);
  l.DynamicShuntGainFactor =
      clampFinite(l.DynamicShuntGainFactor, MIN_DYNAMIC_GAIN_FACTOR, MAX_DYNAMIC_GAIN_FACTOR, 1.0);
  l.DynamicAltCurrentZero =
      clampFinite(l.DynamicAltCurrentZero, -AUTO_ZERO_MAX_OFFSET_A, AUTO_ZERO_MAX_OFFSET_A, 0.0);
  const double big = 1e15;
  auto nonNeg = [&](double& v) { v = clampFinite(v, 0.0, big, 0.0); };
  nonNeg(l.ChargedEnergy_AllTime_Wh);
  nonNeg(l.DischargedEnergy_AllTime_Wh);
  nonNeg(l.AlternatorChargedEnergy_AllTime_Wh);
  nonNeg(l.SolarChargedEnergy_AllTime_Wh);
  nonNeg(l.socAccumulator_AllTime);
  nonNeg(l.totalSocSampleTime_AllTime);
  nonNeg(l.voltageAccumulator_AllTime);
  nonNeg(l.totalVoltageSampleTime_AllTime);
  nonNeg(l.AlternatorFuelUsed_AllTime_L);
  nonNeg(l.AlternatorOnTime_AllTime_s);
  // Split lifetime energies back into whole Wh + retained fraction.
  auto split = [](double& whole, Energy& e) {
    const double w = std::floor(whole);
    e.lifetimeFraction_Wh = whole - w;
    whole = w;
  };
  split(l.ChargedEnergy_AllTime_Wh, charged_);
  split(l.DischargedEnergy_AllTime_Wh, discharged_);
  split(l.AlternatorChargedEnergy_AllTime_Wh, altCharged_);
  split(l.SolarChargedEnergy_AllTime_Wh, solar_);
  capacity_.restore(l.capacity);
  resistance_.restore(l.resistance);
  l.valid = true;
  ledger_ = l;
  telemetryStale_ = true;
  gainReferenceValid_ = false;
}

// ---------------------------------------------------------------- outputs

double BatteryMonitor::chargedEnergyLifetimeWh() const noexcept {
  return ledger_.ChargedEnergy_AllTime_Wh + charged_.lifetimeFraction_Wh;
}

double BatteryMonitor::alternatorChargedEnergyLifetimeWh() const noexcept {
  return ledger_.AlternatorChargedEnergy_AllTime_Wh + altCharged_.lifetimeFraction_Wh;
}

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
  t.CoulombCount_Ah = ledger_.CoulombCount_Ah;
  t.batteryCurrentForSoC = batteryCurrentForSoC_;
  t.FullChargeDetected = FullChargeDetected_;
  t.ChargedEnergy_Wh = charged_.session_Wh;
  t.DischargedEnergy_Wh = discharged_.session_Wh;
  t.AlternatorChargedEnergy_Wh = altCharged_.session_Wh;
  t.SolarChargedEnergy_Wh = solar_.session_Wh;
  t.AlternatorOnTime_s = AlternatorOnTime_s_;
  t.AlternatorFuelUsed_L = AlternatorFuelUsed_L_;
  const double capWh = p_.BatteryCapacity_Ah * nominalVoltage_;
  t.ChargeCycles = capWh > 0.0 ? charged_.session_Wh / capWh : 0.0;
  t.ChargeCycles_AllTime = capWh > 0.0 ? chargedEnergyLifetimeWh() / capWh : 0.0;
  t.AvgSOC = totalSocSampleTime_ > 0.0 ? socAccumulator_ / totalSocSampleTime_ : 0.0;
  t.AvgSOC_AllTime = ledger_.totalSocSampleTime_AllTime > 0.0
                         ? ledger_.socAccumulator_AllTime / ledger_.totalSocSampleTime_AllTime
                         : 0.0;
  t.AvgVoltage_AllTime = ledger_.totalVoltageSampleTime_AllTime > 0.0
                             ? ledger_.voltageAccumulator_AllTime / ledger_.totalVoltageSampleTime_AllTime
                             : 0.0;
  t.timeToFullChargeMin = timeToFullChargeMin_;
  t.timeToFullDischargeMin = timeToFullDischargeMin_;
  t.DynamicShuntGainFactor = ledger_.DynamicShuntGainFactor;
  t.DynamicAltCurrentZero = ledger_.DynamicAltCurrentZero;
  t.autoZeroActive = autoZeroActive_;
  t.ChargedEnergy_AllTime_Wh = chargedEnergyLifetimeWh();
  t.DischargedEnergy_AllTime_Wh = ledger_.DischargedEnergy_AllTime_Wh + discharged_.lifetimeFraction_Wh;
  t.AlternatorChargedEnergy_AllTime_Wh = alternatorChargedEnergyLifetimeWh();
  t.SolarChargedEnergy_AllTime_Wh = ledger_.SolarChargedEnergy_AllTime_Wh + solar_.lifetimeFraction_Wh;
  t.AlternatorFuelUsed_AllTime_L = ledger_.AlternatorFuelUsed_AllTime_L;
  t.AlternatorOnTime_AllTime_s = ledger_.AlternatorOnTime_AllTime_s;
  t.nominalVoltage = nominalVoltage_;
  t.usingVictronCurrent = usingVictron_;
  t.capacity_measured_ah = capacity_.measuredAh();
  t.capacity_cycles = capacity_.cycles();
  t.battery_r_mohm = resistance_.medianMohm();
  t.battery_r_spread_mohm = resistance_.spreadMohm();
  t.battery_r_samples = resistance_.samples();
}

}  // namespace xr
