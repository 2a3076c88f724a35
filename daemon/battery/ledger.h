#pragma once
// The battery and regulator state that must survive a restart
// (docs/operations.md). One plain struct: the store saves and restores it whole, through
// visitLedgerFields() so adding a field here is the only edit needed.
#include <array>
#include <cstddef>

namespace xr {

// What the measured capacity rests on (docs/batteries.md "Measured capacity"):
// the weighted sums of the swings measured so far, and the last point of
// known state of charge with the amp-hours counted since it.
struct CapacityLedger {
  double SumAh = 0.0;         // sum of |counted Ah| over the swings (older ones fade)
  double SumSwing = 0.0;      // sum of |SoC swing| (0..1) over the same swings
  double Cycles = 0.0;        // swings of at least 30 % measured
  double AnchorValid = 0.0;   // 1 while a known point is held
  double AnchorSocPct = 0.0;  // the SoC the point was known at
  double NetAh = 0.0;         // corrected Ah counted since the point (+ into the bank)
  double AnchorAge_s = 0.0;   // time since the point

  bool operator==(const CapacityLedger&) const = default;
};

// The bank's DC resistance (docs/batteries.md "Internal resistance"): the
// latest samples, each corrected to 25 degC, in a ring.
inline constexpr int kResistanceSamples = 16;
struct ResistanceLedger {
  std::array<double, kResistanceSamples> samples_mohm{};
  double count = 0.0;  // samples held (0..kResistanceSamples)
  double next = 0.0;   // where the next one goes

  bool operator==(const ResistanceLedger&) const = default;
};

// The alternator's wear (docs/operations.md "Alternator wear"): running time,
// time at or above each band of the measured temperature, and the share of
// the insulation's life used.
inline constexpr std::array<double, 4> kWearBandsF = {150.0, 175.0, 200.0, 225.0};
struct AlternatorWearLedger {
  double RunTime_s = 0.0;
  std::array<double, kWearBandsF.size()> TimeAbove_s{};
  double LifeUsed_pct = 0.0;
  double BeltSlipEvents = 0.0;

  bool operator==(const AlternatorWearLedger&) const = default;
};

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
  CapacityLedger capacity;
  ResistanceLedger resistance;
  AlternatorWearLedger wear;
  bool valid = false;  // false until restored from the store or initialised

  bool operator==(const BatteryLedger&) const = default;
};

// The health figures' fields (names of this project: the specification has none).
template <typename L, typename F>
void visitHealthLedgerFields(L& l, F&& f) {
  f("CapacitySumAh", l.capacity.SumAh);
  f("CapacitySumSwing", l.capacity.SumSwing);
  f("CapacityCycles", l.capacity.Cycles);
  f("CapacityAnchorValid", l.capacity.AnchorValid);
  f("CapacityAnchorSocPct", l.capacity.AnchorSocPct);
  f("CapacityNetAh", l.capacity.NetAh);
  f("CapacityAnchorAge_s", l.capacity.AnchorAge_s);
  static constexpr const char* kR[kResistanceSamples] = {
      "BatteryR00_mohm", "BatteryR01_mohm", "BatteryR02_mohm", "BatteryR03_mohm",
      "BatteryR04_mohm", "BatteryR05_mohm", "BatteryR06_mohm", "BatteryR07_mohm",
      "BatteryR08_mohm", "BatteryR09_mohm", "BatteryR10_mohm", "BatteryR11_mohm",
      "BatteryR12_mohm", "BatteryR13_mohm", "BatteryR14_mohm", "BatteryR15_mohm"};
  for (int i = 0; i < kResistanceSamples; ++i) f(kR[i], l.resistance.samples_mohm[i]);
  f("BatteryRCount", l.resistance.count);
  f("BatteryRNext", l.resistance.next);
  f("AltRunTime_s", l.wear.RunTime_s);
  static constexpr const char* kBands[kWearBandsF.size()] = {"AltTimeAbove150F_s", "AltTimeAbove175F_s",
                                                             "AltTimeAbove200F_s", "AltTimeAbove225F_s"};
  for (std::size_t i = 0; i < kWearBandsF.size(); ++i) f(kBands[i], l.wear.TimeAbove_s[i]);
  f("AltLifeUsed_pct", l.wear.LifeUsed_pct);
  f("BeltSlipEvents", l.wear.BeltSlipEvents);
}

// Calls f(name, double&) for each numeric field (names are the specification's).
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
  visitHealthLedgerFields(l, f);
}

}  // namespace xr
