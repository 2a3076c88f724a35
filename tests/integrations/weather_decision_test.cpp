// Weather mode's rule and the Open-Meteo parser, at their edges
// (docs/integrations.md "Weather").
#include "integrations/weather_decision.h"

#include <gtest/gtest.h>

#include <string>

#include "integrations/weather_forecast.h"

using namespace xr::integrations;

namespace {

Forecast threeDays(std::optional<double> a, std::optional<double> b, std::optional<double> c) {
  Forecast f;
  f.dayCount = 3;
  f.days[0].uvIndexMax = a;
  f.days[1].uvIndexMax = b;
  f.days[2].uvIndexMax = c;
  return f;
}

std::string daily(const std::string& uv, const std::string& rad = "[20.1,18.2,19.5]",
                  const std::string& time = R"(["2026-12-05","2026-12-06","2026-12-07"])") {
  return R"({"latitude":43.3,"longitude":5.4,"timezone":"Europe/Paris","daily_units":{"time":"iso8601",)"
         R"("uv_index_max":"","shortwave_radiation_sum":"MJ/m²"},"daily":{"time":)" +
         time + R"(,"uv_index_max":)" + uv + R"(,"shortwave_radiation_sum":)" + rad + "}}";
}

}  // namespace

TEST(WeatherDecision, TwoDaysJustAboveTheThresholdHoldTheAlternatorOff) {
  const auto d = decideWeatherMode(threeDays(6.01, 6.01, 1.0), 6.0, 60.0);
  EXPECT_TRUE(d.active);
  EXPECT_EQ(d.sunnyDays, 2);
}

TEST(WeatherDecision, DaysExactlyAtTheThresholdAreNotSunny) {
  const auto d = decideWeatherMode(threeDays(6.0, 6.0, 6.0), 6.0, 60.0);
  EXPECT_FALSE(d.active);
  EXPECT_EQ(d.sunnyDays, 0);
}

TEST(WeatherDecision, OneSunnyDayOfThreeCharges) {
  EXPECT_FALSE(decideWeatherMode(threeDays(9.0, 2.0, 6.0), 6.0, 60.0).active);
}

TEST(WeatherDecision, ANullDayCountsAsNotSunny) {
  EXPECT_FALSE(decideWeatherMode(threeDays(9.0, std::nullopt, 2.0), 6.0, 60.0).active);
  EXPECT_TRUE(decideWeatherMode(threeDays(9.0, std::nullopt, 7.0), 6.0, 60.0).active);
}

TEST(WeatherDecision, AMissingDayCountsAsNotSunny) {
  Forecast f = threeDays(9.0, 9.0, 9.0);
  f.dayCount = 1;  // the server sent one day
  EXPECT_FALSE(decideWeatherMode(f, 6.0, 60.0).active);
  f.dayCount = 2;
  EXPECT_TRUE(decideWeatherMode(f, 6.0, 60.0).active);
}

TEST(WeatherDecision, AForecastOlderThan24HoursCharges) {
  const Forecast sunny = threeDays(9.0, 9.0, 9.0);
  EXPECT_TRUE(decideWeatherMode(sunny, 6.0, kForecastMaxAgeS).active);
  const auto d = decideWeatherMode(sunny, 6.0, kForecastMaxAgeS + 1.0);
  EXPECT_FALSE(d.active);
  EXPECT_NE(d.why.find("older than 24 h"), std::string::npos);
}

TEST(OpenMeteoParse, ReadsThreeDaysWithTheirUvAndRadiation) {
  const auto r = parseOpenMeteoDaily(daily("[7.5,null,8.25]"));
  ASSERT_TRUE(r.forecast) << r.error;
  EXPECT_EQ(r.forecast->dayCount, 3);
  EXPECT_EQ(r.forecast->days[0].date, "2026-12-05");
  EXPECT_DOUBLE_EQ(*r.forecast->days[0].uvIndexMax, 7.5);
  EXPECT_FALSE(r.forecast->days[1].uvIndexMax);
  EXPECT_DOUBLE_EQ(*r.forecast->days[2].radiationMJm2, 19.5);
}

TEST(OpenMeteoParse, RefusesWhatIsNotJson) {
  const auto r = parseOpenMeteoDaily("{\"daily\": [");
  EXPECT_FALSE(r.forecast);
  EXPECT_EQ(r.error, "not JSON");
}

TEST(OpenMeteoParse, RefusesTheWrongShape) {
  EXPECT_FALSE(parseOpenMeteoDaily(R"({"hourly":{}})").forecast);
  EXPECT_FALSE(parseOpenMeteoDaily("[1,2,3]").forecast);
  EXPECT_FALSE(parseOpenMeteoDaily(daily("[7.5,8.0]")).forecast);            // lengths differ
  EXPECT_FALSE(parseOpenMeteoDaily(daily(R"([7.5,"high",8.0])")).forecast);  // a string for a number
  EXPECT_FALSE(parseOpenMeteoDaily(daily("[7.5,-1,8.0]")).forecast);         // below 0
  EXPECT_FALSE(parseOpenMeteoDaily(daily("[7.5,30.5,8.0]")).forecast);       // above any real UV index
  EXPECT_FALSE(parseOpenMeteoDaily(daily("[7.5,8,8]", "[20,20,20]", "[1,2,3]")).forecast);
}

TEST(OpenMeteoParse, KeepsTheFirstThreeOfALongerForecast) {
  const auto r = parseOpenMeteoDaily(
      daily("[1,2,3,9]", "[1,2,3,4]", R"(["2026-12-05","2026-12-06","2026-12-07","2026-12-08"])"));
  ASSERT_TRUE(r.forecast) << r.error;
  EXPECT_EQ(r.forecast->dayCount, 3);
  EXPECT_DOUBLE_EQ(*r.forecast->days[2].uvIndexMax, 3.0);
}
