// describe(): the specification's "Console Messages Reference" wording.
#include <gtest/gtest.h>

#include "core/events.h"

namespace xr {
namespace {

Event make(EventCode c, Reason r = Reason::NONE, double a = 0, double b = 0) {
  Event e;
  e.code = c;
  e.reason = r;
  e.a = a;
  e.b = b;
  return e;
}

TEST(EventWording, ConsoleMessagesReference) {
  EXPECT_EQ(describe(make(EventCode::ImmediateCut, Reason::REASON_TEMP_CRITICAL)),
            "GPIO4 immediate cut: TEMP_CRITICAL");
  EXPECT_EQ(describe(make(EventCode::CutAfterSettle, Reason::REASON_TEMP_WARNING)),
            "GPIO4 cut after settle: TEMP_WARNING");
  EXPECT_EQ(describe(make(EventCode::LockoutStarted, Reason::REASON_TEMP_WARNING, 30.0)),
            "Field lockout started: 30s cooldown before restart allowed");
  EXPECT_EQ(describe(make(EventCode::LockoutExpired)), "Field lockout expired - normal operation resumed");
  EXPECT_EQ(describe(make(EventCode::TempSensorStale)), "OneWire sensor stale, sensor dead or disconnected");
  EXPECT_EQ(
      describe(make(EventCode::VoltageDisagreement, Reason::REASON_VOLTAGE_DISAGREE_WARNING, 13.7, 13.5)),
      "Battery Voltage disagreement! BatteryV=13.70 V, IBV=13.50 V. Field shut off for safety!");
  Event m = make(EventCode::ModeChanged, Reason::REASON_RPM_LOW);
  m.mode = FieldControlMode::MODE_DISABLED_RAMP;
  EXPECT_EQ(describe(m), "Exiting normal mode: RPM_LOW");
  m.mode = FieldControlMode::MODE_NORMAL_AUTO_PID;
  EXPECT_EQ(describe(m), "Entering normal mode");
}

TEST(EventWording, TripsNameTheirValues) {
  EXPECT_EQ(describe(make(EventCode::ProtectionTrip, Reason::REASON_HARD_OVERCURRENT, 71.0, 70.0)),
            "Hard overcurrent: 71.0 A > 70.0 A trip. Field shut off!");
  EXPECT_EQ(describe(make(EventCode::ProtectionClear, Reason::REASON_TEMP_WARNING)),
            "Protection cleared: TEMP_WARNING");
}

}  // namespace
}  // namespace xr
