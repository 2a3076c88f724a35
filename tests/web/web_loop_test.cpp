// The control loop's overrun attribution in /api/system and /metrics
// ("0 overruns attributable to the daemon"): the daemon's own
// overruns and the tick CPU time are there, as numbers, beside the total.
#include <gtest/gtest.h>

#include <boost/json.hpp>
#include <sstream>

#include "tests/web/fake_daemon_api.h"
#include "tests/web/http_client.h"
#include "web/server/web_server.h"

namespace xr::web::test {
namespace {

class LoopFieldsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    api_.publish();
    WebServerOptions o;
    o.listen = "127.0.0.1";
    o.port = 0;
    o.token = "loop-test-token-0123456789";
    server_ = std::make_unique<WebServer>(api_, o);
    server_->start();
  }
  HttpResult get(const std::string& target) { return httpRequest(server_->port(), bhttp::verb::get, target); }
  FakeDaemonApi api_;
  std::unique_ptr<WebServer> server_;
};

TEST_F(LoopFieldsTest, SystemCarriesOwnOverrunsAndTickCpuAsNumbers) {
  const auto r = get("/api/system");
  ASSERT_EQ(r.status, 200);
  const auto loop = boost::json::parse(r.body).as_object().at("loop").as_object();
  ASSERT_TRUE(loop.contains("overruns_own"));
  EXPECT_TRUE(loop.at("overruns_own").is_number());
  EXPECT_EQ(loop.at("overruns_own").to_number<std::uint64_t>(), 2u);
  EXPECT_EQ(loop.at("overruns").to_number<std::uint64_t>(), 5u);
  ASSERT_TRUE(loop.contains("tick_cpu_max_us"));
  EXPECT_TRUE(loop.at("tick_cpu_max_us").is_number());
  EXPECT_DOUBLE_EQ(loop.at("tick_cpu_max_us").to_number<double>(), 310.0);
  EXPECT_DOUBLE_EQ(loop.at("tick_cpu_p99_us").to_number<double>(), 41.5);
}

// A metric's value on its own line, or NaN when the metric is absent.
double metric(const std::string& body, const std::string& name) {
  std::istringstream in(body);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind(name + " ", 0) == 0) return std::stod(line.substr(name.size() + 1));
  return std::nan("");
}

TEST_F(LoopFieldsTest, MetricsCarryOwnOverrunsAndTickCpu) {
  (void)get("/api/status");
  const auto r = get("/metrics");
  ASSERT_EQ(r.status, 200);
  EXPECT_DOUBLE_EQ(metric(r.body, "xregulator_loop_overruns_own_total"), 2.0);
  EXPECT_DOUBLE_EQ(metric(r.body, "xregulator_loop_overruns_total"), 5.0);
  EXPECT_DOUBLE_EQ(metric(r.body, "xregulator_loop_tick_cpu_max_us"), 310.0);
  EXPECT_NE(r.body.find("# TYPE xregulator_loop_overruns_own_total counter"), std::string::npos);
}

}  // namespace
}  // namespace xr::web::test
