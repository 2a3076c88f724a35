#pragma once
// SoC and energy figures exported per tick. Owned by daemon/battery.
namespace xr {

struct BatteryTelemetry {
  double SOC_percent = 0.0;
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
};

}  // namespace xr
