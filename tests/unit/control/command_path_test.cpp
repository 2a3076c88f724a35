// The seed's command path, stage by stage (the field-control specification "Command Path").
#include <gtest/gtest.h>

#include <cmath>

#include "law_rig.h"

namespace xr {
namespace {

TEST(CommandPath, StartupRiseRateUntilCaughtUp) {
  test::LawRig rig;
  rig.start();
  rig.run(1.0);
  EXPECT_NEAR(rig.law.setpointLimited(), 3.0, 0.05);  // StartupRiseRate 3 A/s
  rig.run(20.0);
  EXPECT_DOUBLE_EQ(rig.law.setpointLimited(), 50.0);
  EXPECT_FALSE(rig.law.stages().inIdleStage());
  ControlTelemetry t;
  rig.law.fillTelemetry(t);
  EXPECT_FALSE(t.inStartupRamp);
}

TEST(CommandPath, SetpointRiseAndFallRatesAfterStartup) {
  test::LawRig rig;
  rig.start();
  rig.run(20.0);
  ASSERT_DOUBLE_EQ(rig.law.setpointLimited(), 50.0);
  rig.rpm = 50.0;  // cap table -> 0 A
  rig.run(0.5);
  EXPECT_NEAR(rig.law.setpointLimited(), 50.0 - 25.0, 0.2);  // SetpointFallRate 50 A/s
  rig.run(1.0);
  rig.rpm = 2000.0;
  rig.run(0.5);
  EXPECT_NEAR(rig.law.setpointLimited(), 15.0, 0.2);  // SetpointRiseRate 30 A/s
}

TEST(CommandPath, MaximumAllowedBatteryAmpsCeiling) {
  test::LawRig rig;
  rig.p.MaximumAllowedBatteryAmps = 30.0;
  rig.start();
  rig.tick();
  EXPECT_DOUBLE_EQ(rig.law.uTargetAmps(), 30.0);
}

TEST(CommandPath, MaxTableValueClamp) {
  test::LawRig rig;
  rig.p.MaxTableValue = 40.0;
  rig.start();
  rig.tick();
  EXPECT_DOUBLE_EQ(rig.law.uTargetAmps(), 40.0);
}

TEST(CommandPath, WarmupCeilingAppliesOnlyForItsWindowAfterFieldOn) {
  test::LawRig rig;
  rig.p.WarmupCeilingAmps = 20.0;
  rig.p.WarmupCeilingSec = 10.0;
  rig.start();
  rig.run(9.0);
  EXPECT_DOUBLE_EQ(rig.law.uTargetAmps(), 20.0);
  rig.run(1.5);
  EXPECT_DOUBLE_EQ(rig.law.uTargetAmps(), 50.0);
}

TEST(CommandPath, WarmupCeilingOffByDefault) {
  test::LawRig rig;
  rig.start();
  rig.tick();
  EXPECT_DOUBLE_EQ(rig.law.uTargetAmps(), 50.0);
}

TEST(CommandPath, ThermalPenaltySubtractedFromCap) {
  test::LawRig rig;
  rig.tempF = 170.0;  // well over the 150 degF limit
  rig.start();
  rig.run(3.0);
  const double penalty = rig.law.thermalPenaltyAmps();
  ASSERT_GT(penalty, 1.0);
  EXPECT_NEAR(rig.law.uTargetAmps(), std::max(0.0, 50.0 - penalty), 1e-9);
}

TEST(CommandPath, FastOvCapClampsAndFallRateIsUnlimitedWhileActive) {
  test::LawRig rig;
  rig.start();
  rig.run(20.0);
  ASSERT_DOUBLE_EQ(rig.law.setpointLimited(), 50.0);
  rig.ov.fastOvClampActive = true;
  rig.ov.fastOvCurrentCap = 10.0;
  rig.tick();
  EXPECT_DOUBLE_EQ(rig.law.uTargetAmps(), 10.0);
  EXPECT_DOUBLE_EQ(rig.law.setpointLimited(), 10.0);  // one tick, not 50 A/s
}

TEST(CommandPath, FastSetpointRiseWindowAfterProtectionClears) {
  test::LawRig rig;
  rig.start();
  rig.run(20.0);
  rig.ov.fastOvClampActive = true;
  rig.ov.fastOvCurrentCap = 0.0;
  rig.tick();
  ASSERT_DOUBLE_EQ(rig.law.setpointLimited(), 0.0);
  rig.ov = FastOvVerdict{};  // protection clears; IBV is far below bulk target
  rig.run(0.2);
  // SetpointRiseRate x FastSetpointRiseRate = 90 A/s.
  EXPECT_NEAR(rig.law.setpointLimited(), 90.0 * 0.2, 0.5);
  rig.run(6.0);  // window (5 s) over: back to 30 A/s
  rig.rpm = 50.0;
  rig.run(2.0);
  rig.rpm = 2000.0;
  rig.run(0.2);
  EXPECT_NEAR(rig.law.setpointLimited(), 30.0 * 0.2, 0.5);
}

TEST(CommandPath, PidComputesOnEveryPidSampleDivisorthSample) {
  test::LawRig rig;
  rig.p.PidSampleDivisor = 4;
  rig.start();
  rig.run(0.5);
  int changes = 0;
  double last = rig.law.currentPID().pTerm();
  for (int i = 0; i < 40; ++i) {
    rig.tick();
    if (rig.law.currentPID().pTerm() != last) ++changes;
    last = rig.law.currentPID().pTerm();
  }
  EXPECT_EQ(changes, 10);
}

TEST(CommandPath, FeedbackSignalSelectableRawMaEma) {
  for (int src : {0, 1, 2}) {
    test::LawRig rig;
    rig.p.OutputPIDSigSrc = src;
    rig.p.OutputPIDMA_N = 8;
    rig.start();
    rig.run(0.3);  // current rising: the three signals differ
    ControlTelemetry t;
    rig.law.fillTelemetry(t);
    const double expected = src == 2 ? t.MeasuredAmps : (src == 1 ? t.g_pidMA_N : t.g_pidI_filtered);
    EXPECT_DOUBLE_EQ(t.pidInput, expected) << "src " << src;
  }
  test::LawRig rig;
  rig.start();
  rig.run(0.3);
  ControlTelemetry t;
  rig.law.fillTelemetry(t);
  EXPECT_NE(t.g_pidMA_N, t.MeasuredAmps);
}

TEST(CommandPath, GovernorBypassWhileCvOvershootUntilBelowTargetPlus20mV) {
  test::LawRig rig;
  rig.p.TargetVoltageMode = 1;
  rig.p.TargetVoltageSetpoint = 13.0;
  rig.plant.Vocv = 13.3;  // above target
  rig.start();
  rig.ov.fastOvClampActive = true;
  rig.tick();
  EXPECT_EQ(rig.law.govMode(), GovMode::GOV_BYPASS_SLEW);
  rig.ov = FastOvVerdict{};
  rig.tick();
  EXPECT_EQ(rig.law.govMode(), GovMode::GOV_BYPASS_SLEW);  // latched: IBV still > target + 0.02
  rig.plant.Vocv = 12.9;
  rig.plant.VocvMax = 12.9;
  rig.tick();
  EXPECT_EQ(rig.law.govMode(), GovMode::GOV_NORMAL_SLEW);
}

// A voltage reading the detectors distrust bypasses the governor's slew on
// that tick only, with no latch: far below the target nothing else asks it.
TEST(CommandPath, GovernorBypassWhileTheVoltageSensorsFail) {
  test::LawRig rig;
  rig.start();
  rig.tick();
  EXPECT_EQ(rig.law.govMode(), GovMode::GOV_NORMAL_SLEW);
  rig.sensorFailure = true;
  rig.tick();
  EXPECT_EQ(rig.law.govMode(), GovMode::GOV_BYPASS_SLEW);
  rig.sensorFailure = false;
  rig.tick();
  EXPECT_EQ(rig.law.govMode(), GovMode::GOV_NORMAL_SLEW);
}

}  // namespace
}  // namespace xr
