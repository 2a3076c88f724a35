// Groups 1/2/3 and load dump: the nearBulk gate, thresholds, caps, cv_I
// actions and GOV_BYPASS_SLEW, called as the AUTO path calls them.
#include <gtest/gtest.h>

#include "rig.h"

namespace xr::test {
namespace {

struct FastRig : Rig {
  FastOvInputs x;
  FastOvAction a;
  explicit FastRig(const Params& p = Params{}) : Rig(p) {
    x.voltageControlActive = true;
    x.ChargingVoltageTarget = 14.4;
    x.uTargetAmps = 50.0;
    x.setpointLimited = 40.0;
    x.cv_I = 30.0;
    x.MeasuredAmps = 40.0;
    x.MeasuredAmps_filtered = 40.0;
    x.altCurrentFresh = true;
    ibv = batteryV = 14.35;  // inside the Group 3 voltage sub-gate (> target - 0.10)
  }
  void step() {
    tick();
    x.MeasuredAmps = altAmps;
    a = sup.runFastOvSupervisors(x);
    if (a.verdict.cvIAction != CvIAction::None) x.cv_I = a.verdict.cv_I;
  }
  void steps(int n) {
    for (int i = 0; i < n; ++i) step();
  }
};

// Telemetry before the first AUTO tick reads a cap of 0 A, not the
// verdict's "no clamp asked" (1e300); the first update sets the request.
TEST(FastOvTelemetry, CapReadsZeroUntilTheFirstUpdate) {
  FastRig r;
  EXPECT_EQ(r.sup.telemetry().fastOvCurrentCap, 0.0);
  EXPECT_EQ(FastOvVerdict{}.fastOvCurrentCap, 1e300);
  r.altAmps = 40.0;
  r.step();
  EXPECT_EQ(r.sup.telemetry().fastOvCurrentCap, 50.0);  // idle: the request itself
}

TEST(NearBulk, ArmsOnlyWithinProtectionProxGateVOfBulk) {
  FastRig r;
  r.altAmps = 40.0;
  r.steps(10);
  r.x.ChargingVoltageTarget = 14.0;  // BulkVoltage 14.5 - 0.5: armed
  r.step();
  EXPECT_TRUE(r.a.nearBulk);
  r.x.ChargingVoltageTarget = 13.99;
  r.step();
  EXPECT_FALSE(r.a.nearBulk);
  r.ibv = r.batteryV = 14.2;  // far above this target + margin: would be Group 2
  r.step();
  EXPECT_FALSE(r.a.group2);
  EXPECT_FALSE(r.a.verdict.fastOvClampActive);
  Params p;
  p.ProtectionProxGateV = 0.0;  // 0 = always armed
  r.setParams(p);
  r.step();
  EXPECT_TRUE(r.a.nearBulk);
  EXPECT_TRUE(r.a.group2);
}

// A deviation (docs/deviations.md): FLOAT arms the supervisors whatever the
// distance from BulkVoltage; outside FLOAT the nearBulk gate still decides.
TEST(FastOv, ArmedInFloat) {
  FastRig r;
  r.altAmps = 40.0;
  r.x.ChargingVoltageTarget = 13.5;  // float, 1 V under bulk: nearBulk false
  r.ibv = r.batteryV = 13.61;        // just over target + OvMeasMarginV
  r.x.floatStage = true;
  r.steps(3);
  EXPECT_FALSE(r.a.nearBulk);
  EXPECT_TRUE(r.a.group2);
  EXPECT_TRUE(r.a.verdict.fastOvClampActive);
  r.ibv = r.batteryV = 13.59;  // just under: nothing
  r.steps(3);
  EXPECT_FALSE(r.a.group2);
  r.ibv = r.batteryV = 13.61;
  r.x.floatStage = false;  // the same target outside FLOAT: not armed
  r.steps(3);
  EXPECT_FALSE(r.a.group2);
  EXPECT_FALSE(r.a.verdict.fastOvClampActive);
}

TEST(Group2, FiresAboveTargetPlusMarginAndTrimsCap) {
  Params p;
  p.OvGroup1Enable = false;  // the step would also trip the prediction
  FastRig r(p);
  r.altAmps = 40.0;
  r.steps(5);
  r.ibv = r.batteryV = 14.49;  // target 14.4 + 0.10 not exceeded
  r.step();
  EXPECT_FALSE(r.a.group2);
  r.ibv = r.batteryV = 14.52;
  r.step();
  ASSERT_TRUE(r.a.group2);
  EXPECT_TRUE(r.a.verdict.fastOvClampActive);
  EXPECT_TRUE(r.a.verdict.forceBypassSlew);
  EXPECT_NEAR(r.a.verdict.fastOvCurrentCap, 40.0 - 35.0 * (14.52 - 14.4 - 0.10), 1e-9);
}

TEST(Group2, InactiveWithoutVoltageControlAndWhenDisabled) {
  FastRig r;
  r.steps(5);
  r.ibv = r.batteryV = 14.6;
  r.x.voltageControlActive = false;
  r.step();
  EXPECT_FALSE(r.a.group2);
  Params p;
  p.OvGroup2Enable = false;
  p.OvGroup1Enable = false;
  r.setParams(p);
  r.x.voltageControlActive = true;
  r.step();
  EXPECT_FALSE(r.a.group2);
}

TEST(GovBypass, LatchReleasesBelowTargetPlus20mV) {
  FastRig r;
  r.steps(5);
  r.ibv = r.batteryV = 14.55;
  r.step();
  ASSERT_TRUE(r.a.group2);
  r.ibv = r.batteryV = 14.43;  // below group 2, above target + 0.02
  r.step();
  EXPECT_FALSE(r.a.verdict.fastOvClampActive);
  EXPECT_TRUE(r.a.verdict.forceBypassSlew);
  r.ibv = r.batteryV = 14.41;
  r.step();
  EXPECT_FALSE(r.a.verdict.forceBypassSlew);
}

TEST(Group1, PredictionFromDvdtEmaFiresBeforeMeasuredThreshold) {
  FastRig r;
  r.steps(5);
  // Rise 0.01 V per 5 ms sample = 2 V/s; Vpred = IBV + 0.045 * dvdt.
  bool fired = false;
  double ibvAtFire = 0.0;
  for (int i = 0; i < 40 && !fired; ++i) {
    r.ibv += 0.01;
    r.batteryV = r.ibv;
    r.step();
    if (r.a.group1) {
      fired = true;
      ibvAtFire = r.ibv;
    }
  }
  ASSERT_TRUE(fired);
  EXPECT_LT(ibvAtFire, 14.4 + 0.10);  // before Group 2 could see it
  EXPECT_GT(r.sup.telemetry().Vpred, 14.4 + 0.15);
  EXPECT_TRUE(r.a.verdict.fastOvClampActive);
}

TEST(Group1, FiresAtPredMarginNotJustBelowAndCapsBySlope) {
  Params p;
  p.OvGroup2Enable = false;
  FastRig r(p);
  r.ibv = r.batteryV = 14.549;  // steady: dvdt 0, Vpred = IBV, margin 0.15 not exceeded
  r.steps(50);
  EXPECT_FALSE(r.a.group1);
  r.ibv = r.batteryV = 14.56;
  r.steps(1);
  ASSERT_TRUE(r.a.group1);
  const double vpred = r.sup.telemetry().Vpred;
  EXPECT_GT(vpred, 14.56);  // the step itself raised dvdt
  EXPECT_NEAR(r.a.verdict.fastOvCurrentCap, 40.0 - 35.0 * (vpred - 14.55), 1e-9);
}

TEST(Group1, PredGuardBlocksFarBelowTarget) {
  FastRig r;
  r.steps(5);
  // Violent rise far below target (IBV < target - 0.06): guard holds Group 1 off.
  for (int i = 0; i < 10; ++i) {
    r.ibv += 0.02;
    r.batteryV = r.ibv;
    r.step();
    if (r.ibv < 14.4 - 0.06) {
      EXPECT_FALSE(r.a.group1) << r.ibv;
    }
  }
}

TEST(Group1, DvdtRejectsSampleWindowsOutside1To100ms) {
  FastRig r;
  r.steps(5);
  const double before = r.sup.telemetry().dvdt;
  // Slow-mode cadence: 200 ms between INA samples -> rejected, dvdt holds.
  r.freezeIna = true;
  r.run(fromMs(195));
  r.freezeIna = false;
  r.ibv = 14.39;
  r.step();
  EXPECT_DOUBLE_EQ(r.sup.telemetry().dvdt, before);
  // Fast cadence: accepted.
  r.ibv = 14.40;
  r.step();
  EXPECT_GT(r.sup.telemetry().dvdt, before);
}

TEST(Group3, FiresAfterNTicksSnapsCvIAndReseedsOnReleaseWithHysteresis) {
  Params p;
  p.IExcessSigSrc = 2;  // raw: the tick count is exact
  FastRig r(p);
  r.x.setpointLimited = 40.0;
  r.altAmps = 40.0;
  r.steps(5);
  r.altAmps = 45.5;  // > setpointLimited + IExcessK (45)
  r.step();
  r.step();
  EXPECT_FALSE(r.a.group3);
  r.step();  // third consecutive tick
  ASSERT_TRUE(r.a.group3);
  EXPECT_EQ(r.a.verdict.cvIAction, CvIAction::Snap);
  EXPECT_EQ(r.a.verdict.cv_I, 0.0);
  EXPECT_NEAR(r.a.verdict.fastOvCurrentCap, 50.0 - 1.0 * (45.5 - 40.0), 1e-9);
  r.altAmps = 43.5;  // inside the IEXCESS_HYST band (release below 43)
  r.step();
  EXPECT_TRUE(r.a.group3);
  r.altAmps = 42.9;
  r.step();
  EXPECT_FALSE(r.a.group3);
  EXPECT_EQ(r.a.verdict.cvIAction, CvIAction::Reseed);
  EXPECT_NEAR(r.a.verdict.cv_I, 30.0 * 0.5, 1e-9);  // preEventCvI x IExcessReseedFrac
}

TEST(Group3, JustBelowThresholdNeverFires) {
  Params p;
  p.IExcessSigSrc = 2;
  FastRig r(p);
  r.altAmps = 45.0;  // == setpointLimited + IExcessK, not above
  r.steps(20);
  EXPECT_FALSE(r.a.group3);
}

TEST(Group3, ProportionalBleedWhenKBleedSet) {
  Params p;
  p.IExcessSigSrc = 2;
  p.IExcessKBleed = 2.0;
  FastRig r(p);
  r.steps(5);
  r.altAmps = 50.0;
  r.steps(3);
  ASSERT_TRUE(r.a.group3);
  r.step();
  EXPECT_EQ(r.a.verdict.cvIAction, CvIAction::Bleed);
  // cv_I -= IExcessKBleed * excess * dt = 2 * 10 * 0.005 per tick.
  EXPECT_LT(r.a.verdict.cv_I, 30.0);
  EXPECT_GT(r.a.verdict.cv_I, 29.0);
}

TEST(Group3, VoltageSubGateBlocksFarBelowTarget) {
  Params p;
  p.IExcessSigSrc = 2;
  FastRig r(p);
  r.ibv = r.batteryV = 14.29;  // <= target - OvMeasMarginV
  r.altAmps = 50.0;
  r.steps(10);
  EXPECT_FALSE(r.a.group3);
}

TEST(Group3, PostFastOvGateWaitsForCurrentToFallBack) {
  Params p;
  p.IExcessSigSrc = 2;
  FastRig r(p);
  r.steps(5);
  r.ibv = r.batteryV = 14.55;  // Group 2 event
  r.altAmps = 50.0;
  r.steps(2);
  ASSERT_TRUE(r.a.group2);
  r.ibv = r.batteryV = 14.35;  // Group 2 over; field wind-down current still high
  r.steps(10);
  EXPECT_FALSE(r.a.group3);
  r.altAmps = 44.0;  // back within IExcessK: gate opens
  r.step();
  r.altAmps = 50.0;
  r.steps(3);
  EXPECT_TRUE(r.a.group3);
}

TEST(Group3, MovingAverageSignalSmoothsASpike) {
  FastRig r;  // default: MA(8)
  r.altAmps = 40.0;
  r.steps(10);
  r.altAmps = 80.0;  // one-tick spike: MA = 45 -> not above 45
  r.step();
  r.altAmps = 40.0;
  r.steps(5);
  EXPECT_FALSE(r.a.group3);
}

TEST(LoadDump, Tier1SingleSampleZeroesEverything) {
  FastRig r;
  r.steps(5);
  r.bcur += 4000.0 * 0.005 + 1.0;  // > 4000 A/s over one 5 ms sample
  r.step();
  ASSERT_TRUE(r.a.loadDump);
  EXPECT_EQ(r.a.verdict.fastOvCurrentCap, 0.0);
  EXPECT_TRUE(r.a.verdict.zeroSetpointLimited);
  EXPECT_EQ(r.a.verdict.cvIAction, CvIAction::Snap);
  EXPECT_EQ(r.a.verdict.cv_I, 0.0);
  EXPECT_TRUE(r.a.verdict.forceBypassSlew);
}

TEST(LoadDump, Tier2NeedsTwoConsecutiveAndTier3Three) {
  FastRig r;
  r.steps(5);
  r.bcur += 1600.0 * 0.005;  // tier 2 rate, tier 1 not reached
  r.step();
  EXPECT_FALSE(r.a.loadDump);
  r.bcur += 1600.0 * 0.005;
  r.step();
  EXPECT_TRUE(r.a.loadDump);
  FastRig q;
  q.steps(5);
  for (int i = 0; i < 2; ++i) {
    q.bcur += 1100.0 * 0.005;
    q.step();
    EXPECT_FALSE(q.a.loadDump);
  }
  q.bcur += 1100.0 * 0.005;
  q.step();
  EXPECT_TRUE(q.a.loadDump);
}

TEST(LoadDump, JustBelowThresholdAndSlowInaModeDoNotFire) {
  FastRig r;
  r.steps(5);
  for (int i = 0; i < 5; ++i) {
    r.bcur += 990.0 * 0.005;
    r.step();
    EXPECT_FALSE(r.a.loadDump);
  }
  FastRig s;
  s.in.inaFastModeActive = false;
  s.steps(5);
  s.bcur += 5000.0 * 0.005;
  s.step();
  EXPECT_FALSE(s.a.loadDump);
}

}  // namespace
}  // namespace xr::test
