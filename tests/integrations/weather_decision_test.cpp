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

namespace {
// 2026-12-06 12:00 UTC.
constexpr std::int64_t kNoonDec6 = 1796558400;

Forecast parsed(const std::string& time, double lat = 43.3, double lon = 5.4) {
  std::string body = daily("[8,8,8]", "[20.1,18.2,19.5]", time);
  const auto at = body.find("\"timezone\"");
  body = R"({"latitude":)" + std::to_string(lat) + R"(,"longitude":)" + std::to_string(lon) + "," +
         body.substr(at);
  auto p = parseOpenMeteoDaily(body);
  EXPECT_TRUE(p.forecast) << p.error;
  return p.forecast.value_or(Forecast{});
}
}  // namespace

TEST(ForecastMismatch, TodaysForecastForThePlaceAskedIsTaken) {
  EXPECT_EQ(forecastMismatch(parsed(R"(["2026-12-06","2026-12-07","2026-12-08"])"), 43.3, 5.4, kNoonDec6),
            "");
  // The place's own date may be the UTC date +-1 (time zones), and the
  // server's grid point a few km off.
  EXPECT_EQ(forecastMismatch(parsed(R"(["2026-12-05","2026-12-06","2026-12-07"])"), 43.3, 5.4, kNoonDec6),
            "");
  EXPECT_EQ(forecastMismatch(parsed(R"(["2026-12-07","2026-12-08","2026-12-09"])"), 43.3, 5.4, kNoonDec6),
            "");
  EXPECT_EQ(forecastMismatch(parsed(R"(["2026-12-06","2026-12-07","2026-12-08"])", 43.5, 5.6), 43.3, 5.4,
                             kNoonDec6),
            "");
}

TEST(ForecastMismatch, AForecastForOtherDatesIsRefused) {
  for (const char* t :
       {R"(["1999-07-05","1999-07-06","1999-07-07"])", R"(["2099-07-05","2099-07-06","2099-07-07"])",
        R"(["2026-12-04","2026-12-05","2026-12-06"])", R"(["2026-12-08","2026-12-09","2026-12-10"])"})
    EXPECT_NE(forecastMismatch(parsed(t), 43.3, 5.4, kNoonDec6).find("not for today"), std::string::npos)
        << t;
  EXPECT_NE(forecastMismatch(parsed(R"(["2026-12-06","2026-12-09","2026-12-10"])"), 43.3, 5.4, kNoonDec6)
                .find("not consecutive"),
            std::string::npos);
  EXPECT_NE(forecastMismatch(parsed(R"(["2026-13-06","2026-12-07","2026-12-08"])"), 43.3, 5.4, kNoonDec6)
                .find("not a date"),
            std::string::npos);
}

TEST(ForecastMismatch, AForecastForAnotherPlaceIsRefused) {
  const std::string today = R"(["2026-12-06","2026-12-07","2026-12-08"])";
  EXPECT_NE(forecastMismatch(parsed(today, 53.3, 5.4), 43.3, 5.4, kNoonDec6).find("another place"),
            std::string::npos);
  EXPECT_NE(forecastMismatch(parsed(today, 43.3, 5.95), 43.3, 5.4, kNoonDec6).find("another place"),
            std::string::npos);  // just beyond the 0.5 degree tolerance
  EXPECT_EQ(forecastMismatch(parsed(today, 43.3, 5.85), 43.3, 5.4, kNoonDec6), "");  // just inside
  // Across the date line: 179.9 and -179.9 are 0.2 degrees apart.
  EXPECT_EQ(forecastMismatch(parsed(today, -17.0, -179.9), -17.0, 179.9, kNoonDec6), "");
  // An answer that does not say where it is for.
  auto p = parseOpenMeteoDaily(daily("[8,8,8]", "[20.1,18.2,19.5]", today));
  ASSERT_TRUE(p.forecast);
  p.forecast->latitude.reset();
  EXPECT_NE(forecastMismatch(*p.forecast, 43.3, 5.4, kNoonDec6).find("does not say"), std::string::npos);
}
