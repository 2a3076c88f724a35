// BeltSlipDetector on synthetic signals (docs/operations.md "Belt slip").
#include "health/belt_slip.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace xr {
namespace {

using namespace belt_k;

struct Drive {
  BeltSlipDetector d;
  EventBatch ev;
  double t = 0.0;
  int events = 0;
  int lastDetail = 0;
  void feed(double seconds, const BeltSample& s) {
    for (int i = 0; i < static_cast<int>(seconds * 10); ++i) {
      t += 0.1;
      ev.clear();
      if (d.update(fromSec(t), 0.1, s, ev)) {
        ++events;
        lastDetail = ev.count ? ev.items[ev.count - 1].detail : -1;
      }
    }
  }
};

BeltSample grip(double rpm = 1800.0) {
  BeltSample s;
  s.rpm = rpm;
  s.engineRpm = rpm;
  s.altAmps = 60.0;
  s.dutyPct = 50.0;
  s.targetAmps = 60.0;
  s.fieldOn = true;
  return s;
}

TEST(BeltSlipDetector, ARatioFivePercentLowForTenSecondsIsOneEvent) {
  Drive r;
  r.feed(60, grip());
  BeltSample s = grip();
  s.rpm = 1800.0 * 0.94;  // 6 % slower than learned
  r.feed(kHoldS + 2, s);
  EXPECT_EQ(r.events, 1);
  EXPECT_EQ(r.lastDetail, 1);
  r.feed(300, s);  // the same episode: no second event
  EXPECT_EQ(r.events, 1);
  EXPECT_TRUE(r.d.slipping());
}

TEST(BeltSlipDetector, FourPercentLowOrTooShortIsNothing) {
  Drive r;
  r.feed(60, grip());
  BeltSample s = grip();
  s.rpm = 1800.0 * 0.96;
  r.feed(60, s);
  EXPECT_EQ(r.events, 0);
  s.rpm = 1800.0 * 0.90;
  r.feed(kHoldS - 2, s);
  r.feed(5, grip());
  EXPECT_EQ(r.events, 0);
}

TEST(BeltSlipDetector, AChangingEngineSpeedIsNotASlip) {
  Drive r;
  r.feed(60, grip());
  // The engine accelerates 1800 -> 2400 over 20 s while the tach lags 8 %.
  for (int i = 0; i < 20; ++i) {
    BeltSample s = grip(1800.0 + 30.0 * i);
    s.rpm = s.engineRpm * 0.92;
    r.feed(1, s);
  }
  EXPECT_EQ(r.events, 0);
}

TEST(BeltSlipDetector, CurrentDownWhileDutyUpAtSteadySpeedIsOneEvent) {
  Drive r;
  BeltSample s = grip();
  s.engineRpm = kNoValue;  // no NMEA 2000
  r.feed(30, s);
  for (int i = 0; i < 25; ++i) {  // duty +1 point/s, current -0.5 A/s
    s.dutyPct = 50.0 + i;
    s.altAmps = 60.0 - 0.5 * i;
    r.feed(1, s);
  }
  EXPECT_EQ(r.events, 1);
  EXPECT_EQ(r.lastDetail, 2);
}

TEST(BeltSlipDetector, CurrentDownWhenTheRegulatorAsksLessIsNothing) {
  Drive r;
  BeltSample s = grip();
  s.engineRpm = kNoValue;
  r.feed(30, s);
  for (int i = 0; i < 25; ++i) {
    s.dutyPct = 50.0 + i;
    s.altAmps = 60.0 - 0.5 * i;
    s.targetAmps = s.altAmps + 2.0;  // the current follows its target down
    r.feed(1, s);
  }
  EXPECT_EQ(r.events, 0);
}

TEST(BeltSlipDetector, ANewEpisodeNeedsTenQuietMinutes) {
  Drive r;
  r.feed(60, grip());
  BeltSample s = grip();
  s.rpm = 1800.0 * 0.9;
  r.feed(20, s);
  EXPECT_EQ(r.events, 1);
  r.feed(kRearmS - 30, grip());
  r.feed(20, s);
  EXPECT_EQ(r.events, 1);
  r.feed(kRearmS + 5, grip());
  r.feed(20, s);
  EXPECT_EQ(r.events, 2);
}

// C: the tach alone. A toy of the belt and the regulator, 10 ticks a
// second: the alternator gives `want` A (or the probe's cap, through a
// first-order lag of 1 s), and the tach reads the engine's speed less the
// belt's slip, `slip` of it at 120 A and in proportion below.
struct TachOnly {
  Drive r;
  double amps = 80.0, engine = 1800.0, slip = 0.0;
  double want = 80.0;
  bool probed = false;
  void run(double seconds) {
    for (int i = 0; i < static_cast<int>(seconds * 10); ++i) {
      const double target = std::min(want, r.d.probeCapA());
      probed = probed || r.d.probing();
      amps += (target - amps) * 0.1;
      BeltSample s;
      s.rpm = engine * (1.0 - slip * amps / 120.0);
      s.altAmps = amps;
      s.dutyPct = 60.0;
      s.targetAmps = target;
      s.fieldOn = true;
      s.ratedA = 120.0;
      r.feed(0.1, s);
    }
  }
};

TEST(BeltSlipDetector, TachAloneASpeedThatFollowsTheCurrentIsOneEvent) {
  TachOnly b;
  b.run(60);
  b.slip = 0.5;  // the belt starts slipping at 80 A: the tach falls 33 %
  b.run(30);
  EXPECT_TRUE(b.probed);
  EXPECT_EQ(b.r.events, 1);
  EXPECT_EQ(b.r.lastDetail, 3);
  EXPECT_FALSE(b.r.d.probing());
  b.run(600);  // the same episode: no second event, no more probes
  EXPECT_EQ(b.r.events, 1);
  EXPECT_GE(b.r.d.probeCapA(), 1e299);
}

TEST(BeltSlipDetector, TachAloneAnEngineThatSlowsIsProbedButNoEvent) {
  TachOnly b;
  b.run(60);
  b.engine = 1300.0;  // the skipper pulls the throttle back
  b.run(30);
  EXPECT_TRUE(b.probed);
  EXPECT_EQ(b.r.events, 0);
  EXPECT_FALSE(b.r.d.probing());
  EXPECT_GE(b.r.d.probeCapA(), 1e299);  // the cap is released
}

TEST(BeltSlipDetector, TachAloneThrottleBackThenUpAgainIsNoEvent) {
  TachOnly b;
  b.run(60);
  b.engine = 1300.0;
  b.run(3);  // the probe starts
  ASSERT_TRUE(b.r.d.probing());
  b.engine = 1900.0;  // ... and the throttle goes up during it, and stays
  b.run(30);
  EXPECT_EQ(b.r.events, 0);
}

TEST(BeltSlipDetector, TachAloneAFallAtLowCurrentIsNotProbed) {
  TachOnly b;
  b.want = b.amps = 0.35 * 120.0;  // below kProbeLoadShare of the rating
  b.run(60);
  b.slip = 0.5;
  b.run(30);
  EXPECT_FALSE(b.probed);
  EXPECT_EQ(b.r.events, 0);
}

TEST(BeltSlipDetector, TachAloneOneProbeInFiveMinutes) {
  TachOnly b;
  b.run(60);
  b.engine = 1300.0;
  b.run(30);
  ASSERT_TRUE(b.probed);
  b.probed = false;
  b.engine = 1800.0;
  b.run(60);
  b.engine = 1300.0;  // a second throttle back within kProbeRearmS
  b.run(30);
  EXPECT_FALSE(b.probed);
}

}  // namespace
}  // namespace xr
