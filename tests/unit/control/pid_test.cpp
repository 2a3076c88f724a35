#include "control/pid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "law_rig.h"
#include "plant.h"

namespace xr {
namespace {

// Closed loop: PID -> plant, sampling every dt; returns Ialt at each 50 ms.
std::vector<double> closedLoop(double dt, double seconds, double setpoint) {
  Pid pid(0.3, 2.0, 0.0, Pid::DIRECT);
  pid.setOutputLimits(0.0, 100.0);
  test::Plant plant;
  pid.input = plant.Ialt;
  pid.output = 0.0;
  pid.setMode(Pid::AUTOMATIC);
  std::vector<double> samples;
  const long n = std::lround(seconds / dt);
  const long every = std::lround(0.05 / dt);
  for (long i = 1; i <= n; ++i) {
    pid.input = plant.Ialt;
    pid.setpoint = setpoint;
    pid.compute(dt);
    plant.advance(pid.output, true, dt);
    if (i % every == 0) samples.push_back(plant.Ialt);
  }
  return samples;
}

TEST(Pid, StepResponseSettlesOnSetpointWithinLimits) {
  const auto s = closedLoop(0.0025, 6.0, 20.0);
  EXPECT_NEAR(s.back(), 20.0, 0.1);
  double peak = 0;
  for (double v : s) peak = std::max(peak, v);
  EXPECT_LT(peak, 22.0);  // modest overshoot at most
  EXPECT_GT(s[10], 5.0);  // and it actually moved within 0.5 s
}

TEST(Pid, DtCorrectness_SameResponseAt200HzAnd400Hz) {
  const auto a = closedLoop(1.0 / 200.0, 3.0, 20.0);
  const auto b = closedLoop(1.0 / 400.0, 3.0, 20.0);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) EXPECT_NEAR(a[i], b[i], 0.6) << "at " << (i + 1) * 50 << " ms";
}

TEST(Pid, DtCorrectness_WholeControlLawSameAt200HzAnd400Hz) {
  // Filters, setpoint slew, PID, governor and tracking all use the real dt.
  test::LawRig a, b;
  a.start();
  b.start();
  for (int k = 1; k <= 20; ++k) {  // compare every 0.5 s over 10 s
    a.run(0.5, 1.0 / 200.0);
    b.run(0.5, 1.0 / 400.0);
    EXPECT_NEAR(a.plant.Ialt, b.plant.Ialt, 0.5) << "at " << k * 0.5 << " s";
    EXPECT_NEAR(a.law.setpointLimited(), b.law.setpointLimited(), 0.05);
  }
  EXPECT_GT(a.plant.Ialt, 20.0);
}

TEST(Pid, TrackingAntiWindupUnwindsAtTheSetGain) {
  for (double Kt : {4.0, 8.0}) {
    Pid pid(0.0, 0.0, 0.0, Pid::DIRECT);
    pid.setOutputLimits(0.0, 100.0);
    pid.setTrackingGain(Kt);
    pid.input = 0.0;
    pid.setMode(Pid::AUTOMATIC);
    pid.resetIntegratorTo(80.0);
    const double dt = 0.0025;
    // The governor holds the applied duty at 40 while the integrator sits at 80.
    const double t = 1.0 / Kt;  // one time constant
    const long n = std::lround(t / dt);
    for (long i = 0; i < n; ++i) {
      pid.compute(dt);
      pid.trackAppliedOutput(40.0, dt);
    }
    const double excess = pid.iTerm() - 40.0;
    EXPECT_NEAR(excess, 40.0 * std::exp(-1.0), 40.0 * 0.02) << "Kt " << Kt;
  }
}

TEST(Pid, TrackingAntiWindupKeepsIntegratorNearClampedDuty) {
  Pid pid(0.3, 2.0, 0.0, Pid::DIRECT);
  pid.setOutputLimits(0.0, 100.0);
  pid.setTrackingGain(4.0);
  pid.input = 0.0;
  pid.setMode(Pid::AUTOMATIC);
  test::Plant plant;
  const double dt = 0.0025;
  for (int i = 0; i < 4000; ++i) {  // 10 s demanding 80 A, governor caps duty at 30 %
    pid.input = plant.Ialt;
    pid.setpoint = 80.0;
    pid.compute(dt);
    const double applied = std::min(pid.output, 30.0);
    pid.trackAppliedOutput(applied, dt);
    plant.advance(applied, true, dt);
  }
  // Without tracking the integrator would be pinned at 100 %. With it, it sits
  // where back-calculation (Kt x (30 - P - I)) balances the integral action
  // (Ki x 50 A) with P = 0.3 x 50 = 15: I = 30 - 15 + 2 x 50 / 4 = 40 %.
  EXPECT_NEAR(pid.iTerm(), 40.0, 1.0);
}

TEST(Pid, ManualToAutomaticIsBumpless) {
  Pid pid(0.5, 3.0, 0.0, Pid::DIRECT);
  pid.setOutputLimits(0.0, 100.0);
  pid.input = 12.0;
  pid.setpoint = 12.0;
  pid.resetIntegratorTo(37.0);
  EXPECT_EQ(pid.mode(), Pid::MANUAL);
  EXPECT_FALSE(pid.compute(0.01));  // MANUAL: no compute
  pid.setMode(Pid::AUTOMATIC);
  ASSERT_TRUE(pid.compute(0.0025));
  EXPECT_NEAR(pid.output, 37.0, 1e-9);
}

TEST(Pid, ManualToAutoThroughTheControlLawWithoutDutyJump) {
  test::LawRig rig;
  rig.p.ManualDutyTarget = 25.0;
  rig.manual = true;
  rig.start();
  rig.law.enterSysManual();
  rig.run(3.0);  // reach 25 % and a steady current
  ASSERT_NEAR(rig.duty, 25.0, 1e-6);
  rig.manual = false;
  rig.law.enterSysAuto(rig.sensors(), rig.p);
  const double first = rig.tick();
  EXPECT_NEAR(first, 25.0, 0.5);  // at most one tick of governor slew (50 %/s x 2.5 ms = 0.125)
}

TEST(Pid, DerivativeOnMeasurementHasNoSetpointKick) {
  Pid pid(0.0, 0.0, 1.0, Pid::DIRECT);
  pid.setOutputLimits(-100.0, 100.0);
  pid.input = 5.0;
  pid.setpoint = 5.0;
  pid.setMode(Pid::AUTOMATIC);
  pid.compute(0.01);
  pid.setpoint = 50.0;  // setpoint step
  pid.compute(0.01);
  EXPECT_DOUBLE_EQ(pid.dTerm(), 0.0);
  pid.input = 6.0;  // measurement moves
  pid.compute(0.01);
  EXPECT_NEAR(pid.dTerm(), -100.0, 1e-9);
}

TEST(Pid, ReverseActionRaisesOutputWhenInputExceedsSetpoint) {
  Pid pid(2.0, 0.0, 0.0, Pid::REVERSE);
  pid.setOutputLimits(0.0, 100.0);
  pid.setpoint = 150.0;
  pid.input = 160.0;
  pid.setMode(Pid::AUTOMATIC);
  pid.compute(1.0);
  EXPECT_NEAR(pid.output, 20.0, 1e-9);
  EXPECT_NEAR(pid.pTerm(), 20.0, 1e-9);
}

TEST(Pid, OutputAndIntegratorClampedToLimits) {
  Pid pid(0.0, 100.0, 0.0, Pid::DIRECT);
  pid.setOutputLimits(5.0, 60.0);
  pid.input = 0;
  pid.setMode(Pid::AUTOMATIC);
  pid.setpoint = 100;
  for (int i = 0; i < 100; ++i) pid.compute(0.1);
  EXPECT_DOUBLE_EQ(pid.output, 60.0);
  EXPECT_DOUBLE_EQ(pid.iTerm(), 60.0);
}

TEST(Pid, NanInputDoesNotCompute) {
  Pid pid(1.0, 1.0, 0.0, Pid::DIRECT);
  pid.input = 1.0;
  pid.setMode(Pid::AUTOMATIC);
  pid.input = std::nan("");
  EXPECT_FALSE(pid.compute(0.01));
  EXPECT_TRUE(std::isfinite(pid.output));
}

}  // namespace
}  // namespace xr
