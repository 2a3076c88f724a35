// Charging held for long is an alarm (docs/protections.md "Charging held"):
// 15 minutes of engine run with the bank not full and nothing going in,
// at the limit and just below, and never with the bank full, the engine
// off or the owner's own choice.
#include "control/charge_hold.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

namespace xr {
namespace {

ChargeHoldSample heldByBms() {
  ChargeHoldSample s;
  s.engineRunning = true;
  s.bankFull = false;
  s.batteryA = -4.0;  // the house draws from the bank
  s.cause = ChargeHold::BMS;
  return s;
}

struct HoldRun {
  ChargeHoldDetector d;
  std::vector<Event> events;
  double t = 0.0;
  void feed(const ChargeHoldSample& s, double seconds) {
    for (double end = t + seconds; t < end - 1e-9; t += 1.0) {
      EventBatch ev;
      d.update(fromSec(t + 1.0), 1.0, s, ev);
      for (std::size_t i = 0; i < ev.count; ++i) events.push_back(ev.items[i]);
    }
  }
};

TEST(ChargeHold, FifteenMinutesHeldIsOneIncidentNamingWhatHoldsIt) {
  HoldRun r;
  r.feed(heldByBms(), 899);
  EXPECT_TRUE(r.events.empty());  // 14 min 59 s
  EXPECT_FALSE(r.d.alarm());
  EXPECT_EQ(r.d.cause(), ChargeHold::BMS);  // shown before the alarm
  r.feed(heldByBms(), 1);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].code, EventCode::ChargingHeld);
  EXPECT_EQ(r.events[0].level, EventLevel::Warning);
  EXPECT_TRUE(r.d.alarm());
  const std::string text = describe(r.events[0]);
  EXPECT_NE(text.find("15 min"), std::string::npos) << text;
  EXPECT_NE(text.find("the BMS"), std::string::npos) << text;
  r.feed(heldByBms(), 3 * 3600);
  EXPECT_EQ(r.events.size(), 1u);  // one, however long
}

TEST(ChargeHold, TheEndSaysForHowLong) {
  HoldRun r;
  r.feed(heldByBms(), 1800);
  ChargeHoldSample charging = heldByBms();
  charging.batteryA = 40.0;
  r.feed(charging, 59);
  EXPECT_EQ(r.events.size(), 1u);  // a minute without a hold ends it, not less
  r.feed(charging, 1);
  ASSERT_EQ(r.events.size(), 2u);
  EXPECT_EQ(r.events[1].level, EventLevel::Info);
  EXPECT_NEAR(r.events[1].a, 30.0, 0.1);
  EXPECT_NE(describe(r.events[1]).find("after 30 min held by BMS"), std::string::npos);
  EXPECT_FALSE(r.d.alarm());
}

TEST(ChargeHold, AMomentOfChargeDoesNotRestartTheCount) {
  HoldRun r;
  r.feed(heldByBms(), 600);
  ChargeHoldSample pulse = heldByBms();
  pulse.batteryA = 20.0;  // a BMS letting go for 20 s
  r.feed(pulse, 20);
  r.feed(heldByBms(), 300);
  EXPECT_EQ(r.events.size(), 1u);  // 600 + 300 s held
}

TEST(ChargeHold, NeverWithTheBankFullTheEngineOffOrCurrentGoingIn) {
  ChargeHoldSample full = heldByBms();
  full.bankFull = true;
  ChargeHoldSample stopped = heldByBms();
  stopped.engineRunning = false;
  ChargeHoldSample charging = heldByBms();
  charging.batteryA = ChargeHoldDetector::kNothingInA;  // 1 A goes in: charging, slowly
  ChargeHoldSample owner = heldByBms();
  owner.ownerChoice = true;  // switched off by the owner
  ChargeHoldSample unknown = heldByBms();
  unknown.batteryA = std::numeric_limits<double>::quiet_NaN();
  for (const auto& s : {full, stopped, charging, owner, unknown}) {
    HoldRun r;
    r.feed(s, 2 * 3600);
    EXPECT_TRUE(r.events.empty());
    EXPECT_EQ(r.d.cause(), ChargeHold::NONE);
  }
  HoldRun justUnder;
  ChargeHoldSample trickle = heldByBms();
  trickle.batteryA = ChargeHoldDetector::kNothingInA - 0.01;
  justUnder.feed(trickle, 900);
  EXPECT_EQ(justUnder.events.size(), 1u);
}

TEST(ChargeHold, EachCauseHasItsWords) {
  for (auto c : {ChargeHold::DVCC, ChargeHold::BATTERY_COLD, ChargeHold::WEATHER, ChargeHold::LIMIT}) {
    ChargeHoldSample s = heldByBms();
    s.cause = c;
    HoldRun r;
    r.feed(s, 900);
    ASSERT_EQ(r.events.size(), 1u);
    EXPECT_EQ(r.events[0].detail, static_cast<int>(c));
    EXPECT_EQ(describe(r.events[0]).find("nothing known"), std::string::npos);
  }
}

}  // namespace
}  // namespace xr
