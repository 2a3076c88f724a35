// CurrentChecks on its own: hard overcurrent above its trip for its
// debounce, not at the trip; current stale after CurrentStaleMs, with the
// longer window in INA228 slow mode.
#include "protection/current_checks.h"

#include <gtest/gtest.h>

#include "params/constants.h"
#include "params/derived.h"
#include "part_log.h"

namespace xr::test {
namespace {

struct CurRig {
  Params p;
  CurrentChecks checks;
  PartLog log;
  TimeNs boot = log.t;
  TimeNs ch1 = 0, ina = 0;
  bool fast = true;
  void tick(double amps, TimeNs dt = fromMs(5), bool freshSamples = true) {
    log.t += dt;
    if (freshSamples) ch1 = ina = log.t;
    checks.update({amps, ch1, ina, fast, boot}, p, log.at());
    log.collect();
  }
};

TEST(CurrentChecksPart, HardOvercurrentAfterItsDebounceNotAtTheTrip) {
  CurRig r;
  const double trip = hardOCTripAmps(r.p);
  for (int i = 0; i < 20; ++i) r.tick(trip);
  EXPECT_FALSE(r.checks.hardOvercurrent());
  r.tick(trip + 0.1);
  EXPECT_FALSE(r.checks.hardOvercurrent());  // the debounce starts
  r.tick(trip + 0.1, fromMs(r.p.HardOCDebounceMs));
  EXPECT_TRUE(r.checks.hardOvercurrent());
  EXPECT_EQ(r.log.count(EventCode::ProtectionTrip, Reason::REASON_HARD_OVERCURRENT), 1u);
  r.tick(trip - 1.0);
  EXPECT_FALSE(r.checks.hardOvercurrent());  // resets at once
}

TEST(CurrentChecksPart, StaleAfterCurrentStaleMsInFastModeNotBefore) {
  CurRig r;
  r.tick(20.0, fromMs(k::INA_SLOW_INTERVAL_MS));  // fast mode settled
  r.tick(20.0);
  r.tick(20.0, fromMs(r.p.CurrentStaleMs), false);
  EXPECT_FALSE(r.checks.stale());
  r.tick(20.0, fromMs(1), false);
  EXPECT_TRUE(r.checks.stale());
}

TEST(CurrentChecksPart, SlowModeAllowsTwoMoreConversionPeriods) {
  CurRig r;
  r.fast = false;
  r.tick(20.0);
  r.ch1 = 0;  // CH1 keeps coming; only the INA228 pauses
  const TimeNs inaWin = fromMs(r.p.CurrentStaleMs) + 2 * fromMs(k::INA_SLOW_INTERVAL_MS);
  const TimeNs last = r.ina;
  r.log.t = last + inaWin;
  r.checks.update({20.0, r.log.t, last, false, r.boot}, r.p, r.log.at());
  EXPECT_FALSE(r.checks.stale());
  r.log.t += fromMs(1);
  r.checks.update({20.0, r.log.t, last, false, r.boot}, r.p, r.log.at());
  EXPECT_TRUE(r.checks.stale());
}

}  // namespace
}  // namespace xr::test
