// TemperatureChecks on its own: T1 above its threshold not at it, T2 after
// TempSustainedTimeout and its reenable, T3 and its hold, T5 after the boot
// grace, and the heat-soak hold after an engine stop.
#include "protection/temperature_checks.h"

#include <gtest/gtest.h>

#include "params/constants.h"
#include "part_log.h"

namespace xr::test {
namespace {

struct TempRig {
  Params p;
  TemperatureChecks checks;
  PartLog log;
  TimeNs boot = log.t;
  void tick(double tempF, bool engineStopped = false, TimeNs dt = fromMs(5)) {
    log.t += dt;
    checks.update({Reading{tempF, log.t, true}, log.t, boot, engineStopped}, p, log.at());
    log.collect();
  }
  void run(double tempF, TimeNs span) {
    for (TimeNs end = log.t + span; log.t < end;) tick(tempF, false, fromMs(100));
  }
  double warnAt() const { return p.TemperatureLimitF + p.TempWarnExcess; }
  double critAt() const { return p.TemperatureLimitF + p.TempCritExcess; }
};

TEST(TemperatureChecksPart, T1AboveItsThresholdNotAtIt) {
  TempRig r;
  r.tick(r.warnAt());
  EXPECT_FALSE(r.checks.warning());
  r.tick(r.warnAt() + 0.1);
  EXPECT_TRUE(r.checks.warning());
  EXPECT_EQ(r.log.count(EventCode::ProtectionTrip, Reason::REASON_TEMP_WARNING), 1u);
}

TEST(TemperatureChecksPart, T2AfterTheSustainedTimeoutAndClearedByReenable) {
  TempRig r;
  r.run(r.warnAt() + 0.5, fromSec(r.p.TempSustainedTimeout) - fromMs(200));
  EXPECT_FALSE(r.checks.sustained());
  r.run(r.warnAt() + 0.5, fromMs(300));
  EXPECT_TRUE(r.checks.sustained());
  r.run(100.0, fromSec(1.0));
  EXPECT_TRUE(r.checks.sustained());  // latched: no auto-restart
  r.checks.reenable();
  EXPECT_FALSE(r.checks.sustained());
}

TEST(TemperatureChecksPart, T3AboveItsThresholdHeldWhileTheReadingIsBad) {
  TempRig r;
  r.tick(r.critAt());
  EXPECT_FALSE(r.checks.critical());
  r.tick(r.critAt() + 0.1);
  EXPECT_TRUE(r.checks.critical());
  r.tick(-100.0);  // out of the sensor's range: not a cooler reading
  EXPECT_TRUE(r.checks.critical());
  r.tick(100.0);
  EXPECT_FALSE(r.checks.critical());
}

TEST(TemperatureChecksPart, NeverReadIsStaleOnlyAfterTheBootGrace) {
  TempRig r;
  auto never = [&](TimeNs dt) {
    r.log.t += dt;
    r.checks.update({Reading{}, r.log.t, r.boot, false}, r.p, r.log.at());
    r.log.collect();
  };
  never(fromMs(k::TEMP_BOOT_GRACE_MS) - (r.log.t - r.boot));  // exactly the grace
  EXPECT_FALSE(r.checks.stale());
  never(1);
  EXPECT_TRUE(r.checks.stale());
  EXPECT_EQ(r.log.count(EventCode::TempSensorStale), 1u);
}

TEST(TemperatureChecksPart, HeatSoakHoldsAfterAnEngineStopUntilCooledToTheLimit) {
  TempRig r;
  r.tick(r.warnAt() + 1.0, true);  // engine stopped: soaking, T1 not counted
  EXPECT_TRUE(r.checks.soakHold());
  EXPECT_FALSE(r.checks.warning());
  r.tick(r.warnAt() + 1.0, false);  // restarted hot: held
  EXPECT_TRUE(r.checks.soakHold());
  EXPECT_EQ(r.log.count(EventCode::ProtectionTrip, Reason::REASON_TEMP_SOAK), 1u);
  r.tick(r.p.TemperatureLimitF, false);  // cooled to the limit
  EXPECT_FALSE(r.checks.soakHold());
}

}  // namespace
}  // namespace xr::test
