// The control behaviour a cruising day needs — the field resting on a full
// bank, the absorption tail, the thermal derate, the voltage loop — each at its
// threshold and just below (docs/deviations.md names these tests; the voltage
// loop's are in cv_loop_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "control/thermal_derate.h"
#include "law_rig.h"
#include "protection/mode_selection.h"
#include "reg_rig.h"

namespace xr {
namespace {

// A full bank held by TargetVoltageMode at 13.5 V: at 2,000 rpm the RPM floor
// (~3.2 %) makes ~3.2 A against a 1 A house load, and the bank saturates at
// `vocvMax`, so the floor alone lifts it above the target.
Params fullBankParams() {
  Params p;
  p.TargetVoltageMode = 1;
  p.TargetVoltageSetpoint = 13.5;
  return p;
}
struct FullBank : test::RegRig {
  explicit FullBank(double vocvMax) : test::RegRig(fullBankParams()) {
    plant.house = 1.0;
    plant.Vocv = 13.45;
    plant.VocvMax = vocvMax;
    plant.voltsPerAmpSec = 0.005;
  }
};

bool anyProtectionMode(const test::RegRig& r) { return !isNormalMode(r.out->telemetry.mode); }

TEST(FieldRest, FullBankAboveTargetAtTheFloorRestsWithoutATrip) {
  FullBank r(13.62);  // V settles ~13.64: over target + 0.05 V
  bool rested = false, tripped = false;
  for (int i = 0; i < 120 * 400; ++i) {
    r.tick();
    rested |= !r.out->fieldEnable && r.out->telemetry.mode == FieldControlMode::MODE_NORMAL_AUTO_PID;
    tripped |= anyProtectionMode(r);
  }
  EXPECT_TRUE(rested);
  EXPECT_FALSE(tripped);
  EXPECT_LT(r.plant.V(), r.p.AlternatorHardShutdownV > 0 ? r.p.AlternatorHardShutdownV : 14.8);
}

TEST(FieldRest, JustUnderTheMarginTheFieldKeepsWorking) {
  FullBank r(13.515);  // V settles ~13.54: under target + 0.05 V
  r.run(5.0);
  bool rested = false;
  for (int i = 0; i < 120 * 400; ++i) rested |= !r.tick().fieldEnable;
  EXPECT_FALSE(rested);
}

TEST(FieldRest, WakesWhenTheBankFallsUnderTheTarget) {
  FullBank r(13.62);
  r.run(120.0);
  ASSERT_FALSE(r.out->fieldEnable);
  r.plant.house = 30.0;  // a load comes on: the bank sags
  bool woke = false;
  for (int i = 0; i < 60 * 400 && !woke; ++i) {
    r.tick();
    woke = r.out->fieldEnable;
    if (woke) {
      EXPECT_LT(r.plant.V(), r.p.TargetVoltageSetpoint - r.p.FieldRestWakeV + 0.01);
    }
  }
  EXPECT_TRUE(woke);
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
}

TEST(FieldRest, RpmGateTrustsThePreRestRpmWhileResting) {
  FullBank r(13.62);
  r.run(120.0);
  ASSERT_FALSE(r.out->fieldEnable);
  r.rpm = 0.0;  // a stator tach goes quiet with the field off
  r.run(10.0);
  EXPECT_EQ(r.out->telemetry.mode, FieldControlMode::MODE_NORMAL_AUTO_PID);
  // The rest ends (load on) and the tach stays dead past the grace: the gate cuts.
  r.plant.house = 30.0;
  r.run(30.0);
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_RPM_LOW);
}

TEST(FieldRest, RpmGateCutsAtOnceWhenNotResting) {
  FullBank r(14.8);  // the bank takes the current: no rest
  r.run(5.0);
  ASSERT_TRUE(r.out->fieldEnable);
  r.rpm = 199.9;  // just under MinRPMForField
  r.tick();
  EXPECT_EQ(r.out->telemetry.reason, Reason::REASON_RPM_LOW);
}

// One tuningActive() for both ends of a rest: a run that owns the field
// neither starts a rest nor leaves one in place.
struct RestingLaw : test::LawRig {
  RestingLaw() : test::LawRig(fullBankParams()) {
    plant.house = 1.0;
    plant.Vocv = 13.45;
    plant.VocvMax = 13.62;
    plant.voltsPerAmpSec = 0.005;
    start();
  }
};

TEST(FieldRest, LawRestsWithoutTuning) {
  RestingLaw r;
  r.run(120.0);
  EXPECT_TRUE(r.law.fieldResting());
  EXPECT_EQ(r.duty, 0.0);
}

TEST(FieldRest, SystemIdEndsARestLikeTheOtherTuningModes) {
  RestingLaw r;
  r.run(120.0);
  ASSERT_TRUE(r.law.fieldResting());
  ASSERT_TRUE(r.law.startSystemId(r.now, true));
  r.tick();
  EXPECT_FALSE(r.law.fieldResting());
  EXPECT_GT(r.duty, 0.0);  // the step test drives the field
  for (int i = 0; i < 10 * 400 && r.law.systemIdRunning(); ++i) {
    r.tick();
    EXPECT_FALSE(r.law.fieldResting());
  }
}

TEST(FieldRest, TuningModeEndsARest) {
  RestingLaw r;
  r.run(120.0);
  ASSERT_TRUE(r.law.fieldResting());
  r.p.TuningMode = 1;
  r.tick();
  EXPECT_FALSE(r.law.fieldResting());
  r.run(60.0);
  EXPECT_FALSE(r.law.fieldResting());  // and none starts while it lasts
}

// Tail current: a bank discharging into a load bigger than the cap is not full.
TEST(ChargingStage, TailNeedsTheVoltageHeld) {
  test::LawRig rig;
  rig.p.bulkVoltageHoldMs = 1000;
  rig.plant.Vocv = 14.6;
  rig.start();
  rig.run(2.0);
  ASSERT_EQ(rig.law.stages().stage(), ChargeStage::ABSORPTION);
  rig.plant.Vocv = 13.6;  // the inverter pulls the bank down
  rig.plant.VocvMax = 13.6;
  rig.plant.house = 120.0;  // far over the 50 A cap: Bcur ~ -70 A <= TailCurrent_A
  rig.run(90.0);
  EXPECT_EQ(rig.law.stages().stage(), ChargeStage::ABSORPTION);
}

TEST(ChargingStage, TailCountsWhenTheVoltageIsHeld) {
  test::LawRig rig;
  rig.p.bulkVoltageHoldMs = 1000;
  rig.plant.Vocv = 14.38;
  rig.plant.VocvMax = 14.38;  // full just under absorption: the current tails off
  rig.plant.house = 2.0;
  rig.start();
  rig.run(2.0);
  rig.plant.Vocv = 14.6;
  rig.run(2.0);
  rig.plant.Vocv = 14.38;
  rig.run(120.0);
  EXPECT_EQ(rig.law.stages().stage(), ChargeStage::FLOAT);
}

// MaintainMode: Bcur ~ 0, but never more alternator current than the cap.
TEST(MaintainMode, AlternatorCurrentStaysUnderTheCap) {
  Params p;
  p.MaintainMode = 1;
  test::RegRig r(p);  // 2,000 rpm: the default cap table gives 50 A
  r.plant.house = 65.0;
  r.plant.Vocv = 13.0;
  r.run(30.0);
  EXPECT_LE(r.plant.Ialt, 51.0);
  EXPECT_GE(r.plant.Ialt, 45.0);
}

TEST(MaintainMode, UnderTheCapItStillChasesZeroBatteryCurrent) {
  Params p;
  p.MaintainMode = 1;
  test::RegRig r(p);
  r.plant.house = 40.0;
  r.plant.Vocv = 13.0;
  r.run(30.0);
  EXPECT_NEAR(r.plant.Ibat(), 0.0, 1.5);
}

// Thermal loop.
struct ThermalRun {
  Params p;
  ThermalDerate t;
  ThermalInputs in;
  ThermalRun() {
    in.now = fromSec(1000.0);
    in.tempValid = true;
  }
  void run(double seconds, double tempF, double sampleEverySec = 1.0) {
    in.dtSec = 0.01;
    TimeNs nextSample = in.now;
    const long n = std::lround(seconds / in.dtSec);
    for (long i = 0; i < n; ++i) {
      in.now += fromSec(in.dtSec);
      in.tempFresh = in.now >= nextSample;
      if (in.tempFresh) {
        in.TempToUse = tempF;
        nextSample = in.now + fromSec(sampleEverySec);
      }
      t.update(in, p);
    }
  }
};

TEST(Thermal, RegulatesWithTheMarginUnderTheLimit) {
  ThermalRun at, below;  // default limit 150, margin 2: the setpoint is 148
  at.run(60.0, 148.3);
  below.run(60.0, 147.7);
  EXPECT_GT(at.t.penaltyTarget(), 0.0);
  EXPECT_EQ(below.t.penaltyTarget(), 0.0);
}

TEST(Thermal, ACoolingSlopeDoesNotHideAPresentExcess) {
  ThermalRun r;
  r.run(60.0, 160.0);
  r.run(60.0, 152.0);  // falling fast: projected well under, present still over
  ASSERT_LT(r.t.projectedTempF(), r.p.TemperatureLimitF - r.p.TempRegulationMarginF);
  EXPECT_GT(r.t.penaltyTarget(), 0.0);
}

TEST(Thermal, FilterSmoothsPerSecondWhateverTheSensorRate) {
  ThermalRun slow, fast;
  slow.run(1.0, 100.0, 1.0);
  fast.run(1.0, 100.0, 0.25);
  slow.run(10.0, 110.0, 1.0);
  fast.run(10.0, 110.0, 0.25);
  // Both have seen 10 s of the step: the same filtered value.
  EXPECT_NEAR(slow.t.tempFiltered(), fast.t.tempFiltered(), 0.2);
}

TEST(Thermal, ImplausibleSlopeIsIgnored) {
  ThermalRun r;
  r.p.TempPIDFilterAlpha = 1.0;
  r.run(70.0, 100.0);
  ASSERT_NEAR(r.t.thermalSlopeFPerSec(), 0.0, 1e-9);
  r.run(5.0, 300.0);  // a 200 degF jump in 5 s: a glitch, not heat
  EXPECT_NEAR(r.t.thermalSlopeFPerSec(), 0.0, 1e-9);
}

}  // namespace
}  // namespace xr
