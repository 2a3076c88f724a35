// The integrations in /api/system and /metrics (docs/integrations.md): the JSON entry
// and the Prometheus lines of web/server/json_format.
#include <gtest/gtest.h>

#include <cmath>

#include "web/server/json_format.h"

namespace xr::web {
namespace {

IntegrationState mqtt() {
  IntegrationState i;
  i.name = "mqtt";
  i.enabled = true;
  i.connected = true;
  i.messages_sent = 42;
  i.values_refused = 3;
  i.outages = 1;
  return i;
}

TEST(IntegrationWeb, SystemEntryHasStateErrorAndCounts) {
  auto i = mqtt();
  i.last_error = "127.0.0.1:1883: connection refused";
  i.values = {{"bms_ccl_a", 50.0}, {"bms_cvl_v", std::nan("")}};
  auto o = integrationToJson(i);
  EXPECT_EQ(o.at("name").as_string(), "mqtt");
  EXPECT_TRUE(o.at("connected").as_bool());
  EXPECT_EQ(o.at("last_error").as_string(), "127.0.0.1:1883: connection refused");
  EXPECT_EQ(o.at("messages_sent").as_uint64(), 42u);
  EXPECT_EQ(o.at("values_refused").as_uint64(), 3u);
  // Rounded as /api/status: a whole value is written as an integer (50).
  EXPECT_DOUBLE_EQ(o.at("values").as_object().at("bms_ccl_a").to_number<double>(), 50.0);
  EXPECT_TRUE(o.at("values").as_object().at("bms_cvl_v").is_null());  // NaN is no value
}

TEST(IntegrationWeb, MetricsOnlyForEnabledIntegrations) {
  IntegrationState off;
  off.name = "signalk";
  const std::string text = integrationMetrics({mqtt(), off});
  EXPECT_NE(text.find("xregulator_integration_connected{integration=\"mqtt\"} 1\n"), std::string::npos)
      << text;
  EXPECT_NE(text.find("xregulator_integration_messages_sent_total{integration=\"mqtt\"} 42\n"),
            std::string::npos);
  EXPECT_NE(text.find("xregulator_integration_values_refused_total{integration=\"mqtt\"} 3\n"),
            std::string::npos);
  EXPECT_NE(text.find("# TYPE xregulator_integration_outages_total counter"), std::string::npos);
  EXPECT_EQ(text.find("signalk"), std::string::npos);
  EXPECT_EQ(integrationMetrics({off}), "");
}

}  // namespace
}  // namespace xr::web
