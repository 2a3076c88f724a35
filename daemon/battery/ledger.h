#pragma once
// The battery and regulator state that must survive a restart
// (docs/operations.md). One plain struct: the store saves and restores it whole, through
// visitLedgerFields() so adding a field here is the only edit needed.
namespace xr {

struct BatteryLedger {
  double CoulombCount_Ah = 0.0;        // SoC = CoulombCount_Ah / BatteryCapacity_Ah
  double coulombAccumulator_Ah = 0.0;  // retained remainder
  double DynamicShuntGainFactor = 1.0;
  double DynamicAltCurrentZero = 0.0;
  double ChargedEnergy_AllTime_Wh = 0.0;
  double DischargedEnergy_AllTime_Wh = 0.0;
  double AlternatorChargedEnergy_AllTime_Wh = 0.0;
  double SolarChargedEnergy_AllTime_Wh = 0.0;
  double socAccumulator_AllTime = 0.0;          // %·s
  double totalSocSampleTime_AllTime = 0.0;      // s
  double voltageAccumulator_AllTime = 0.0;      // V·s
  double totalVoltageSampleTime_AllTime = 0.0;  // s
  double AlternatorFuelUsed_AllTime_L = 0.0;
  double AlternatorOnTime_AllTime_s = 0.0;
  // Where CoulombCount_Ah comes from (SocSource in battery_telemetry.h):
  // 0 unknown, 1 an estimate from the rested voltage, 2 counted from a
  // known point (a full charge or a value set). A database from before this
  // field has no row for it and keeps 2, what those releases assumed.
  double SocSource = 2.0;
  bool valid = false;  // false until restored from the store or initialised

  bool operator==(const BatteryLedger&) const = default;
};

// Calls f(name, double&) for each numeric field (names are the seeds').
template <typename L, typename F>
void visitLedgerFields(L& l, F&& f) {
  f("CoulombCount_Ah", l.CoulombCount_Ah);
  f("coulombAccumulator_Ah", l.coulombAccumulator_Ah);
  f("DynamicShuntGainFactor", l.DynamicShuntGainFactor);
  f("DynamicAltCurrentZero", l.DynamicAltCurrentZero);
  f("ChargedEnergy_AllTime", l.ChargedEnergy_AllTime_Wh);
  f("DischargedEnergy_AllTime", l.DischargedEnergy_AllTime_Wh);
  f("AlternatorChargedEnergy_AllTime", l.AlternatorChargedEnergy_AllTime_Wh);
  f("SolarChargedEnergy_AllTime", l.SolarChargedEnergy_AllTime_Wh);
  f("socAccumulator_AllTime", l.socAccumulator_AllTime);
  f("totalSocSampleTime_AllTime", l.totalSocSampleTime_AllTime);
  f("voltageAccumulator_AllTime", l.voltageAccumulator_AllTime);
  f("totalVoltageSampleTime_AllTime", l.totalVoltageSampleTime_AllTime);
  f("AlternatorFuelUsed_AllTime", l.AlternatorFuelUsed_AllTime_L);
  f("AlternatorOnTime_AllTime", l.AlternatorOnTime_AllTime_s);
  f("SocSource", l.SocSource);
}

}  // namespace xr
