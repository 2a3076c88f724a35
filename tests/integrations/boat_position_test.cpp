// Where the forecast is asked for: the freshest boat position under a day,
// else the file's, else none; a move that asks again; Signal K's delta.
#include "integrations/boat_position.h"

#include <gtest/gtest.h>

#include <boost/json.hpp>
#include <cmath>

namespace xr::integrations {
namespace {

TEST(BoatPosition, FreshestBoatSourceWinsOverTheOtherAndTheFile) {
  const std::vector<PositionReport> boat{{"nmea2000", 43.1, 5.1, 30.0}, {"signalk", 43.2, 5.2, 5.0}};
  const auto p = choosePosition(boat, 50.0, 1.0);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->source, "signalk");
  EXPECT_DOUBLE_EQ(p->latitudeDeg, 43.2);
  const std::vector<PositionReport> older{{"nmea2000", 43.1, 5.1, 3.0}, {"signalk", 43.2, 5.2, 5.0}};
  EXPECT_EQ(choosePosition(older, 50.0, 1.0)->source, "nmea2000");
}

TEST(BoatPosition, ABoatPositionOlderThanADayGivesWayToTheFile) {
  const std::vector<PositionReport> atLimit{{"nmea2000", 43.1, 5.1, kBoatPositionMaxAgeS}};
  EXPECT_EQ(choosePosition(atLimit, 50.0, 1.0)->source, "nmea2000");
  const std::vector<PositionReport> over{{"nmea2000", 43.1, 5.1, kBoatPositionMaxAgeS + 1.0}};
  const auto p = choosePosition(over, 50.0, 1.0);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->source, "file");
  EXPECT_DOUBLE_EQ(p->latitudeDeg, 50.0);
}

TEST(BoatPosition, ZeroZeroNanAndOutOfRangeAreNotPositions) {
  EXPECT_FALSE(choosePosition({}, 0.0, 0.0));
  EXPECT_TRUE(choosePosition({}, 0.0, 0.5));  // on the Equator is a place
  const std::vector<PositionReport> bad{{"signalk", 0.0, 0.0, 1.0},
                                        {"nmea2000", std::nan(""), 5.0, 1.0},
                                        {"signalk", 91.0, 5.0, 1.0},
                                        {"nmea2000", 43.0, 5.0, -1.0}};  // from the future: a broken clock
  EXPECT_FALSE(choosePosition(bad, 0.0, 0.0));
  EXPECT_FALSE(usablePosition(0.0, 181.0));
  EXPECT_TRUE(usablePosition(-90.0, 180.0));
}

TEST(BoatPosition, AskAgainWhenAPositionAppearsOrTheBoatMovedPastTheCell) {
  const ChosenPosition here{43.0, 5.0, "file"};
  EXPECT_TRUE(needsNewForecast(std::nullopt, here));
  EXPECT_FALSE(needsNewForecast(std::nullopt, std::nullopt));
  EXPECT_FALSE(needsNewForecast(here, std::nullopt));
  EXPECT_FALSE(needsNewForecast(here, ChosenPosition{43.0 + 0.99 * kForecastMoveDeg, 5.0, "signalk"}));
  EXPECT_TRUE(needsNewForecast(here, ChosenPosition{43.0 + kForecastMoveDeg + 0.01, 5.0, "signalk"}));
  EXPECT_TRUE(needsNewForecast(here, ChosenPosition{43.0, 5.0 - kForecastMoveDeg - 0.01, "nmea2000"}));
}

TEST(BoatPosition, SignalKDeltaGivesTheLastUsablePosition) {
  const auto v = boost::json::parse(R"({"context":"vessels.urn:mrn:imo:mmsi:230099999","updates":[
    {"timestamp":"2026-12-05T03:00:00Z","values":[{"path":"navigation.speedOverGround","value":3.1},
      {"path":"navigation.position","value":{"latitude":60.15,"longitude":24.95}}]}]})");
  const auto p = positionFromSignalKDelta(v);
  ASSERT_TRUE(p);
  EXPECT_DOUBLE_EQ(p->latitudeDeg, 60.15);
  EXPECT_DOUBLE_EQ(p->longitudeDeg, 24.95);
  EXPECT_EQ(p->source, "signalk");
}

TEST(BoatPosition, SignalKDeltaWithoutAUsablePositionGivesNone) {
  for (
      const char* text :
      {R"({"updates":[{"values":[{"path":"navigation.position","value":{"latitude":"60","longitude":24}}]}]})",
       R"({"updates":[{"values":[{"path":"navigation.position","value":{"latitude":95,"longitude":24}}]}]})",
       R"({"updates":[{"values":[{"path":"navigation.position","value":null}]}]})",
       R"({"updates":[{"values":[{"path":"navigation.position"}]}]})", R"({"updates":{}})", R"([1,2])",
       R"({"statusCode":403})"})
    EXPECT_FALSE(positionFromSignalKDelta(boost::json::parse(text))) << text;
}

TEST(BoatPosition, SignalKPositionReportsItsAge) {
  SignalKPosition sk;
  const auto t0 = std::chrono::steady_clock::time_point{} + std::chrono::hours(5);
  EXPECT_FALSE(sk.report(t0));
  sk.post(60.1, 24.9, t0);
  const auto r = sk.report(t0 + std::chrono::seconds(90));
  ASSERT_TRUE(r);
  EXPECT_DOUBLE_EQ(r->ageS, 90.0);
  EXPECT_EQ(r->source, "signalk");
}

}  // namespace
}  // namespace xr::integrations
