#include <gtest/gtest.h>

#include <cmath>

#include "control/thermal_derate.h"

namespace xr {
namespace {

struct ThermalRig {
  Params p;
  ThermalDerate t;
  ThermalInputs in;
  ThermalRig() {
    in.now = fromSec(1000.0);
    in.dtSec = 0.0025;
    in.tempValid = true;
  }
  // Temperature follows f(t) with 1 Hz samples; control ticks at 2.5 ms... too
  // many for minutes, so tick at 10 ms here (the derate uses real dt).
  template <typename F>
  void run(double seconds, F tempAt) {
    in.dtSec = 0.01;
    const long n = std::lround(seconds / in.dtSec);
    for (long i = 0; i < n; ++i) {
      in.now += fromSec(in.dtSec);
      in.tempFresh = (i % 100) == 0;
      if (in.tempFresh) in.TempToUse = tempAt(toSec(in.now));
      t.update(in, p);
    }
  }
};

TEST(Thermal, DeratingStartsBeforeTheLimitWhenTemperatureRisesFast) {
  ThermalRig fast, steady;
  const double t0 = 1000.0;
  // Fast: 100 -> 140 degF at 0.5 degF/s (80 s). Steady: 140 degF throughout.
  fast.run(80.0, [&](double t) { return 100.0 + 0.5 * (t - t0); });
  steady.run(80.0, [](double) { return 140.0; });
  ASSERT_LT(fast.t.tempFiltered(), fast.p.TemperatureLimitF);
  EXPECT_GT(fast.t.projectedTempF(), fast.p.TemperatureLimitF);
  EXPECT_GT(fast.t.thermalPenaltyAmps(), 5.0);
  EXPECT_DOUBLE_EQ(steady.t.thermalPenaltyAmps(), 0.0);
}

TEST(Thermal, PenaltyIsSlewLimitedAsymmetrically) {
  ThermalRig r;
  r.p.TempPIDFilterAlpha = 1.0;
  r.p.TempPIDIntervalMs = 100;
  r.run(0.5, [](double) { return 200.0; });                // target jumps to MaxTableValue (60 A)
  EXPECT_NEAR(r.t.thermalPenaltyAmps(), 60.0 * 0.5, 0.7);  // ThermalPenaltyRiseRate 60 A/s
  r.run(2.0, [](double) { return 200.0; });
  ASSERT_NEAR(r.t.thermalPenaltyAmps(), 60.0, 1e-9);
  r.run(0.5, [](double) { return 80.0; });  // target drops to 0
  // ThermalPenaltyFallRate 20 A/s (less up to one compute interval of latency).
  EXPECT_GE(r.t.thermalPenaltyAmps(), 60.0 - 20.0 * 0.5 - 1e-6);
  EXPECT_LE(r.t.thermalPenaltyAmps(), 60.0 - 20.0 * 0.4 + 1e-6);
}

TEST(Thermal, PenaltyHeldOnStaleInput) {
  ThermalRig r;
  r.run(30.0, [](double) { return 170.0; });
  const double held = r.t.thermalPenaltyAmps();
  ASSERT_GT(held, 10.0);
  r.in.tempValid = false;
  r.run(60.0, [](double) { return 80.0; });  // would drop the penalty if read
  EXPECT_DOUBLE_EQ(r.t.thermalPenaltyAmps(), held);
  EXPECT_TRUE(r.t.holding());
  r.in.tempValid = true;  // fresh valid cool data: now it falls
  r.run(60.0, [](double) { return 80.0; });
  EXPECT_LT(r.t.thermalPenaltyAmps(), held);
}

TEST(Thermal, AntiWindupParksIntegratorOnlyWhenOuterErrorPositive) {
  // Cool (outerError = 145 - 120 > 0): integrator parked at implied - margin.
  ThermalRig cool;
  cool.in.impliedPenalty = 30.0;
  cool.run(30.0, [](double) { return 120.0; });
  EXPECT_NEAR(cool.t.integrator(), 30.0 - cool.p.TempPIDAntiWindupMarginA, 0.5);
  // Warm (outerError = 145 - 148 < 0): tracking must not touch it.
  ThermalRig warm;
  warm.in.impliedPenalty = 30.0;
  warm.run(30.0, [](double) { return 148.0; });
  EXPECT_LT(warm.t.integrator(), 1.0);
}

TEST(Thermal, IgnoreTemperatureGivesNoPenalty) {
  ThermalRig r;
  r.p.IgnoreTemperature = 1;
  r.run(30.0, [](double) { return 200.0; });
  EXPECT_DOUBLE_EQ(r.t.thermalPenaltyAmps(), 0.0);
}

}  // namespace
}  // namespace xr
