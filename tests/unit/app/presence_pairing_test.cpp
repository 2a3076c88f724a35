// Pairing by presence (app/presence_pairing.h): the ignition turned
// off-on-off-on within 10 s opens a pairing window once; slower turns, a
// single restart, or the input staying where it is do not. Also the window
// it opens: any one device pairs without a code, paired devices or not.
#include "app/presence_pairing.h"

#include <gtest/gtest.h>

#include "web/server/pairing.h"

namespace xr::app {
namespace {

// Feeds `on` from t to t+holdMs every 100 ms (the supervisor's rate).
bool hold(PresenceSequence& s, bool on, std::int64_t& t, std::int64_t holdMs) {
  bool fired = false;
  for (std::int64_t end = t + holdMs; t < end; t += 100) fired |= s.feed(on, t);
  return fired;
}

TEST(PresenceSequence, OffOnOffOnWithinTenSecondsOpensOnce) {
  PresenceSequence s;
  std::int64_t t = 0;
  EXPECT_FALSE(hold(s, false, t, 60'000));  // parked for a minute
  EXPECT_FALSE(hold(s, true, t, 2'000));
  EXPECT_FALSE(hold(s, false, t, 2'000));
  EXPECT_TRUE(hold(s, true, t, 2'000));  // the first on to the last: 4 s
  EXPECT_FALSE(hold(s, true, t, 30'000)) << "once per sequence";
}

TEST(PresenceSequence, TheSequenceAtItsTenSecondLimitCountsAndJustOverDoesNot) {
  for (const std::int64_t span : {10'000, 10'100}) {
    PresenceSequence s;
    std::int64_t t = 0;
    hold(s, false, t, 1'000);
    hold(s, true, t, span / 2);
    hold(s, false, t, span - span / 2);
    EXPECT_EQ(s.feed(true, t), span <= kPresenceSequenceMs) << span;
  }
}

TEST(PresenceSequence, FromRunningTheLastThreeTurnsCount) {
  PresenceSequence s;
  std::int64_t t = 0;
  hold(s, true, t, 60'000);  // the engine ran
  hold(s, false, t, 1'000);
  hold(s, true, t, 1'000);
  hold(s, false, t, 1'000);
  EXPECT_TRUE(hold(s, true, t, 1'000));
}

TEST(PresenceSequence, AStopAndARestartDoNotOpen) {
  PresenceSequence s;
  std::int64_t t = 0;
  hold(s, true, t, 60'000);
  EXPECT_FALSE(hold(s, false, t, 3'000));
  EXPECT_FALSE(hold(s, true, t, 60'000));
}

TEST(PresenceSequence, AStartingLevelIsNotATurn) {
  PresenceSequence s;
  std::int64_t t = 0;
  // The first sample is "on": no "off before" was seen, so on-off-on is only two turns.
  EXPECT_FALSE(hold(s, true, t, 1'000));
  EXPECT_FALSE(hold(s, false, t, 1'000));
  EXPECT_FALSE(hold(s, true, t, 1'000));
}

TEST(PresenceWindow, OneDevicePairsWithoutACodeWhenDevicesArePairedAlready) {
  std::int64_t ms = 1'000;
  web::Pairing p{std::make_shared<web::MemoryAuthStore>(), [&] { return ms; }};
  ASSERT_EQ(p.pair(p.newCode().code, "owner").kind, web::Pairing::Outcome::Paired);
  EXPECT_EQ(p.pairInWindow("crew").kind, web::Pairing::Outcome::NoWindow);
  p.openPresenceWindow(kPresenceWindowMs);
  const auto crew = p.pairInWindow("crew");
  ASSERT_EQ(crew.kind, web::Pairing::Outcome::Paired);
  EXPECT_NE(p.ownerId(), crew.device.id);  // the owner stays the owner
  // One device per window: the next is told the window was used, and by whom.
  const auto third = p.pairInWindow("third");
  EXPECT_EQ(third.kind, web::Pairing::Outcome::WindowClaimed);
  EXPECT_NE(third.claimedBy.find("\"crew\""), std::string::npos) << third.claimedBy;
  p.openPresenceWindow(kPresenceWindowMs);
  ms += kPresenceWindowMs;
  EXPECT_EQ(p.pairInWindow("late").kind, web::Pairing::Outcome::NoWindow);
}

}  // namespace
}  // namespace xr::app
