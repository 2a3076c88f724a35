// BatteryHealth on its own (docs/batteries.md "Measured capacity"): a swing
// of 30 % between points of known SoC is measured, one just below is not;
// the event; the BMS's SoC of the tick; the ledger round trip.
#include "battery/battery_health.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xr {
namespace {

constexpr TimeNs kT0 = fromSec(1000.0);

TEST(BatteryHealth, ASwingOfThirtyPercentIsMeasuredJustBelowItIsHeld) {
  BatteryHealth h;
  EventBatch ev;
  EXPECT_FALSE(h.knownSoc(kT0, 100.0, true, 200.0, ev));  // the first point anchors
  h.addAh(-59.8, 3600.0);
  EXPECT_FALSE(h.knownSoc(kT0, 70.1, false, 200.0, ev)) << "29.9 %: too small a swing";
  EXPECT_EQ(ev.count, 0u);
  h.addAh(-0.2, 60.0);
  EXPECT_TRUE(h.knownSoc(kT0, 70.0, false, 200.0, ev));  // 60 Ah over 30 %: 200 Ah
  ASSERT_EQ(ev.count, 1u);
  EXPECT_EQ(ev.items[0].code, EventCode::CapacityMeasured);
  EXPECT_NEAR(ev.items[0].a, 200.0, 1e-9);
  EXPECT_EQ(h.capacity().cycles(), 1);
  EXPECT_TRUE(std::isnan(h.capacity().measuredAh())) << "one swing is not yet a figure";
}

TEST(BatteryHealth, KeepsTheBmsSocOfTheLastTickOnly) {
  BatteryHealth h;
  HealthInput in;
  in.dt_s = 1.0;
  in.capacityAh = 200.0;
  in.bmsSocPct = 55.0;
  h.update(in);
  EXPECT_DOUBLE_EQ(h.bmsSocPct(), 55.0);
  in.bmsSocPct = kNoValue;  // stale now
  h.update(in);
  EXPECT_TRUE(std::isnan(h.bmsSocPct()));
}

TEST(BatteryHealth, LedgerRoundTrip) {
  BatteryHealth h;
  EventBatch ev;
  h.knownSoc(kT0, 100.0, true, 200.0, ev);
  h.addAh(-80.0, 3600.0);
  BatteryLedger l;
  h.toLedger(l);
  BatteryHealth back;
  back.restore(l);
  BatteryLedger again;
  back.toLedger(again);
  EXPECT_EQ(again.capacity, l.capacity);
  EXPECT_EQ(again.resistance, l.resistance);
  EXPECT_DOUBLE_EQ(l.capacity.NetAh, -80.0);
}

}  // namespace
}  // namespace xr
