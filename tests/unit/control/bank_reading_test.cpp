// Not set up on any bank (docs/configuration.md "Not set up"): the core
// reads the bank class from the battery before any voltage trip is armed,
// scales the not-set-up limits to it, and stays at the 12 V limits when the
// reading fits no bank.
#include "control/bank_reading.h"

#include <gtest/gtest.h>

#include <cmath>

#include "config/param_sources.h"
#include "control/regulator.h"
#include "params/derived.h"

namespace xr {
namespace {

// The shipped catalogue, not set up, nobody naming the bank's size.
Params notSetUp() {
  ParamOrigins origins;
  return runningParams(Params{}, origins);
}

// Healthy sensors with the battery at `volts` (NaN: no reading yet).
Inputs readingOf(TimeNs now, double volts) {
  Inputs in;
  in.now = now;
  in.inaPresent = true;
  if (std::isfinite(volts)) {
    in.IBV = {volts, now, true};
    in.BatteryV = {volts, now, true};
    in.Bcur = {2.0, now, true};
    in.inaDiagStamp = now;
  }
  in.altCurrentRaw = {5.0, now, true};
  in.rpm = {2000.0, now, true};
  in.thermistorF = {100.0, now, true};
  in.AlternatorTemperatureF = {100.0, now, true};
  in.tempTaskHeartbeat = now;
  in.ignitionOn = true;
  in.bmsChargeEnabled = true;
  return in;
}

struct RunSummary {
  bool alarm = false;
  int trips = 0;  // Error or Critical events
  bool fieldOn = false;
};

// Steps `seconds` at 2.5 ms with the battery at `volts`.
RunSummary runAt(Regulator& reg, TimeNs& now, double volts, double seconds) {
  RunSummary r;
  for (long i = 0; i < std::lround(seconds / 0.0025); ++i) {
    now += fromSec(0.0025);
    const Outputs& o = reg.step(readingOf(now, volts));
    r.alarm = r.alarm || o.buzzer;
    r.fieldOn = r.fieldOn || o.fieldEnable;
    for (std::size_t k = 0; k < o.events.count; ++k) r.trips += o.events.items[k].level >= EventLevel::Error;
  }
  return r;
}

TEST(BankReading, ClassOfAReadingAtItsWindowEdges) {
  EXPECT_EQ(bankClassOfReading(10.0), SystemClass::V12);
  EXPECT_EQ(bankClassOfReading(16.0), SystemClass::V12);
  EXPECT_EQ(bankClassOfReading(20.0), SystemClass::V24);
  EXPECT_EQ(bankClassOfReading(26.0), SystemClass::V24);
  EXPECT_EQ(bankClassOfReading(32.0), SystemClass::V24);
  EXPECT_EQ(bankClassOfReading(40.0), SystemClass::V48);
  EXPECT_EQ(bankClassOfReading(64.0), SystemClass::V48);
}

TEST(BankReading, AReadingThatFitsNoBankPicksNoClass) {
  for (double v : {0.0, 9.99, 16.01, 18.0, 19.99, 32.01, 36.0, 39.99, 64.01, double(NAN)})
    EXPECT_FALSE(bankClassOfReading(v).has_value()) << v;
}

TEST(BankReading, RunningSetReadsTheBankOnlyWhileNobodyNamedItsSize) {
  EXPECT_TRUE(notSetUp().SetupBankFromBattery);
  ParamOrigins named;
  named.file = {"BulkVoltage"};
  EXPECT_FALSE(runningParams(Params{}, named).SetupBankFromBattery);
  ParamOrigins cells;
  cells.dashboard = {"BatteryCells"};
  Params eight;
  eight.BatteryCells = 8;
  EXPECT_FALSE(runningParams(eight, cells).SetupBankFromBattery);
  // The shipped file's BatteryCells = 0 means "from the voltage class": it names no size.
  ParamOrigins shipped;
  shipped.file = {"BatteryCells", "BatteryCapacity_Ah"};
  EXPECT_TRUE(runningParams(Params{}, shipped).SetupBankFromBattery);
  ParamOrigins chosen;
  chosen.file = {"BatteryProfile"};
  EXPECT_FALSE(runningParams(Params{}, chosen).SetupBankFromBattery);
}

TEST(BankReading, WithBankClassScalesEveryBankVoltageAndWhatFollowsIt) {
  Params in = notSetUp();
  in.AlternatorHardShutdownV = 14.8;
  const Params p = withBankClass(in, SystemClass::V24);
  EXPECT_DOUBLE_EQ(p.BulkVoltage, 28.0);
  EXPECT_DOUBLE_EQ(p.FloatVoltage, 26.8);
  EXPECT_DOUBLE_EQ(p.SetupCeilingV, 28.0);
  EXPECT_DOUBLE_EQ(p.AlternatorHardShutdownV, 29.6);
  EXPECT_DOUBLE_EQ(voltageAlarmHighV(p), 30.0);
  EXPECT_DOUBLE_EQ(voltageAlarmLowV(p), 22.0);
  EXPECT_NEAR(voltageHardwareLimit(p), 28.3, 1e-9);
  EXPECT_DOUBLE_EQ(p.OvMeasMarginV, in.OvMeasMarginV);  // a margin, not a bank voltage
  EXPECT_FALSE(p.SetupBankFromBattery);
}

TEST(BankReading, FieldOffAndBusLimitAboveEveryBankUntilTheFirstReading) {
  Regulator reg(notSetUp());
  TimeNs now = fromSec(1.0);
  const RunSummary r = runAt(reg, now, NAN, 1.0);
  EXPECT_FALSE(r.fieldOn);
  EXPECT_EQ(r.trips, 0);
  EXPECT_DOUBLE_EQ(reg.outputs().inaBovlVolts, kBankReadingBovlV);
  EXPECT_FALSE(reg.outputs().telemetry.setupBank.fromBattery);
}

TEST(BankReading, TwentyFourVoltBankGetsTheTwentyFourVoltLimitsWithNoAlarm) {
  Regulator reg(notSetUp());
  TimeNs now = fromSec(1.0);
  const RunSummary r = runAt(reg, now, 26.0, 3.0);
  const Telemetry::SetupBank& b = reg.outputs().telemetry.setupBank;
  EXPECT_TRUE(b.fromBattery);
  EXPECT_EQ(b.classV, 24);
  EXPECT_TRUE(b.fits);
  EXPECT_DOUBLE_EQ(b.readV, 26.0);
  EXPECT_DOUBLE_EQ(reg.params().BulkVoltage, 28.0);
  EXPECT_NEAR(reg.outputs().inaBovlVolts, 28.3, 1e-9);
  EXPECT_FALSE(r.alarm);
  EXPECT_EQ(r.trips, 0);
  EXPECT_TRUE(r.fieldOn);  // it charges, within 28 V
  EXPECT_LE(reg.outputs().telemetry.target_v, 28.0 + 1e-9);
}

TEST(BankReading, FortyEightVoltBankAtTheTopOfItsWindow) {
  Regulator reg(notSetUp());
  TimeNs now = fromSec(1.0);
  runAt(reg, now, 40.0, 0.1);
  EXPECT_EQ(reg.outputs().telemetry.setupBank.classV, 48);
  EXPECT_DOUBLE_EQ(reg.params().BulkVoltage, 56.0);
}

TEST(BankReading, EighteenVoltsFitsNoBankAndKeepsTheTwelveVoltLimits) {
  Regulator reg(notSetUp());
  TimeNs now = fromSec(1.0);
  runAt(reg, now, 18.0, 0.1);
  const Telemetry::SetupBank& b = reg.outputs().telemetry.setupBank;
  EXPECT_TRUE(b.fromBattery);
  EXPECT_FALSE(b.fits);
  EXPECT_EQ(b.classV, 12);
  EXPECT_DOUBLE_EQ(reg.params().BulkVoltage, 14.0);
}

TEST(BankReading, ZeroVoltsFitsNoBankAndKeepsTheTwelveVoltLimits) {
  Regulator reg(notSetUp());
  TimeNs now = fromSec(1.0);
  runAt(reg, now, 0.0, 0.1);
  EXPECT_FALSE(reg.outputs().telemetry.setupBank.fits);
  EXPECT_DOUBLE_EQ(reg.params().BulkVoltage, 14.0);
  EXPECT_FALSE(reg.outputs().fieldEnable);  // 0 V is no bank: the sensor checks hold the field
}

TEST(BankReading, NoReadingWithinFiveSecondsKeepsTheTwelveVoltLimits) {
  Regulator reg(notSetUp());
  TimeNs now = fromSec(1.0);
  runAt(reg, now, NAN, 4.9);
  EXPECT_FALSE(reg.outputs().telemetry.setupBank.fromBattery);
  runAt(reg, now, NAN, 0.2);
  const Telemetry::SetupBank& b = reg.outputs().telemetry.setupBank;
  EXPECT_TRUE(b.fromBattery);
  EXPECT_FALSE(b.fits);
  EXPECT_TRUE(std::isnan(b.readV));
  EXPECT_DOUBLE_EQ(reg.params().BulkVoltage, 14.0);
}

TEST(BankReading, ASetUpSetDoesNotReadTheBank) {
  Params p;
  p.BulkVoltage = p.AbsorptionVoltage = 28.8;
  p.FloatVoltage = 27.0;
  Regulator reg(p);
  TimeNs now = fromSec(1.0);
  runAt(reg, now, 26.0, 0.1);
  EXPECT_FALSE(reg.outputs().telemetry.setupBank.fromBattery);
  EXPECT_DOUBLE_EQ(reg.params().BulkVoltage, 28.8);
}

TEST(BankReading, ANewNotSetUpSetReadsTheBankAgain) {
  Regulator reg(notSetUp());
  TimeNs now = fromSec(1.0);
  runAt(reg, now, 26.0, 0.1);
  reg.setParams(notSetUp());
  EXPECT_DOUBLE_EQ(reg.params().BulkVoltage, 14.0);
  runAt(reg, now, 26.0, 0.1);
  EXPECT_DOUBLE_EQ(reg.params().BulkVoltage, 28.0);
}

// The first tick before the engine speed was read: the field waits off, but
// no "Exiting normal mode: RPM_LOW" row (docs/protections.md "First readings").
TEST(FirstReadings, NoModeChangeRowBeforeTheFirstEngineSpeed) {
  Params p;
  p.BulkVoltage = p.AbsorptionVoltage = 14.4;
  Regulator reg(p);
  Inputs in = readingOf(fromSec(1.0), 12.8);
  in.rpm = {};
  const Outputs& o = reg.step(in);
  EXPECT_FALSE(o.fieldEnable);
  for (std::size_t k = 0; k < o.events.count; ++k) EXPECT_NE(o.events.items[k].code, EventCode::ModeChanged);
  // A reading that is really low still says so.
  Inputs low = readingOf(fromSec(1.1), 12.8);
  low.rpm = {100.0, low.now, true};
  const Outputs& o2 = reg.step(low);
  bool rpmLow = false;
  for (std::size_t k = 0; k < o2.events.count; ++k)
    rpmLow = rpmLow || o2.events.items[k].reason == Reason::REASON_RPM_LOW;
  EXPECT_TRUE(rpmLow);
}

// The part on its own: it waits until kWait without a reading, not a
// nanosecond less; a reading settles at once; restart() reads again.
TEST(BankReadingPart, WaitsTheWholeWaitThenTheTwelveVoltClass) {
  BankReading b;
  const Reading none;
  EXPECT_FALSE(b.update(none, fromSec(1.0)).has_value());
  EXPECT_FALSE(b.update(none, fromSec(1.0) + BankReading::kWait - 1).has_value());
  EXPECT_EQ(b.update(none, fromSec(1.0) + BankReading::kWait), std::optional<SystemClass>(SystemClass::V12));
  EXPECT_TRUE(b.shown().fromBattery);
  EXPECT_FALSE(b.shown().fits);
}

TEST(BankReadingPart, AReadingSettlesAtOnceAndRestartReadsAgain) {
  BankReading b;
  const Reading v24{25.6, fromSec(1.0), true};
  EXPECT_EQ(b.update(v24, fromSec(1.0)), std::optional<SystemClass>(SystemClass::V24));
  EXPECT_TRUE(b.shown().fits);
  EXPECT_EQ(b.shown().classV, 24);
  b.restart();
  EXPECT_FALSE(b.shown().fromBattery);
  EXPECT_FALSE(b.update(Reading{}, fromSec(2.0)).has_value());
}

}  // namespace
}  // namespace xr
