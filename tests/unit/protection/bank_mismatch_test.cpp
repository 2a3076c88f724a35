// Bank size check (a deviation, docs/deviations.md "Bank size check"): settings for
// one bank size on a bank of another — a whole 24 V [voltage] section on a
// 12 V bank, which passes every per-value and set check because it is
// consistent in itself. Every live voltage sensor reading another bank class
// than BulkVoltage's for 5 s cuts the field at once, in every mode, until
// the readings and the settings agree.
#include <gtest/gtest.h>

#include <limits>

#include "params/derived.h"
#include "part_log.h"
#include "rig.h"

namespace xr::test {
namespace {

using M = FieldControlMode;

// The reproducer's file: BulkVoltage 28.8, AbsorptionVoltage 28.6,
// FloatVoltage 27.0, with the other bank voltages of the 24 V class.
Params params24V() {
  Params p;
  p.BulkVoltage = 28.8;
  p.AbsorptionVoltage = 28.6;
  p.FloatVoltage = 27.0;
  return p;
}

// A 24 V file on a 12 V bank: both sensors on the 12 V class's top edge.
void twelveVoltBank(Rig& r, double volts) { r.ibv = r.batteryV = volts; }

TEST(BankMismatch, TheTestFileIsA24VoltSetThatPassesTheSetChecks) {
  const Params p = params24V();
  EXPECT_EQ(systemClass(p), SystemClass::V24);
  EXPECT_EQ(bankClassOfVoltage(17.99), SystemClass::V12);
  EXPECT_EQ(bankClassOfVoltage(18.0), SystemClass::V24);
}

TEST(BankMismatch, CutsTheFieldAfterFiveSecondsOnA12VoltBank) {
  Rig r(params24V());
  twelveVoltBank(r, 17.99);
  r.warmUp();
  r.log.clear();
  const TimeNs took = r.runUntil([&] { return r.d.reason == Reason::REASON_BANK_MISMATCH; }, fromSec(7.0));
  ASSERT_GE(took, 0) << "a 24 V set-point ran on a 12 V bank";
  // warmUp() ran 2 s of the 5 s already.
  EXPECT_GE(took, fromSec(3.0) - 2 * kTick);
  EXPECT_LE(took, fromSec(3.0) + 2 * kTick);
  EXPECT_EQ(r.d.mode, M::MODE_CRITICAL_RAMP);
  // Immediate cut: GPIO4 LOW and duty 0 in the same tick.
  EXPECT_FALSE(r.sc.fieldEnable);
  EXPECT_EQ(r.sc.dutyPct, 0.0);
  EXPECT_TRUE(r.sc.applyImmediateCut);
  EXPECT_TRUE(r.sup.flags().bankMismatch);
  EXPECT_EQ(r.sup.telemetry().lastTripReason, Reason::REASON_BANK_MISMATCH);
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_BANK_MISMATCH), 1u);
  EXPECT_EQ(r.count(EventCode::ImmediateCut, Reason::REASON_BANK_MISMATCH), 1u);
}

TEST(BankMismatch, DoesNotActAtTheBankBoundary) {
  Rig r(params24V());
  twelveVoltBank(r, 18.0);  // a deeply discharged 24 V bank is still a 24 V bank
  r.warmUp();
  EXPECT_EQ(r.runUntil([&] { return r.d.reason == Reason::REASON_BANK_MISMATCH; }, fromSec(20.0)), -1);
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_AUTO_PID);
}

TEST(BankMismatch, ACrankingDipShorterThanTheHoldDoesNotAct) {
  Rig r(params24V());
  r.ibv = r.batteryV = 25.6;
  r.warmUp();
  twelveVoltBank(r, 14.0);  // 24 V starter dip
  r.run(fromMs(4900));
  r.ibv = r.batteryV = 24.8;
  r.run(fromSec(10.0));
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_BANK_MISMATCH), 0u);
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_AUTO_PID);
}

TEST(BankMismatch, OneSensorInAnotherClassIsADisagreementNotAMismatch) {
  Rig r(params24V());
  r.ibv = 25.6;
  r.batteryV = 13.0;
  r.warmUp();
  r.run(fromSec(10.0));
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_BANK_MISMATCH), 0u);
  EXPECT_FALSE(r.sup.flags().bankMismatch);
  EXPECT_TRUE(r.sup.flags().voltageDisagreeCritical);
}

TEST(BankMismatch, WithoutTheIna228TheAdcAloneDecides) {
  Params p = params24V();
  p.INADisconnected = true;
  Rig r(p);
  r.ibv = std::numeric_limits<double>::quiet_NaN();
  r.batteryV = 13.2;
  r.limp = true;  // without the INA228 only MANUAL and Limp Home run
  r.warmUp();
  ASSERT_GE(r.runUntil([&] { return r.d.reason == Reason::REASON_BANK_MISMATCH; }, fromSec(6.0)), 0);
  EXPECT_FALSE(r.sc.fieldEnable);
}

// Unlike the voltage protections of the specification's table, it acts in MANUAL and
// Limp Home: Limp Home's only voltage guard is the hard shutdown, which a
// 24 V file puts at 29.1 V.
TEST(BankMismatch, ActsInManualAndLimpHome) {
  for (int mode = 0; mode < 2; ++mode) {
    Rig r(params24V());
    r.manual = mode == 0;
    r.limp = mode == 1;
    twelveVoltBank(r, 13.1);
    r.warmUp();
    const TimeNs took = r.runUntil([&] { return r.d.reason == Reason::REASON_BANK_MISMATCH; }, fromSec(6.0));
    ASSERT_GE(took, 0) << (r.manual ? "MANUAL" : "Limp Home");
    EXPECT_FALSE(r.sc.fieldEnable);
    EXPECT_EQ(r.sc.dutyPct, 0.0);
  }
}

TEST(BankMismatch, HeldWhileItLastsWithOneEventThenNormalWhenTheSettingsMatch) {
  Rig r(params24V());
  twelveVoltBank(r, 13.1);
  r.warmUp();
  ASSERT_GE(r.runUntil([&] { return r.d.reason == Reason::REASON_BANK_MISMATCH; }, fromSec(6.0)), 0);
  r.run(fromSec(120.0));  // well past any lockout
  EXPECT_EQ(r.d.reason, Reason::REASON_BANK_MISMATCH);
  EXPECT_FALSE(r.sc.fieldEnable);
  EXPECT_EQ(r.count(EventCode::ProtectionTrip, Reason::REASON_BANK_MISMATCH), 1u);
  EXPECT_EQ(r.count(EventCode::ImmediateCut, Reason::REASON_BANK_MISMATCH), 1u);
  EXPECT_EQ(r.count(EventCode::LockoutStarted), 0u);

  // The owner loads the 12 V values: normal on the next tick, no cooldown.
  r.setParams(Params{});
  r.tick();
  EXPECT_EQ(r.d.mode, M::MODE_NORMAL_AUTO_PID);
  EXPECT_TRUE(r.sc.fieldEnable);
  EXPECT_FALSE(r.sup.flags().bankMismatch);
}

// The other direction: 12 V settings on a 24 V bank. The hard shutdown
// (BulkVoltage + 0.3 V) acts first, with its lockout; after 5 s the bank
// check names the cause and holds the field off after the lockout.
TEST(BankMismatch, TwelveVoltSettingsOnA24VoltBankAreHeldOffToo) {
  Rig r;
  r.ibv = r.batteryV = 13.5;
  r.warmUp();
  r.ibv = r.batteryV = 25.8;
  r.tick();
  EXPECT_EQ(r.d.reason, Reason::REASON_ALT_HARD_SHUTDOWN);
  EXPECT_FALSE(r.sc.fieldEnable);
  ASSERT_GE(r.runUntil([&] { return r.sup.flags().bankMismatch; }, fromSec(6.0)), 0);
  EXPECT_EQ(r.d.reason, Reason::REASON_BANK_MISMATCH);
  r.run(fromSec(60.0));
  EXPECT_EQ(r.d.reason, Reason::REASON_BANK_MISMATCH);
  EXPECT_FALSE(r.sc.fieldEnable);
  EXPECT_EQ(r.sup.telemetry().lastTripReason, Reason::REASON_BANK_MISMATCH);
}

}  // namespace
}  // namespace xr::test

// The part on its own (BankMismatchCheck::update): held kHoldMs, not just
// under it; one live sensor reading the configured bank keeps it off.
namespace xr::test {
namespace {

TEST(BankMismatchPart, TripsAfterItsHoldNotJustBefore) {
  Params p;  // a 12 V bank (BulkVoltage 14.5 V)
  BankMismatchCheck check;
  PartLog log;
  auto tick = [&](double ibv, double batteryV, TimeNs dt) {
    log.t += dt;
    check.update({ibv, batteryV}, p, log.at());
    log.collect();
  };
  tick(27.0, 13.0, fromMs(5));
  tick(27.0, 13.0, fromMs(BankMismatchCheck::kHoldMs));
  EXPECT_FALSE(check.mismatch());  // one sensor still reads the 12 V bank
  tick(27.0, 27.0, fromMs(5));
  tick(27.0, 27.0, fromMs(BankMismatchCheck::kHoldMs) - fromMs(10));
  EXPECT_FALSE(check.mismatch());
  tick(27.0, 27.0, fromMs(10));
  EXPECT_TRUE(check.mismatch());
  EXPECT_EQ(log.count(EventCode::ProtectionTrip, Reason::REASON_BANK_MISMATCH), 1u);
  tick(13.0, 13.0, fromMs(5));
  EXPECT_FALSE(check.mismatch());
}

}  // namespace
}  // namespace xr::test
