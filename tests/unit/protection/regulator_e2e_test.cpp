// End to end through Regulator::step (control + protections + battery): the
// three shutdown paths, lockout, T2 re-enable, Limp Home and MANUAL gating,
// the buzzer — checked on the Outputs the runtime writes to PWM/GPIO4/GPIO21.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "control/regulator.h"

namespace xr::test {
namespace {

using M = FieldControlMode;
constexpr double kDt = 0.0025;

// A crude alternator: current follows duty (0.6 A/%) with a 0.1 s lag while
// the field is enabled, decays otherwise. Voltage is held by the battery.
struct E2E {
  Params p;
  Regulator reg;
  TimeNs now = fromSec(10.0);
  double ialt = 0.0;
  double ibv = 13.2, batteryV = 13.2, rpm = 2000.0, tempF = 100.0;
  bool ch1Frozen = false, inaAlert = false;
  TimeNs ch1Stamp = 0;
  const Outputs* out = nullptr;
  std::vector<Event> log;

  explicit E2E(const Params& params = Params{}) : p(params), reg(params) {}

  Inputs inputs() {
    Inputs in;
    in.now = now;
    in.inaPresent = true;
    in.inaFastModeActive = out ? out->inaFastMode : false;
    in.IBV = {ibv, now, true};
    in.Bcur = {ialt - 10.0, now, true};
    in.inaDiagStamp = now;
    in.inaBusOvervoltage = inaAlert;
    in.BatteryV = {batteryV, now, true};
    if (!ch1Frozen) ch1Stamp = now;
    in.altCurrentRaw = {ialt, ch1Stamp, !ch1Frozen};
    in.rpm = {rpm, now, true};
    in.AlternatorTemperatureF = {tempF, now, true};
    in.thermistorF = {tempF, now, true};
    in.tempTaskHeartbeat = now;
    return in;
  }

  const Outputs& tick() {
    now += fromSec(kDt);
    out = &reg.step(inputs());
    const double target = out->fieldEnable ? 0.6 * out->dutyPct : 0.0;
    ialt += (target - ialt) * (kDt / 0.1);
    for (std::size_t i = 0; i < out->events.count; ++i) log.push_back(out->events.items[i]);
    return *out;
  }
  void run(double s) {
    for (long i = 0; i < std::lround(s / kDt); ++i) tick();
  }
  template <typename P>
  double runUntil(P pred, double limit) {
    for (long i = 0; i < std::lround(limit / kDt); ++i) {
      tick();
      if (pred()) return (i + 1) * kDt;
    }
    return -1.0;
  }
  // Charging steadily with a healthy duty.
  void warm() {
    run(5.0);
    log.clear();
  }
  int count(EventCode c) const {
    int n = 0;
    for (const Event& e : log) n += e.code == c;
    return n;
  }
  bool said(const std::string& line) const {
    for (const Event& e : log)
      if (describe(e) == line) return true;
    return false;
  }
};

TEST(RegulatorE2E, HealthyStartReachesAutoWithFieldOn) {
  E2E r;
  r.warm();
  EXPECT_EQ(r.out->telemetry.mode, M::MODE_NORMAL_AUTO_PID);
  EXPECT_TRUE(r.out->fieldEnable);
  EXPECT_GT(r.out->dutyPct, 5.0);
  EXPECT_FALSE(r.out->buzzer);
}

TEST(RegulatorE2E, T3ImmediateCutWithinTheTickThenNoCooldown) {
  E2E r;
  r.warm();
  r.tempF = 161.0;
  r.tick();
  EXPECT_FALSE(r.out->fieldEnable);
  EXPECT_EQ(r.out->dutyPct, 0.0);
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_TEMP_CRITICAL);
  EXPECT_EQ(r.out->telemetry.control.sysMode, SysMode::SYS_MODE_FAULT);
  EXPECT_EQ(r.out->telemetry.setpoint_a, 0.0);
  EXPECT_TRUE(r.said("GPIO4 immediate cut: TEMP_CRITICAL"));
  r.run(1.0);
  EXPECT_EQ(r.count(EventCode::ImmediateCut), 1);  // no duplicate logging while cut
  r.tempF = 100.0;
  r.tick();
  EXPECT_EQ(r.out->telemetry.mode, M::MODE_NORMAL_AUTO_PID);
  EXPECT_TRUE(r.out->fieldEnable);
  EXPECT_EQ(r.count(EventCode::LockoutStarted), 0);
}

TEST(RegulatorE2E, WarningRampSlopesSettleCutAndLockout) {
  E2E r;
  r.warm();
  const double d0 = r.out->dutyPct;
  ASSERT_GT(d0, 10.0);
  r.tempF = 152.5;  // T1
  r.tick();
  EXPECT_EQ(r.out->telemetry.mode, M::MODE_WARNING_RAMP_AND_LOCKOUT);
  EXPECT_TRUE(r.out->fieldEnable);
  EXPECT_NEAR(d0 - r.out->dutyPct, 50.0 * kDt, 1e-6);  // DutyRampRate
  double prev = r.out->dutyPct;
  r.tick();
  EXPECT_NEAR(prev - r.out->dutyPct, 50.0 * kDt, 1e-6);
  // GPIO4 stays HIGH through phases 1-4 and goes LOW once, after the settle.
  const double cut = r.runUntil([&] { return !r.out->fieldEnable; }, 20.0);
  ASSERT_GT(cut, 0.0);
  const double minDuty = r.out->telemetry.control.rpmMinDuty;
  const double expect = (std::min(d0, 100.0) - minDuty) / 50.0 + minDuty / 1.0 + 1.0;
  EXPECT_NEAR(cut + 2 * kDt, expect, 0.05);
  EXPECT_TRUE(r.said("GPIO4 cut after settle: TEMP_WARNING"));
  EXPECT_TRUE(r.said("Field lockout started: 30s cooldown before restart allowed"));
  r.tempF = 100.0;
  const double back = r.runUntil([&] { return r.out->fieldEnable; }, 40.0);
  EXPECT_NEAR(back, 30.0, 0.01);
  EXPECT_TRUE(r.said("Field lockout expired - normal operation resumed"));
  EXPECT_EQ(r.out->telemetry.mode, M::MODE_NORMAL_AUTO_PID);
}

TEST(RegulatorE2E, CriticalRampCurrentStaleCutsAfterSettle) {
  E2E r;
  r.warm();
  r.ch1Frozen = true;
  const double t = r.runUntil([&] { return r.out->telemetry.mode == M::MODE_CRITICAL_RAMP; }, 1.0);
  ASSERT_GT(t, 0.0);
  EXPECT_NEAR(t, 0.5, 0.01);
  EXPECT_EQ(r.out->dutyPct, 0.0);
  EXPECT_TRUE(r.out->fieldEnable);
  const double cut = r.runUntil([&] { return !r.out->fieldEnable; }, 3.0);
  EXPECT_NEAR(cut, 1.0, 0.01);
  r.run(0.5);
  EXPECT_EQ(r.out->telemetry.mode, M::MODE_LOCKOUT_RAMP);
  EXPECT_TRUE(r.out->buzzer);
}

TEST(RegulatorE2E, T2StaysOffUntilReenableFieldCommand) {
  E2E r;
  r.warm();
  r.tempF = 153.0;
  r.run(125.0);
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_TEMP_SUSTAINED);
  r.tempF = 100.0;
  r.run(60.0);
  EXPECT_FALSE(r.out->fieldEnable);
  ASSERT_TRUE(r.reg.command(Command{CommandType::ReenableField}));
  r.run(0.1);
  EXPECT_EQ(r.out->telemetry.mode, M::MODE_NORMAL_AUTO_PID);
  EXPECT_TRUE(r.out->fieldEnable);
}

TEST(RegulatorE2E, LimpHomeIgnoresT3ButNotTheInaLatch) {
  E2E r;
  r.warm();
  ASSERT_TRUE(r.reg.command(Command{CommandType::LimpHome}));
  r.tempF = 170.0;
  r.run(1.0);
  EXPECT_EQ(r.out->telemetry.mode, M::MODE_LIMP_HOME);
  EXPECT_TRUE(r.out->fieldEnable);
  r.inaAlert = true;
  r.run(0.3);
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_INA_OVERVOLTAGE);
  EXPECT_FALSE(r.out->fieldEnable);
  EXPECT_EQ(r.out->dutyPct, 0.0);
}

TEST(RegulatorE2E, ManualHardOvercurrentCuts) {
  Params p;
  p.MaxTableValue = 40.0;  // hard OC at 50 A
  E2E r(p);
  r.warm();
  ASSERT_TRUE(r.reg.command(Command{CommandType::Manual, 90.0}));
  r.run(0.05);
  EXPECT_EQ(r.out->telemetry.mode, M::MODE_NORMAL_MANUAL);
  // (The alternator hard shutdown now cuts MANUAL too: HardOverVoltage.*.)
  // The crude plant gives 0.6 A/% -> 54 A at 90 %: above the 50 A fuse.
  const double t =
      r.runUntil([&] { return r.out->telemetry.reason == Reason::REASON_HARD_OVERCURRENT; }, 10.0);
  ASSERT_GT(t, 0.0);
  EXPECT_FALSE(r.out->fieldEnable);
  EXPECT_EQ(r.out->dutyPct, 0.0);
}

TEST(RegulatorE2E, OnOffZeroRampsDownWithoutAlarmOrLockout) {
  E2E r;
  r.warm();
  Params p = r.p;
  p.OnOff = false;
  r.reg.setParams(p);
  r.tick();
  EXPECT_EQ(r.out->telemetry.mode, M::MODE_DISABLED_RAMP);
  EXPECT_TRUE(r.out->fieldEnable);
  ASSERT_GT(r.runUntil([&] { return !r.out->fieldEnable; }, 20.0), 0.0);
  r.run(1.0);
  EXPECT_FALSE(r.out->buzzer);
  EXPECT_EQ(r.count(EventCode::LockoutStarted), 0);
}

TEST(RegulatorE2E, LockoutReArmsWhileTheFaultPersists) {
  E2E r;
  r.warm();
  r.tempF = 152.5;  // T1 held: warning ramp, lockout, and again after it
  r.run(45.0);
  EXPECT_EQ(r.count(EventCode::LockoutStarted), 2);
  EXPECT_FALSE(r.out->fieldEnable);
}

}  // namespace
}  // namespace xr::test
