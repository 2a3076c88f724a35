#pragma once
// SoC and energy figures exported per tick. Owned by daemon/battery.
#include <limits>

namespace xr {

inline constexpr double kNoHealthValue = std::numeric_limits<double>::quiet_NaN();

// Where the SoC figure comes from (docs/batteries.md "State of charge at
// first start"): the dashboard shows no number while it is Unknown, and "≈"
// while it is an OcvEstimate.
enum class SocSource { Unknown = 0, OcvEstimate = 1, Counted = 2 };

struct BatteryTelemetry {
  double SOC_percent = 0.0;
  bool socKnown = false;  // false while SOC_percent is only the start-up guess (dashboard shows "estimate")
  SocSource socSource = SocSource::Unknown;  // not visited: the status JSON names it (soc_source)
  double CoulombCount_Ah = 0.0;
  double batteryCurrentForSoC = 0.0;
  bool FullChargeDetected = false;
  double ChargedEnergy_Wh = 0.0, DischargedEnergy_Wh = 0.0, AlternatorChargedEnergy_Wh = 0.0,
         SolarChargedEnergy_Wh = 0.0;
  double AlternatorOnTime_s = 0.0;
  double AlternatorFuelUsed_L = 0.0;
  double ChargeCycles = 0.0, ChargeCycles_AllTime = 0.0;
  double AvgSOC = 0.0, AvgSOC_AllTime = 0.0, AvgVoltage_AllTime = 0.0;
  double timeToFullChargeMin = -999.0, timeToFullDischargeMin = -999.0;
  double DynamicShuntGainFactor = 1.0;
  double DynamicAltCurrentZero = 0.0;
  bool autoZeroActive = false;
  // Lifetime figures (whole + retained fraction) and the detected system class.
  double ChargedEnergy_AllTime_Wh = 0.0, DischargedEnergy_AllTime_Wh = 0.0,
         AlternatorChargedEnergy_AllTime_Wh = 0.0, SolarChargedEnergy_AllTime_Wh = 0.0;
  double AlternatorFuelUsed_AllTime_L = 0.0;
  double AlternatorOnTime_AllTime_s = 0.0;
  int nominalVoltage = 12;           // 12 / 24 / 48 from the battery voltage (cycle counter)
  bool usingVictronCurrent = false;  // BatteryCurrentSource = 3 and VE.Direct fresh
  // Health (docs/batteries.md "Measured capacity", "Internal resistance"):
  // NaN until there is enough data for a figure.
  double capacity_measured_ah = kNoHealthValue;
  int capacity_cycles = 0;                        // swings of >= 30 % the figure rests on
  double battery_r_mohm = kNoHealthValue;         // median, corrected to 25 degC
  double battery_r_spread_mohm = kNoHealthValue;  // standard deviation of the samples
  int battery_r_samples = 0;
};

// Visits every field as f("name", value) — the one list the status JSON
// and any other exporter use, so a new field is exported by adding it here.
template <typename T, typename F>
void visitBatteryTelemetry(T& t, F&& f) {
  f("SOC_percent", t.SOC_percent);
  f("socKnown", t.socKnown);
  f("CoulombCount_Ah", t.CoulombCount_Ah);
  f("batteryCurrentForSoC", t.batteryCurrentForSoC);
  f("FullChargeDetected", t.FullChargeDetected);
  f("ChargedEnergy_Wh", t.ChargedEnergy_Wh);
  f("DischargedEnergy_Wh", t.DischargedEnergy_Wh);
  f("AlternatorChargedEnergy_Wh", t.AlternatorChargedEnergy_Wh);
  f("SolarChargedEnergy_Wh", t.SolarChargedEnergy_Wh);
  f("AlternatorOnTime_s", t.AlternatorOnTime_s);
  f("AlternatorFuelUsed_L", t.AlternatorFuelUsed_L);
  f("ChargeCycles", t.ChargeCycles);
  f("ChargeCycles_AllTime", t.ChargeCycles_AllTime);
  f("AvgSOC", t.AvgSOC);
  f("AvgSOC_AllTime", t.AvgSOC_AllTime);
  f("AvgVoltage_AllTime", t.AvgVoltage_AllTime);
  f("timeToFullChargeMin", t.timeToFullChargeMin);
  f("timeToFullDischargeMin", t.timeToFullDischargeMin);
  f("DynamicShuntGainFactor", t.DynamicShuntGainFactor);
  f("DynamicAltCurrentZero", t.DynamicAltCurrentZero);
  f("autoZeroActive", t.autoZeroActive);
  f("ChargedEnergy_AllTime_Wh", t.ChargedEnergy_AllTime_Wh);
  f("DischargedEnergy_AllTime_Wh", t.DischargedEnergy_AllTime_Wh);
  f("AlternatorChargedEnergy_AllTime_Wh", t.AlternatorChargedEnergy_AllTime_Wh);
  f("SolarChargedEnergy_AllTime_Wh", t.SolarChargedEnergy_AllTime_Wh);
  f("AlternatorFuelUsed_AllTime_L", t.AlternatorFuelUsed_AllTime_L);
  f("AlternatorOnTime_AllTime_s", t.AlternatorOnTime_AllTime_s);
  f("nominalVoltage", t.nominalVoltage);
  f("usingVictronCurrent", t.usingVictronCurrent);
  f("capacity_measured_ah", t.capacity_measured_ah);
  f("capacity_cycles", t.capacity_cycles);
  f("battery_r_mohm", t.battery_r_mohm);
  f("battery_r_spread_mohm", t.battery_r_spread_mohm);
  f("battery_r_samples", t.battery_r_samples);
}

}  // namespace xr
