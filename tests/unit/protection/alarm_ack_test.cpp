// Acknowledging an alarm (docs/protections.md "Acknowledging an alarm"):
// the buzzer goes quiet, the protection keeps acting; a new alarm row sounds
// again; the acknowledgement ends once every row has been quiet for 30 s.
#include <gtest/gtest.h>

#include "rig.h"

namespace xr::test {
namespace {

// A thermal trip (T3) in AUTO: the field is cut and the buzzer sounds.
Rig thermalFault() {
  Rig r;
  r.warmUp();
  r.tempF = 170.0;  // above TemperatureLimitF 150 + TempCritExcess 10
  r.run(fromSec(1.0));
  return r;
}

TEST(AlarmAck, SilencesTheBuzzerNotTheProtection) {
  Rig r = thermalFault();
  ASSERT_TRUE(r.buzzer);
  ASSERT_EQ(r.d.reason, Reason::REASON_TEMP_CRITICAL);
  r.sup.acknowledgeAlarm();
  r.tick();
  EXPECT_FALSE(r.buzzer) << "quiet at the next tick";
  EXPECT_TRUE(r.sup.alarmAcknowledged());
  r.run(fromSec(5.0));
  EXPECT_FALSE(r.buzzer);
  EXPECT_TRUE(r.sup.flags().tempCritical) << "the protection still acts";
  EXPECT_EQ(r.d.reason, Reason::REASON_TEMP_CRITICAL);
  EXPECT_FALSE(r.sc.fieldEnable) << "the field stays cut";
}

TEST(AlarmAck, ANewAlarmRowSoundsAgain) {
  Rig r = thermalFault();
  r.sup.acknowledgeAlarm();
  r.run(fromSec(1.0));
  ASSERT_FALSE(r.buzzer);
  r.ibv = r.batteryV = 15.2;  // VoltageAlarmHigh (15 V): a row that was not sounding
  r.run(fromMs(300));
  EXPECT_TRUE(r.buzzer);
  EXPECT_FALSE(r.sup.alarmAcknowledged());
}

TEST(AlarmAck, EndsAfterEveryRowWasQuiet30sSoTheNextAlarmSounds) {
  Rig r = thermalFault();
  r.sup.acknowledgeAlarm();
  r.tempF = 100.0;  // the cause is gone
  r.run(fromSec(29.0));
  EXPECT_TRUE(r.sup.alarmAcknowledged()) << "a row hovering on its threshold stays acknowledged";
  r.run(fromSec(120.0));  // past the hold (and the cooldown)
  EXPECT_FALSE(r.sup.alarmAcknowledged());
  r.tempF = 170.0;
  r.run(fromSec(1.0));
  EXPECT_TRUE(r.buzzer) << "the next fault is heard";
}

TEST(AlarmAck, ReleasesALatchedBuzzer) {
  Params p;
  p.AlarmLatchEnabled = true;
  Rig r(p);
  r.warmUp();
  r.tempF = 170.0;
  r.run(fromSec(1.0));
  r.tempF = 100.0;
  r.run(fromSec(2.0));
  ASSERT_TRUE(r.buzzer) << "latched";
  r.sup.acknowledgeAlarm();
  r.tick();
  EXPECT_FALSE(r.buzzer);
}

TEST(AlarmAck, WithNothingSoundingChangesNothing) {
  Rig r;
  r.warmUp();
  r.sup.acknowledgeAlarm();
  r.run(fromSec(31.0));
  EXPECT_FALSE(r.sup.alarmAcknowledged());
  r.tempF = 170.0;
  r.run(fromSec(1.0));
  EXPECT_TRUE(r.buzzer);
  EXPECT_EQ(r.d.reason, Reason::REASON_TEMP_CRITICAL);
}

}  // namespace
}  // namespace xr::test
