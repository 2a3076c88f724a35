// /api/history/trends, /api/history/export and /api/history/charges?day=
// (docs/dashboard.md "Trends", "History"): the rows as columns and as CSV,
// and every bad bound answered 400 with a reason, before the store is asked.
#include <gtest/gtest.h>

#include <boost/json.hpp>
#include <string>

#include "tests/web/fake_daemon_api.h"
#include "tests/web/http_client.h"
#include "web/server/web_server.h"

namespace xr::web::test {
namespace {

namespace json = boost::json;
constexpr const char* kToken = "trends-test-token";

class TrendsRoutes : public ::testing::Test {
 protected:
  void SetUp() override {
    WebServerOptions o;
    o.listen = "127.0.0.1";
    o.port = 0;
    o.token = kToken;
    server_ = std::make_unique<WebServer>(api_, o);
    server_->start();
  }
  HttpResult get(const std::string& target) {
    return httpRequest(server_->port(), bhttp::verb::get, target, "",
                       {{"Authorization", std::string("Bearer ") + kToken}});
  }
  FakeDaemonApi api_;
  std::unique_ptr<WebServer> server_;
};

TEST_F(TrendsRoutes, TrendsComeAsColumnsOfMinMeanMaxWithUnits) {
  const auto r = get("/api/history/trends?from=1780000000&to=1780604800&step=hour");
  ASSERT_EQ(r.status, 200) << r.body;
  const auto o = json::parse(r.body).as_object();
  EXPECT_EQ(o.at("step"), "hour");
  EXPECT_EQ(o.at("t").as_array().size(), 2u);
  const auto& v = o.at("series").at("battery_v");
  EXPECT_EQ(v.at("unit"), "V");
  EXPECT_EQ(v.at("mean").at(0), json::value(13.123));  // volts: 3 decimals
  EXPECT_TRUE(o.at("series").at("battery_temp_c").at("mean").at(0).is_null());
  EXPECT_EQ(api_.lastTrends().fromS, 1780000000);
  EXPECT_FALSE(api_.lastTrends().daily);
}

TEST_F(TrendsRoutes, AYearWithoutAStepIsAskedOfTheDailyRows) {
  ASSERT_EQ(get("/api/history/trends?from=-31536000").status, 200);
  EXPECT_TRUE(api_.lastTrends().daily);
  ASSERT_EQ(get("/api/history/trends?from=-604800").status, 200);
  EXPECT_FALSE(api_.lastTrends().daily);
}

TEST_F(TrendsRoutes, ExportIsCsvWithAHeaderAndEmptyCellsForUnknown) {
  const auto r = get("/api/history/export?from=1780000000&to=1780086400");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.headers["Content-Type"], "text/csv; charset=utf-8");
  EXPECT_NE(
      r.headers["Content-Disposition"].find("attachment; filename=\"xregulator-2026-05-28-hourly.csv\""),
      std::string::npos)
      << r.headers["Content-Disposition"];
  const auto firstLine = r.body.substr(0, r.body.find("\r\n"));
  EXPECT_EQ(firstLine.rfind("time_utc,time_unix_s,samples,battery_v_min,battery_v_mean,battery_v_max,", 0),
            0u);
  EXPECT_NE(r.body.find("\r\n2026-05-28T20:26:40Z,1780000000,3600,12.457,13.123,14.4,-20,5.56,80,"),
            std::string::npos)
      << r.body;
  EXPECT_NE(r.body.find(",,,"), std::string::npos);  // the battery temperature: not known, empty
}

TEST_F(TrendsRoutes, BadBoundsAreRefusedWithAReason) {
  for (const std::string q :
       {"from=abc", "to=1e99", "from=1780000000&to=1770000000", "from=1780000000&to=1780000000", "step=week",
        "from=5000000000", "from=1000000000&to=1780000000&step=hour", "from=nan"}) {
    const auto r = get("/api/history/export?" + q);
    EXPECT_EQ(r.status, 400) << q;
    EXPECT_NE(r.body.find("\"error\""), std::string::npos) << q;
    EXPECT_EQ(get("/api/history/trends?" + q).status, 400) << q;
  }
  EXPECT_EQ(get("/api/history/export?from=1000000000&to=1780000000&step=day").status, 200);
}

TEST_F(TrendsRoutes, ChargesOfADayAndADayThatDoesNotExist) {
  const auto r = get("/api/history/charges?day=2026-07-01");
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(json::parse(r.body).at("charges").as_array().size(), 1u);
  EXPECT_EQ(get("/api/history/charges?day=2026-02-30").status, 400);
}

}  // namespace
}  // namespace xr::web::test
