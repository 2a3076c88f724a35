// The journal says what changed, once (docs/operations.md "The journal"):
// a held alarm row is one line per episode, not one per 30 s repeat.
#include "logging/journal_gate.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace xr::logging {
namespace {

Event ev(EventCode code, int detail = 0) {
  Event e;
  e.code = code;
  e.detail = detail;
  return e;
}

TEST(JournalGate, AHeldAlarmRowIsOneLinePerEpisode) {
  JournalGate g;
  EXPECT_TRUE(g.pass(ev(EventCode::AlarmCondition, 0)));  // TempHigh: said
  EXPECT_FALSE(g.pass(ev(EventCode::AlarmOn)));           // the same tick: the row's line says it
  int repeats = 0;
  for (int i = 0; i < 200; ++i) repeats += g.pass(ev(EventCode::AlarmCondition, 0)) ? 1 : 0;
  EXPECT_EQ(repeats, 0);
  EXPECT_TRUE(g.pass(ev(EventCode::AlarmCondition, 2)));  // another row joining: said once
  EXPECT_FALSE(g.pass(ev(EventCode::AlarmCondition, 2)));
  EXPECT_TRUE(g.pass(ev(EventCode::AlarmOff)));
  // The next episode names its rows again.
  EXPECT_TRUE(g.pass(ev(EventCode::AlarmCondition, 0)));
}

TEST(JournalGate, TheFieldOffOfAnImmediateCutIsSaidByTheCut) {
  JournalGate g;
  Event cut = ev(EventCode::ImmediateCut);
  cut.reason = Reason::REASON_TEMP_CRITICAL;
  Event off = ev(EventCode::FieldOff);
  off.reason = Reason::REASON_TEMP_CRITICAL;
  EXPECT_TRUE(g.pass(cut));
  EXPECT_FALSE(g.pass(off));
  off.reason = Reason::REASON_RPM_LOW;  // an off for another cause is news
  EXPECT_TRUE(g.pass(off));
}

TEST(JournalGate, LimpHomeIsSaidOnceUntilTheModeChanges) {
  JournalGate g;
  EXPECT_TRUE(g.pass(ev(EventCode::LimpHomeActive)));
  EXPECT_FALSE(g.pass(ev(EventCode::LimpHomeActive)));
  EXPECT_TRUE(g.pass(ev(EventCode::ModeChanged)));
  EXPECT_TRUE(g.pass(ev(EventCode::LimpHomeActive)));
}

TEST(JournalGate, EveryOtherEventPasses) {
  JournalGate g;
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(g.pass(ev(EventCode::ProtectionTrip)));
    EXPECT_TRUE(g.pass(ev(EventCode::StageChanged)));
    EXPECT_TRUE(g.pass(ev(EventCode::BmsBadFrames)));  // its own rate limit, not this gate's
  }
}

// A value never read is NaN in the event: no message shows "nan" (the
// INA228 alert at start read "IBV=nan V"), whatever the code and reason.
TEST(EventWords, AValueNeverReadReadsNoReadingNeverNan) {
  for (int code = 0; code < kEventCodeCount; ++code)
    for (int reason = 0; reason <= static_cast<int>(Reason::REASON_BANK_MISMATCH); ++reason)
      for (int detail = 0; detail < 3; ++detail) {
        Event e;
        e.code = static_cast<EventCode>(code);
        e.reason = static_cast<Reason>(reason);
        e.detail = detail;
        e.a = std::nan("");
        e.b = -std::nan("");
        const std::string text = describe(e);
        EXPECT_EQ(text.find("nan"), std::string::npos) << text;
        e.a = INFINITY;
        EXPECT_EQ(describe(e).find("inf "), std::string::npos) << describe(e);
      }
  Event ina;
  ina.code = EventCode::InaLatchSet;
  ina.a = std::nan("");
  ina.b = 14.8;
  EXPECT_EQ(describe(ina),
            "INA228 hardware overvoltage alert: IBV=no reading (limit 14.80 V). Field cut, latched");
}

TEST(EventWords, WordsThatHoldNanOrInfAreLeftAlone) {
  Event e;
  e.code = EventCode::ProtectionTrip;
  e.reason = Reason::REASON_RPM_LOW;
  e.a = 150;
  e.b = 200;
  EXPECT_EQ(describe(e), "RPM below minimum: 150 < 200 RPM. Field off");
}

}  // namespace
}  // namespace xr::logging
