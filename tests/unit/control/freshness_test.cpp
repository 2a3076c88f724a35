// One freshness rule per input (docs/architecture.md "Freshness"): each rule
// at its limit and just past it, and the consumers that used to hold their
// own rule now follow the shared one.
#include "core/freshness.h"

#include <gtest/gtest.h>

#include "params/constants.h"
#include "reg_rig.h"

namespace xr {
namespace {

Reading at(double value, TimeNs stamp) { return Reading{value, stamp, false}; }

TEST(Freshness, AReadingIsFreshUpToItsMaximumAgeAndNotANanosecondLonger) {
  const TimeNs now = fromSec(100.0);
  EXPECT_TRUE(fresh::within(at(1.0, now - fromSec(5.0)), now, fromSec(5.0)));
  EXPECT_FALSE(fresh::within(at(1.0, now - fromSec(5.0) - 1), now, fromSec(5.0)));
  EXPECT_FALSE(fresh::within(at(1.0, 0), now, fromSec(500.0))) << "never read";
  EXPECT_FALSE(fresh::within(at(kNoValue, now), now, fromSec(5.0))) << "no value";
}

TEST(Freshness, TheEngineSpeedIsFreshForOneSecond) {
  const TimeNs now = fromSec(100.0);
  EXPECT_TRUE(fresh::engineRpm(at(1500.0, now - fromSec(1.0)), now));
  EXPECT_FALSE(fresh::engineRpm(at(1500.0, now - fromSec(1.0) - 1), now));
}

TEST(Freshness, TheEngineTurnsFrom200Rpm) {
  EXPECT_TRUE(fresh::engineTurning(200.0));
  EXPECT_FALSE(fresh::engineTurning(199.9));
  EXPECT_FALSE(fresh::engineTurning(kNoValue));
}

TEST(Freshness, ABmsIsHeardForBmsStaleS) {
  const TimeNs now = fromSec(100.0);
  EXPECT_TRUE(fresh::bms(now - fromSec(5.0), now, 5.0));
  EXPECT_FALSE(fresh::bms(now - fromSec(5.0) - 1, now, 5.0));
}

TEST(Freshness, TheBatteryTemperatureNeedsItsRangeAndTwentySeconds) {
  const TimeNs now = fromSec(100.0);
  const TimeNs limit = fromMs(k::BATTERY_TEMP_STALE_MS);
  EXPECT_TRUE(fresh::batteryTemp(at(20.0, now - limit), now));
  EXPECT_FALSE(fresh::batteryTemp(at(20.0, now - limit - 1), now));
  EXPECT_TRUE(fresh::batteryTemp(at(k::BATTERY_TEMP_VALID_MAX_C, now), now));
  EXPECT_FALSE(fresh::batteryTemp(at(k::BATTERY_TEMP_VALID_MAX_C + 0.1, now), now));
  EXPECT_FALSE(fresh::batteryTemp(at(k::BATTERY_TEMP_VALID_MIN_C - 0.1, now), now));
}

TEST(Freshness, TheAlternatorTemperatureNeedsItsRangeAndTwentySeconds) {
  const TimeNs now = fromSec(100.0);
  const TimeNs limit = fromMs(k::TEMP_STALE_MS);
  EXPECT_TRUE(fresh::alternatorTemp(at(180.0, now - limit), now));
  EXPECT_FALSE(fresh::alternatorTemp(at(180.0, now - limit - 1), now));
  EXPECT_FALSE(fresh::alternatorTemp(at(k::TEMP_VALID_MAX_F + 1.0, now), now));
}

// The wear count reads the temperature the protections act on: a reading out
// of the sensor's range adds nothing to the insulation life used, where it
// used to count as a glowing-hot winding for a minute.
TEST(Freshness, AnOutOfRangeAlternatorTemperatureAddsNoWear) {
  test::RegRig hot;
  hot.tempF = 250.0;  // in range and hot: it wears
  hot.run(30.0);
  const double hotWear = hot.out->telemetry.wear.alt_life_used_pct;
  EXPECT_GT(hotWear, 0.0);

  test::RegRig broken;
  broken.tempF = k::TEMP_VALID_MAX_F + 200.0;  // a shorted thermistor, say
  broken.run(30.0);
  EXPECT_DOUBLE_EQ(broken.out->telemetry.wear.alt_life_used_pct, 0.0);
  EXPECT_GT(broken.out->telemetry.wear.alt_run_hours, 0.0) << "the running hours still count";
}

}  // namespace
}  // namespace xr
