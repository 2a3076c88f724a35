// The one rule for the alternator temperature (core/alternator_temperature.h):
// which sensor TempSource names, and when a reading counts — at the stale
// limit, just past it, and at the ends of the sensors' range.
#include "core/alternator_temperature.h"

#include <gtest/gtest.h>

#include <cmath>

namespace xr {
namespace {

TEST(AlternatorTemperature, TempSourceNamesTheSensor) {
  Inputs in;
  in.AlternatorTemperatureF = {150.0, 1, true};
  in.thermistorF = {160.0, 1, true};
  EXPECT_DOUBLE_EQ(alternatorTemperature(in, 0).value, 150.0);
  EXPECT_DOUBLE_EQ(alternatorTemperature(in, 1).value, 160.0);
}

TEST(AlternatorTemperature, AReadingCountsUpToTheStaleLimitAndNotAfter) {
  const TimeNs stamp = fromMs(1000);
  const TimeNs limit = stamp + fromMs(k::TEMP_STALE_MS);
  EXPECT_TRUE(temperatureFresh(150.0, stamp, limit));
  EXPECT_FALSE(temperatureFresh(150.0, stamp, limit + 1));
  EXPECT_FALSE(temperatureFresh(150.0, 0, fromMs(10)));  // never read
}

TEST(AlternatorTemperature, OnlyReadingsInTheSensorsRangeCount) {
  EXPECT_TRUE(temperatureInRange(k::TEMP_VALID_MIN_F));
  EXPECT_TRUE(temperatureInRange(k::TEMP_VALID_MAX_F));
  EXPECT_FALSE(temperatureInRange(k::TEMP_VALID_MAX_F + 0.1));
  EXPECT_FALSE(temperatureInRange(k::TEMP_VALID_MIN_F - 0.1));
  EXPECT_FALSE(temperatureInRange(NAN));
  EXPECT_FALSE(temperatureFresh(k::TEMP_VALID_MAX_F + 1.0, fromMs(1), fromMs(2)));
}

}  // namespace
}  // namespace xr
