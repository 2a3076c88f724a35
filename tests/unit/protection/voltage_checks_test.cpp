// VoltageChecks on its own: the hard shutdown at its threshold, the
// disagreement warning after its timeout (not just below the threshold), a
// dead sensor critical at once, and the INA228 latch's suppression.
#include "protection/voltage_checks.h"

#include <gtest/gtest.h>

#include "params/derived.h"
#include "part_log.h"

namespace xr::test {
namespace {

struct VoltRig {
  Params p;
  VoltageChecks checks;
  PartLog log;
  void tick(const VoltageChecksInput& in, TimeNs dt = fromMs(5)) {
    log.t += dt;
    checks.update(in, p, log.at());
    log.collect();
  }
  void run(const VoltageChecksInput& in, TimeNs span) {
    for (TimeNs end = log.t + span; log.t < end;) tick(in);
  }
};

TEST(VoltageChecksPart, HardShutdownAboveItsThresholdNotAtIt) {
  VoltRig r;
  const double hs = alternatorHardShutdownV(r.p);
  r.tick({hs, hs, false, false, false});
  EXPECT_FALSE(r.checks.altHardShutdown());
  r.tick({hs + 0.01, hs + 0.01, false, false, false});
  EXPECT_TRUE(r.checks.altHardShutdown());
  EXPECT_EQ(r.log.count(EventCode::ProtectionTrip, Reason::REASON_ALT_HARD_SHUTDOWN), 1u);
  // With the INA228 latch set too, its InaLatchSet line is the one log line.
  VoltRig both;
  both.tick({hs + 0.01, hs + 0.01, false, true, true});
  EXPECT_TRUE(both.checks.altHardShutdown());
  EXPECT_EQ(both.log.count(EventCode::ProtectionTrip, Reason::REASON_ALT_HARD_SHUTDOWN), 0u);
}

TEST(VoltageChecksPart, DisagreementWarnsAfterItsTimeoutAndNotJustBelowTheThreshold) {
  VoltRig r;
  const double over = 13.5 + r.p.VoltageDisagreeThreshold + 0.01;
  const double under = 13.5 + r.p.VoltageDisagreeThreshold - 0.01;
  r.run({under, 13.5, false, false, false}, fromSec(r.p.VoltageDisagreeTimeout + 1.0));
  EXPECT_FALSE(r.checks.disagreeWarning());
  r.run({over, 13.5, false, false, false}, fromSec(r.p.VoltageDisagreeTimeout) - fromMs(10));
  EXPECT_FALSE(r.checks.disagreeWarning());
  r.run({over, 13.5, false, false, false}, fromMs(20));
  EXPECT_TRUE(r.checks.disagreeWarning());
  EXPECT_EQ(r.log.count(EventCode::VoltageDisagreement), 1u);
  // The INA228 latch's suppression resets the timer and clears the flag.
  r.tick({over, 13.5, false, true, true});
  EXPECT_FALSE(r.checks.disagreeWarning());
}

TEST(VoltageChecksPart, DeadSensorIsCriticalAtOnceButNotBeforeItsFirstReading) {
  VoltRig r;
  r.tick({13.5, 0.05, true, false, false});  // not read yet: nothing
  EXPECT_FALSE(r.checks.disagreeCritical());
  r.tick({13.5, 0.05, false, false, false});
  EXPECT_TRUE(r.checks.disagreeCritical());
}

TEST(VoltageChecksPart, ImplausibleOnlyWhenBothSensorsAreOutsideTheRange) {
  VoltRig r;
  const VoltageRange range = plausibleVoltageRange(r.p);
  r.tick({range.max + 1.0, 13.5, false, false, false});
  EXPECT_FALSE(r.checks.implausible());
  r.tick({range.max + 1.0, range.max + 1.0, false, false, false});
  EXPECT_TRUE(r.checks.implausible());
}

}  // namespace
}  // namespace xr::test
