// One clock (docs/architecture.md "One clock"): in simulation the store's
// events and the charge summaries are stamped on the simulated clock, so a
// 100 s fault is 100 s apart and a 2 h charge at --speed 30, read once a
// wall second, counts 2 h of amp-hours.
#include <gtest/gtest.h>

#include "app/store_service.h"
#include "runtime/wall_clock.h"
#include "store_test_util.h"

namespace xr::app {
namespace {

using xr::test::TempDir;

Event eventAt(EventCode code) {
  Event e;
  e.code = code;
  e.level = EventLevel::Warning;
  return e;
}

TEST(OneClock, EventsAreStampedOnTheSimulatedClock) {
  TempDir d;
  StoreService svc(d.file("x.db"), 300);
  TimeNs simulated = 0;
  rt::WallClock clock;
  clock.followSimulation([&] { return simulated; });
  svc.useClock(clock, 30.0);
  svc.appendEvent(eventAt(EventCode::AlarmOn));
  simulated += fromSec(100.0);  // 3.3 s of wall time at --speed 30
  svc.appendEvent(eventAt(EventCode::AlarmOff));
  const auto rows = svc.queryEvents(10, std::nullopt);
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows[0].tMs - rows[1].tMs, 100'000);  // newest first
  svc.stop(BatteryLedger{}, false);
}

TEST(OneClock, ATwoHourChargeAtSpeed30CountsTwoHours) {
  TempDir d;
  StoreService svc(d.file("x.db"), 300);
  TimeNs simulated = 0;
  rt::WallClock clock;
  clock.followSimulation([&] { return simulated; });
  svc.useClock(clock, 30.0);
  rt::RuntimeSnapshot s;
  s.tick = 1000;
  s.telemetry.field_enable = true;
  s.telemetry.stage = ChargeStage::BULK;
  s.telemetry.alt_a = 50.0;
  s.telemetry.battery_v = 14.0;
  s.telemetry.bcur_a = 45.0;
  // The supervisor's once-a-second housekeeping: 30 simulated seconds each.
  for (int i = 0; i <= 240; ++i) {
    s.telemetry.now = simulated;
    svc.housekeeping(s, BatteryLedger{}, false);
    simulated += fromSec(30.0);
  }
  const auto charges = svc.charges(1);
  ASSERT_EQ(charges.size(), 1u);
  EXPECT_NEAR(charges[0].altAh, 100.0, 2.0);    // 50 A for 2 h, within 2 %
  EXPECT_NEAR(charges[0].altWh, 1400.0, 28.0);  // at 14 V
  EXPECT_NEAR(static_cast<double>(charges[0].endMs - charges[0].startMs), 7'200'000.0, 144'000.0);
  svc.stop(BatteryLedger{}, false);
}

}  // namespace
}  // namespace xr::app
