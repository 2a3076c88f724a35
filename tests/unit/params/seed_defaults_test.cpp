// Every default in the specification's quick-reference tables is the catalogue's default
// (docs/parameters.md). One row per entry of the specification: name, its value in the
// catalogue's unit, and where the specification states it. Newer specification documents win over
// the original firmware's description where they disagree (docs/architecture.md); the legacy "Key
// Parameters Reference" column is labelled "Example Default" and its rows that
// newer specification documents replaced are listed in SupersededLegacyExamples below.
#include <gtest/gtest.h>

#include <string_view>

#include "params/derived.h"
#include "params/params.h"

namespace xr {
namespace {

struct SeedDefault {
  std::string_view name;
  double value;
  std::string_view source;
};

// Values converted to the catalogue unit (e.g. FIELD_COLLAPSE_DELAY 30 s -> 30000 ms).
constexpr SeedDefault kScalarDefaults[] = {
    // the protections specification "Quick Reference — User-Settable Parameters": Voltage OV throttling
    {"OvGroup1Enable", 1, "S&P quick ref: on"},
    {"OvGroup2Enable", 1, "S&P quick ref: on"},
    {"OvPredMarginV", 0.150, "S&P quick ref"},
    {"OvMeasMarginV", 0.100, "S&P quick ref"},
    {"KHard", 35, "S&P quick ref"},
    {"TdPred", 0.045, "S&P quick ref"},
    {"DvdtAlpha", 0.08, "S&P quick ref"},
    {"IExcessK", 5, "S&P quick ref"},
    {"IExcessN", 3, "S&P quick ref"},
    {"IExcessKBleed", 0, "S&P quick ref: 0 (snap)"},
    {"IExcessReseedFrac", 0.5, "S&P quick ref"},
    {"IExcessSigSrc", 0, "S&P quick ref: MA(N) (0 = MA in the catalogue)"},
    {"LoadDumpDtThresh1", 4000, "S&P quick ref"},
    {"LoadDumpDtThresh", 1500, "S&P quick ref"},
    {"LoadDumpDtThresh3", 1000, "S&P quick ref"},
    {"ProtectionProxGateV", 0.5, "S&P quick ref"},
    {"AwBleedRate", 2.0, "S&P quick ref"},
    {"AwRecoverRate", 0.1, "S&P quick ref"},
    {"AwSeedProtectMs", 150, "S&P quick ref; the field-control specification quick ref"},
    {"SlopeBleedThresh", 0.5, "S&P quick ref"},
    {"SlopeBleedK", 50, "S&P quick ref"},
    {"SlopeBleedProxV", 0.5, "S&P quick ref"},
    // Voltage shutdown / sensor health
    {"VoltageDisagreeThreshold", 0.15, "S&P quick ref"},
    {"VoltageDisagreeTimeout", 10, "S&P quick ref: 10 s"},
    {"FIELD_COLLAPSE_DELAY", 30000,
     "S&P quick ref: 30 s; the field-control specification quick ref: 30000 ms"},
    {"SettleTimeBeforeCut", 1000, "S&P quick ref; the field-control specification quick ref"},
    // Shutdown ramp shape
    {"DutyRampRate", 50, "S&P quick ref; the field-control specification quick ref"},
    {"DutySlowRampRate", 1, "S&P quick ref; the field-control specification quick ref"},
    {"ShutdownPhase2HoldMs", 0, "S&P quick ref: 0 (skip)"},
    // Temperature
    {"TemperatureLimitF", 150, "S&P quick ref"},
    {"TempWarnExcess", 2, "S&P quick ref (legacy example 10 superseded)"},
    {"TempCritExcess", 10, "S&P quick ref (legacy example 30 superseded)"},
    {"TempSustainedTimeout", 120, "S&P quick ref: 120 s; legacy 120000 ms"},
    {"TempAlarmLow", 32, "S&P quick ref"},
    {"ThermalLookaheadSec", 450,
     "changed here; the specification's S&P quick ref and the field-control specification quick ref 90"},
    // Added here (docs/deviations.md "Thermal loop"): the specification's 3 and 0.025
    // (S&P quick ref) overshot the limit on an idle-to-cruise step.
    {"TempPIDKp", 5.0, "changed here; the specification's S&P quick ref 3"},
    {"TempPIDKi", 0.06, "changed here; the specification's S&P quick ref 0.025"},
    {"TempPIDFilterAlpha", 0.2, "S&P quick ref; the field-control specification quick ref"},
    {"TempPIDIntervalMs", 5000, "S&P quick ref; the field-control specification quick ref"},
    {"ThermalPenaltyRiseRate", 60, "S&P quick ref; the field-control specification quick ref"},
    {"ThermalPenaltyFallRate", 20, "S&P quick ref; the field-control specification quick ref"},
    {"IgnoreTemperature", 0, "S&P quick ref"},
    // Overcurrent / RPM
    {"HardOCDebounceMs", 20, "S&P quick ref"},
    // Added here (docs/deviations.md "CurrentAlarmHigh follows the cap"): 0 = 10 %
    // above the commandable current; the specification's S&P quick ref has 100 A.
    {"CurrentAlarmHigh", 0, "added here; the specification's S&P quick ref 100"},
    {"MaximumAllowedBatteryAmps", 150, "S&P quick ref"},
    {"MinRPMForField", 200, "S&P quick ref"},
    {"IgnoreRPM", 0, "S&P quick ref"},
    // the field-control specification "Slew Rates and Time Constants — Quick Reference"
    {"SetpointRiseRate", 30, "FC quick ref"},
    {"SetpointFallRate", 50, "FC quick ref"},
    {"StartupRiseRate", 3, "FC quick ref"},
    {"VoltageLoopInterval", 100, "FC quick ref; Three Control Loops (legacy example 500 superseded)"},
    {"DvdtTC", 58, "FC quick ref"},
    // the field-control specification text defaults
    {"PIDTrackingGain", 4.0, "FC Output Current PID: 4.0/sec"},
    {"bulkVoltageHoldMs", 30000, "FC BULK: default 30 s"},
    {"absorptionCompleteTime", 30000, "FC ABSORPTION: default 30 s"},
    {"AbsorptionTimeoutMs", 3600000, "FC ABSORPTION: default 60 min"},
    {"MinFloatTime", 300000, "FC FLOAT: default 5 min"},
    {"rebulkDebounceTime", 60000, "FC FLOAT: default 60 s"},
    // the battery specification
    {"SOCUpdateInterval", 2000, "BM: every 2 s (SOCUpdateInterval)"},
    // the specification implies BulkVoltage = 14.5 V (hard shutdown 14.8 V = Bulk + 0.3)
    {"BulkVoltage", 14.5, "S&P Cascade (Default 12 V Settings)"},
};

struct SeedTable {
  std::string_view name;
  RpmTable value;
};

// the field-control specification "RPM Tables".
const SeedTable kTableDefaults[] = {
    {"rpmTableRPMPoints", {100, 600, 1100, 1600, 2100, 2600, 3100, 3600, 4100, 4600}},
    {"rpmCurrentTable", {0, 50, 50, 50, 50, 50, 50, 50, 50, 50}},
    {"rpmCapCurrentTable", {0, 50, 50, 50, 50, 50, 50, 50, 50, 50}},
    {"rpmCapPowerTable", {0, 0, 0, 0, 0, 0, 0, 0, 0, 0}},
    {"rpmMinDutyTable", {5, 5, 4, 4, 3, 3, 2, 2, 1, 1}},
    // HiLow == 0 tables: "Defaults to one-quarter of the Normal-mode current values".
    {"rpmCapCurrentTableLo", {0, 12.5, 12.5, 12.5, 12.5, 12.5, 12.5, 12.5, 12.5, 12.5}},
    {"rpmCapPowerTableLo", {0, 0, 0, 0, 0, 0, 0, 0, 0, 0}},
    {"rpmMinDutyTableLo", {5, 5, 4, 4, 3, 3, 2, 2, 1, 1}},
};

class SeedScalarDefault : public ::testing::TestWithParam<SeedDefault> {};

TEST_P(SeedScalarDefault, IsTheCatalogueDefault) {
  const SeedDefault& d = GetParam();
  const ParamSpec* spec = findParam(d.name);
  ASSERT_NE(spec, nullptr) << d.name << " (" << d.source << ") is missing from the catalogue";
  EXPECT_DOUBLE_EQ(spec->defaultValue, d.value) << d.name << " (" << d.source << ")";
  EXPECT_DOUBLE_EQ(spec->get(Params{}, 0), d.value) << d.name << ": Params{} disagrees with the catalogue";
}

INSTANTIATE_TEST_SUITE_P(Specification, SeedScalarDefault, ::testing::ValuesIn(kScalarDefaults),
                         [](const auto& info) { return std::string(info.param.name); });

class SeedTableDefault : public ::testing::TestWithParam<SeedTable> {};

TEST_P(SeedTableDefault, IsTheCatalogueDefault) {
  const SeedTable& d = GetParam();
  const ParamSpec* spec = findParam(d.name);
  ASSERT_NE(spec, nullptr) << d.name;
  ASSERT_EQ(spec->kind, ParamKind::Table);
  for (std::size_t i = 0; i < RPM_TABLE_SIZE; ++i) {
    EXPECT_DOUBLE_EQ(spec->tableDefault[i], d.value[i]) << d.name << "[" << i << "]";
    EXPECT_DOUBLE_EQ(spec->get(Params{}, i), d.value[i]) << d.name << "[" << i << "]";
  }
}

INSTANTIATE_TEST_SUITE_P(Specification, SeedTableDefault, ::testing::ValuesIn(kTableDefaults),
                         [](const auto& info) { return std::string(info.param.name); });

// Derived defaults stated in the specification's quick-reference tables.
TEST(SeedDerivedDefaults, FirstBootHardShutdownIsBulkPlus0_3) {
  EXPECT_DOUBLE_EQ(Params{}.AlternatorHardShutdownV, 0.0);  // 0 = "not yet saved"
  EXPECT_DOUBLE_EQ(alternatorHardShutdownV(Params{}), 14.8);
}

// The specification's 190 degF buzzer beside its 150 degF limit: TempAlarm's 0 derives
// exactly that, and follows a raised limit by the same 40 degF
// (docs/deviations.md "Alarms follow their limits").
TEST(SeedDerivedDefaults, TempAlarmIs190AtTheSeedLimitAndFollowsARaisedOne) {
  Params p;
  EXPECT_DOUBLE_EQ(p.TempAlarm, 0.0);
  EXPECT_DOUBLE_EQ(tempAlarmF(p), 190.0);
  p.TemperatureLimitF = 194.0;  // 90 degC, as the set-up page saves it
  EXPECT_DOUBLE_EQ(tempAlarmF(p), 234.0);
  p.TempAlarm = 250.0;  // written by the owner: used as written
  EXPECT_DOUBLE_EQ(tempAlarmF(p), 250.0);
}

// The specification's 12 V alarm voltages (15 / 11 V) and the catalogue's former
// 12 V values scale with the bank of BulkVoltage.
TEST(SeedDerivedDefaults, BankVoltagesFollowTheBankOfBulkVoltage) {
  Params p;
  EXPECT_DOUBLE_EQ(voltageAlarmHighV(p), 15.0);
  EXPECT_DOUBLE_EQ(voltageAlarmLowV(p), 11.0);
  EXPECT_DOUBLE_EQ(chargedVoltageV(p), 13.8);
  EXPECT_DOUBLE_EQ(rebulkVoltageV(p), 12.9);
  EXPECT_DOUBLE_EQ(targetVoltageSetpointV(p), 13.6);
  p.BulkVoltage = 28.8;
  p.AbsorptionVoltage = 28.8;
  p.FloatVoltage = 27.0;
  EXPECT_DOUBLE_EQ(voltageAlarmHighV(p), 30.0);
  EXPECT_DOUBLE_EQ(voltageAlarmLowV(p), 22.0);
  EXPECT_DOUBLE_EQ(chargedVoltageV(p), 27.6);
  EXPECT_DOUBLE_EQ(rebulkVoltageV(p), 25.8);
  EXPECT_DOUBLE_EQ(targetVoltageSetpointV(p), 27.2);
  p.BulkVoltage = 29.9;  // an equalising bulk: the alarm stays above it
  EXPECT_DOUBLE_EQ(voltageAlarmHighV(p), 30.5);
  p.FloatVoltage = 25.7;  // a low float: the re-bulk stays under it
  EXPECT_DOUBLE_EQ(rebulkVoltageV(p), 25.5);
  p.VoltageAlarmHigh = 31.0;  // written by the owner: used as written
  EXPECT_DOUBLE_EQ(voltageAlarmHighV(p), 31.0);
}

TEST(SeedDerivedDefaults, HardwareLimitAndHardOcTrip) {
  const Params p;
  EXPECT_DOUBLE_EQ(voltageHardwareLimit(p), p.BulkVoltage + 0.3);
  EXPECT_DOUBLE_EQ(hardOCTripAmps(p), p.MaxTableValue + 10.0);
  EXPECT_DOUBLE_EQ(criticalDisagreementThreshold(p), 1.0);
}

// Legacy "Key Parameters Reference" names that newer specification documents replaced: they
// must NOT come back as separate parameters (one name per behaviour).
TEST(SupersededLegacyExamples, AreNotInTheCatalogue) {
  for (std::string_view legacy : {"PidSampleTime", "SetpointRampRate", "bulkCompleteTime",
                                  "VoltageSpikeMargin", "ForceFloat", "LearningMode", "MaxPenaltyDuration"}) {
    EXPECT_EQ(findParam(legacy), nullptr) << legacy;
  }
  // Their replacements are.
  for (std::string_view now : {"PidSampleDivisor", "SetpointRiseRate", "SetpointFallRate",
                               "bulkVoltageHoldMs", "AlternatorHardShutdownV", "MaintainMode"}) {
    EXPECT_NE(findParam(now), nullptr) << now;
  }
}

}  // namespace
}  // namespace xr
