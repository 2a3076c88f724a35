// API tests (docs/dashboard.md "API") against a real WebServer on an ephemeral loopback port
// with the fake DaemonApi: every endpoint, auth, atomic PATCH, every command,
// malformed and oversized inputs, WebSocket, many concurrent clients.
#include <gtest/gtest.h>

#include <atomic>
#include <boost/json.hpp>
#include <filesystem>
#include <fstream>
#include <thread>

#include "params/params.h"
#include "tests/web/fake_daemon_api.h"
#include "tests/web/http_client.h"
#include "web/server/json_status.h"
#include "web/server/web_server.h"

namespace xr::web::test {
namespace {
namespace json = boost::json;
namespace fs = std::filesystem;

constexpr const char* kToken = "s3cret-token-for-tests";

class WebApiTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("xr-web-test-" + std::to_string(::getpid()) + "-" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(root_ / "www" / "js");
    std::ofstream(root_ / "www" / "index.html") << "<!doctype html><title>xr</title>";
    std::ofstream(root_ / "www" / "js" / "app.js") << "console.log(1);";
    std::ofstream(root_ / "www" / "style.css") << "body{}";
    std::ofstream(root_ / "secret.txt") << "TOP SECRET";
    fs::create_symlink(root_ / "secret.txt", root_ / "www" / "link.txt");
  }
  void TearDown() override {
    server_.reset();
    std::error_code ec;
    fs::remove_all(root_, ec);
  }
  void start(WebServerOptions o = {}) {
    o.listen = "127.0.0.1";
    o.port = 0;
    o.token = kToken;
    o.www_root = (root_ / "www").string();
    o.telemetry_rate_hz = 20;
    server_ = std::make_unique<WebServer>(api_, o);
    server_->start();
    port_ = server_->port();
  }
  HttpResult get(const std::string& target, std::map<std::string, std::string> h = {}) {
    return httpRequest(port_, bhttp::verb::get, target, "", h);
  }
  HttpResult patch(const std::string& body, const std::string& token = kToken) {
    std::map<std::string, std::string> h;
    if (!token.empty()) h["Authorization"] = "Bearer " + token;
    return httpRequest(port_, bhttp::verb::patch, "/api/params", body, h);
  }
  HttpResult command(const std::string& body, const std::string& token = kToken) {
    std::map<std::string, std::string> h;
    if (!token.empty()) h["Authorization"] = "Bearer " + token;
    return httpRequest(port_, bhttp::verb::post, "/api/commands", body, h);
  }
  static json::object obj(const HttpResult& r) { return json::parse(r.body).as_object(); }

  FakeDaemonApi api_;
  std::unique_ptr<WebServer> server_;
  std::uint16_t port_ = 0;
  fs::path root_;
};

TEST_F(WebApiTest, Status_503BeforeFirstTick) {
  start();
  EXPECT_EQ(get("/api/status").status, 503);
}

TEST_F(WebApiTest, Status_HasEveryDesignCsvColumnWithFakeValues) {
  api_.publish();
  start();
  const auto r = get("/api/status");
  ASSERT_EQ(r.status, 200);
  EXPECT_EQ(r.headers["Content-Type"], "application/json");
  const auto o = obj(r);
  for (const char* col : {"t_s",
                          "mode",
                          "stage",
                          "reason",
                          "ibv_v",
                          "battery_v",
                          "bcur_a",
                          "alt_a",
                          "rpm",
                          "temp_f",
                          "duty_pct",
                          "field_enable",
                          "setpoint_a",
                          "target_a",
                          "target_v",
                          "thermal_penalty_a",
                          "fast_ov_active",
                          "soc_pct",
                          "alarm",
                          "charged_wh_lifetime",
                          "alt_charged_wh_lifetime",
                          "sim_battery_v",
                          "sim_alt_a",
                          "sim_alt_temp_f",
                          "sim_soc_pct",
                          "sim_bms_connected",
                          "sim_field_on"})
    EXPECT_TRUE(o.contains(col)) << col;
  StatusSnapshot s;
  ASSERT_TRUE(api_.latestStatus(s));
  EXPECT_NEAR(o.at("battery_v").to_number<double>(), s.telemetry.battery_v, 0.0005);  // rounded to 1 mV
  EXPECT_EQ(o.at("schema").as_int64(), kStatusSchema);
  EXPECT_EQ(o.at("mode").as_string(), "MODE_NORMAL_AUTO_PID");
  EXPECT_EQ(o.at("stage").as_string(), "BULK");
  EXPECT_EQ(o.at("reason").as_string(), "NONE");
  EXPECT_TRUE(o.at("field_enable").as_bool());  // a flag is a boolean for programs
  EXPECT_DOUBLE_EQ(o.at("t_s").to_number<double>(), 0.1);
  EXPECT_EQ(o.at("protection").at("last_trip_reason").as_string(), "REASON_TEMP_WARNING");
  EXPECT_DOUBLE_EQ(o.at("battery").at("charge_cycles").to_number<double>(), 12.3);
  EXPECT_EQ(o.at("loop").at("ticks").to_number<int>(), 40);
  EXPECT_DOUBLE_EQ(o.at("tuning").at("score").to_number<double>(), 0.8);
  EXPECT_EQ(o.at("control").at("sys_mode").as_string(), "SYS_MODE_AUTO");
  // Every field of the per-module structs is exported (the lists beside the
  // structs drive the JSON), including the detector states the Protections
  // page shows.
  std::size_t n = 0;
  visitProtectionTelemetry(s.telemetry.protection, [&](const char* name, const auto&) {
    EXPECT_TRUE(o.at("protection").as_object().contains(snakeName(name))) << name;
    ++n;
  });
  EXPECT_GE(n, 30u);
  visitControlTelemetry(s.telemetry.control, [&](const char* name, const auto&) {
    EXPECT_TRUE(o.at("control").as_object().contains(snakeName(name))) << name;
  });
  visitBatteryTelemetry(s.telemetry.battery, [&](const char* name, const auto&) {
    EXPECT_TRUE(o.at("battery").as_object().contains(snakeName(name))) << name;
  });
  EXPECT_EQ(o.at("protection").at("hard_overcurrent").as_bool(), s.telemetry.protection.hardOvercurrent);
}

// No number for a SoC the regulator does not know (docs/batteries.md "State
// of charge at first start"), and the source of one it shows.
TEST_F(WebApiTest, Status_SocIsNullWhileUnknownAndNamesItsSource) {
  api_.socSource = SocSource::Unknown;
  api_.publish();
  start();
  auto o = obj(get("/api/status"));
  EXPECT_TRUE(o.at("soc_pct").is_null());
  EXPECT_EQ(o.at("soc_source").as_string(), "unknown");
  api_.socSource = SocSource::OcvEstimate;
  api_.publish();
  o = obj(get("/api/status"));
  EXPECT_GT(o.at("soc_pct").to_number<double>(), 0.0);
  EXPECT_EQ(o.at("soc_source").as_string(), "ocv_estimate");
  api_.socSource = SocSource::Counted;
  api_.publish();
  EXPECT_EQ(obj(get("/api/status")).at("soc_source").as_string(), "counted");
}

// The owner model (docs/dashboard.md "Owner model"): one object, the same
// in /api/status and in the WebSocket frame, with every limit acting now.
TEST_F(WebApiTest, Status_OwnerListsTheC10CapInStatusAndInTheWebSocketFrame) {
  api_.caps.ratingA = 120.0;
  api_.caps.rpmTableA = api_.caps.rpmTableTopA = 100.0;
  api_.caps.commandA = 28.0;
  api_.caps.batteryTempA = 28.0;
  api_.caps.batteryTempCause = BatteryTempCap::NO_PROBE;
  api_.publish();
  start();
  const auto o = obj(get("/api/status"));
  const auto& owner = o.at("owner").as_object();
  EXPECT_NE(owner.at("state").as_string().find("limited by C/10 without a battery probe"), std::string::npos);
  const auto& first = owner.at("limits").as_array().at(0).as_object();
  EXPECT_EQ(first.at("id").as_string(), "battery_temp_required");
  EXPECT_EQ(first.at("what").as_string(), "C/10 without a battery probe");
  EXPECT_EQ(first.at("amps").to_number<double>(), 28.0);
  EXPECT_FALSE(first.at("why").as_string().empty());
  EXPECT_EQ(owner.at("hero").at("unit").as_string(), "A");
  EXPECT_EQ(o.at("caps").at("battery_temp_cause").as_string(), "NO_PROBE");
  WsClient ws(port_, std::string("/ws?token=") + kToken);
  const auto frame = json::parse(ws.read()).as_object();
  EXPECT_EQ(frame.at("owner").at("limits").as_array().at(0).at("id").as_string(), "battery_temp_required");
}

// One SoC: a talking BMS's, the same in owner.soc, soc_pct and soc_source;
// "Not set up" from the same state as /api/params.
TEST_F(WebApiTest, Status_OwnerSocIsTheBmsWhileItTalksAndNotSetUpLeadsTheLimits) {
  api_.bmsState = BmsState::OK;
  api_.bmsSocPct = 40.0;
  api_.setUp = false;
  api_.publish();
  start();
  const auto o = obj(get("/api/status"));
  EXPECT_EQ(o.at("owner").at("soc").at("pct").to_number<double>(), 40.0);
  EXPECT_EQ(o.at("owner").at("soc").at("source").as_string(), "bms");
  EXPECT_EQ(o.at("soc_pct").to_number<double>(), 40.0);
  EXPECT_EQ(o.at("soc_source").as_string(), "bms");
  EXPECT_EQ(o.at("owner").at("bms").at("state").as_string(), "talking");
  EXPECT_EQ(o.at("owner").at("limits").as_array().at(0).at("id").as_string(), "not_set_up");
  EXPECT_TRUE(o.at("owner").at("limits").as_array().at(0).at("amps").is_null());
}

TEST_F(WebApiTest, Status_FollowsNewTicks) {
  api_.publish();
  start();
  const auto a = obj(get("/api/status")).at("seq").to_number<int>();
  api_.publish();
  const auto b = obj(get("/api/status")).at("seq").to_number<int>();
  EXPECT_EQ(b, a + 1);
}

TEST_F(WebApiTest, Params_ListsEveryCatalogueEntryWithMetadata) {
  start();
  const auto r = get("/api/params");
  ASSERT_EQ(r.status, 200);
  const auto o = obj(r);
  const auto& list = o.at("params").as_array();
  ASSERT_EQ(list.size(), catalogue().size());
  for (const auto& p : list) {
    const auto& e = p.as_object();
    for (const char* k :
         {"name", "group", "kind", "unit", "min", "max", "help", "value", "default", "file", "changed"})
      EXPECT_TRUE(e.contains(k)) << k;
    EXPECT_FALSE(e.at("changed").as_bool()) << e.at("name");
  }
  EXPECT_FALSE(o.at("groups").as_array().empty());
}

// each parameter names its source; BatteryProfile is a named choice.
TEST_F(WebApiTest, Params_NameTheirSourceAndTheProfileItsChoices) {
  start();
  ASSERT_EQ(patch(R"({"BulkVoltage": 14.2})").status, 200);
  bool sawProfile = false;
  // Kept in a variable: a range-for over a member of obj()'s temporary would
  // read a destroyed value.
  const json::object params = obj(get("/api/params"));
  for (const auto& p : params.at("params").as_array()) {
    const auto& e = p.as_object();
    const std::string name(e.at("name").as_string());
    const std::string src(e.at("source").as_string());
    EXPECT_EQ(src, name == "BulkVoltage" ? "dashboard" : "default") << name;
    if (name == "BatteryProfile") {
      sawProfile = true;
      EXPECT_EQ(e.at("value_name").as_string(), "custom");
      EXPECT_EQ(e.at("choices").as_array().size(), 5u);
    }
  }
  EXPECT_TRUE(sawProfile);
  // By name: applied; an unknown name: 400, nothing applied.
  ASSERT_EQ(patch(R"({"BatteryProfile": "agm"})").status, 200);
  EXPECT_EQ(api_.currentParams().BatteryProfile, 1);
  const auto bad = patch(R"({"BatteryProfile": "lithium", "BulkVoltage": 14.3})");
  EXPECT_EQ(bad.status, 400);
  EXPECT_NE(std::string(obj(bad).at("errors").as_object().at("BatteryProfile").as_string()).find("one of"),
            std::string::npos);
  EXPECT_EQ(api_.currentParams().BatteryProfile, 1);
  EXPECT_DOUBLE_EQ(api_.currentParams().BulkVoltage, 14.2);
}

TEST_F(WebApiTest, Patch_AppliesValidChangesAndMarksThemChanged) {
  start();
  const auto r = patch(R"({"BulkVoltage": 14.2, "TuningMode": true, "PidSampleDivisor": 2})");
  ASSERT_EQ(r.status, 200) << r.body;
  const Params p = api_.currentParams();
  EXPECT_DOUBLE_EQ(p.BulkVoltage, 14.2);
  EXPECT_TRUE(p.TuningMode);
  EXPECT_EQ(p.PidSampleDivisor, 2);
  const auto list = obj(get("/api/params")).at("params").as_array();
  for (const auto& e : list)
    if (e.at("name").as_string() == "BulkVoltage") {
      EXPECT_TRUE(e.at("changed").as_bool());
      EXPECT_DOUBLE_EQ(e.at("value").to_number<double>(), 14.2);
    }
}

TEST_F(WebApiTest, Patch_TableTakesTenNumbers) {
  start();
  const ParamSpec* table = nullptr;
  for (const auto& s : catalogue())
    if (s.kind == ParamKind::Table) table = &s;
  ASSERT_NE(table, nullptr);
  json::array a;
  for (std::size_t i = 0; i < RPM_TABLE_SIZE; ++i) a.push_back(table->min);
  json::object body;
  body[table->name] = a;
  ASSERT_EQ(patch(json::serialize(body)).status, 200);
  EXPECT_DOUBLE_EQ(table->get(api_.currentParams(), 9), table->min);
  a.pop_back();
  body[table->name] = a;
  const auto r = patch(json::serialize(body));
  EXPECT_EQ(r.status, 400);
  EXPECT_TRUE(obj(r).at("errors").as_object().contains(table->name));
}

TEST_F(WebApiTest, Patch_401WithoutToken403WithWrongToken) {
  start();
  const auto none = patch(R"({"BulkVoltage": 14.2})", "");
  EXPECT_EQ(none.status, 401);
  EXPECT_EQ(none.headers["WWW-Authenticate"].substr(0, 6), "Bearer");
  EXPECT_EQ(patch(R"({"BulkVoltage": 14.2})", "wrong").status, 403);
  EXPECT_EQ(patch(R"({"BulkVoltage": 14.2})", std::string(kToken) + "x").status, 403);
  EXPECT_EQ(httpRequest(port_, bhttp::verb::patch, "/api/params", R"({"BulkVoltage": 14.2})",
                        {{"Authorization", std::string("Basic ") + kToken}})
                .status,
            403);
  EXPECT_EQ(api_.patchCalls(), 0);
  EXPECT_DOUBLE_EQ(api_.currentParams().BulkVoltage, Params{}.BulkVoltage);
}

// null is "drop the dashboard's value": the layer below applies again
// (docs/configuration.md "One chain of values").
TEST_F(WebApiTest, Patch_NullDropsTheDashboardValue) {
  start();
  ASSERT_EQ(patch(R"({"FloatVoltage": 13.1})").status, 200);
  EXPECT_DOUBLE_EQ(api_.currentParams().FloatVoltage, 13.1);
  const auto r = patch(R"({"FloatVoltage": null})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_DOUBLE_EQ(api_.currentParams().FloatVoltage, api_.fileParams().FloatVoltage);
}

// The server parses: an unknown name, a value of the wrong JSON type or a
// table of the wrong shape is refused here, naming each; values of the right
// type go to the daemon, which alone checks them (ranges included).
TEST_F(WebApiTest, Patch_OneUnparsableFieldAppliesNothingAndNamesEachBadField) {
  start();
  const auto r =
      patch(R"({"BulkVoltage": 14.2, "FloatVoltage": 999, "NoSuchParam": 1, "PidSampleDivisor": "two",
                          "TuningMode": "yes", "AbsorptionVoltage": []})");
  ASSERT_EQ(r.status, 400);
  const auto errors = obj(r).at("errors").as_object();
  EXPECT_EQ(errors.size(), 4u);
  EXPECT_EQ(errors.at("NoSuchParam").as_string(), "unknown parameter");
  EXPECT_EQ(errors.at("PidSampleDivisor").as_string(), "expected a number");
  EXPECT_TRUE(errors.contains("TuningMode"));
  EXPECT_TRUE(errors.contains("AbsorptionVoltage"));
  EXPECT_FALSE(errors.contains("FloatVoltage")) << "a range is the daemon's to check";
  EXPECT_FALSE(errors.contains("BulkVoltage"));
  EXPECT_EQ(api_.patchCalls(), 0);
  EXPECT_DOUBLE_EQ(api_.currentParams().BulkVoltage, Params{}.BulkVoltage);
}

TEST_F(WebApiTest, Patch_DaemonCrossFieldRejectionIsAllOrNone) {
  start();
  // Each value fits the catalogue, but together FloatVoltage > BulkVoltage.
  const auto r = patch(R"({"BulkVoltage": 13.0, "FloatVoltage": 13.4})");
  ASSERT_EQ(r.status, 400) << r.body;
  EXPECT_TRUE(obj(r).at("errors").as_object().contains("FloatVoltage"));
  EXPECT_DOUBLE_EQ(api_.currentParams().BulkVoltage, Params{}.BulkVoltage);
}

// ?dry_run=1: the daemon is asked with dryRun, its checked set comes back
// (values by name, the bank, the errors) and nothing is applied; ?bank= is
// passed on as the set-up's bank choice; a malformed query is refused.
TEST_F(WebApiTest, Patch_DryRunAnswersTheCheckedSetAndAppliesNothing) {
  start();
  auto dry = [&](const std::string& query, const std::string& body) {
    return httpRequest(port_, bhttp::verb::patch, "/api/params" + query, body,
                       {{"Authorization", std::string("Bearer ") + kToken}});
  };
  const auto r = dry("?dry_run=1&bank=24", R"({"FloatVoltage": 13.1})");
  ASSERT_EQ(r.status, 200) << r.body;
  const auto o = obj(r);
  EXPECT_TRUE(o.at("dry_run").as_bool());
  EXPECT_TRUE(o.at("ok").as_bool());
  EXPECT_DOUBLE_EQ(o.at("values").at("FloatVoltage").to_number<double>(), 13.1);
  EXPECT_EQ(o.at("bank_v").to_number<int>(), 12);
  EXPECT_TRUE(api_.lastPatchOptions().dryRun);
  EXPECT_EQ(api_.lastPatchOptions().bankV, 24);
  EXPECT_DOUBLE_EQ(api_.currentParams().FloatVoltage, Params{}.FloatVoltage) << "a dry run applied";
  // The daemon's refusal comes back as errors, still nothing applied.
  const auto bad = dry("?dry_run=1", R"({"BulkVoltage": 13.0, "FloatVoltage": 13.4})");
  ASSERT_EQ(bad.status, 200) << bad.body;
  EXPECT_FALSE(obj(bad).at("ok").as_bool());
  EXPECT_TRUE(obj(bad).at("errors").as_object().contains("FloatVoltage"));
  EXPECT_DOUBLE_EQ(api_.currentParams().BulkVoltage, Params{}.BulkVoltage);
  // A malformed query never reaches the daemon.
  const int calls = api_.patchCalls();
  EXPECT_EQ(dry("?dry_run=maybe", R"({"FloatVoltage": 13.1})").status, 400);
  EXPECT_EQ(dry("?bank=twelve", R"({"FloatVoltage": 13.1})").status, 400);
  EXPECT_EQ(api_.patchCalls(), calls);
  // Without dry_run the same body applies.
  ASSERT_EQ(dry("", R"({"FloatVoltage": 13.1})").status, 200);
  EXPECT_FALSE(api_.lastPatchOptions().dryRun);
  EXPECT_DOUBLE_EQ(api_.currentParams().FloatVoltage, 13.1);
}

TEST_F(WebApiTest, Patch_MalformedBodiesGet400WithMessage) {
  start();
  for (const char* body : {"", "{", "not json", "[1,2]", "42", "{}", "{\"BulkVoltage\": 14.2,}",
                           "{\"BulkVoltage\": [[[[[[[[[[[[[[[[[[[[[[1]]]]]]]]]]]]]]]]]]]]]}"}) {
    const auto r = patch(body);
    EXPECT_EQ(r.status, 400) << body;
    EXPECT_TRUE(obj(r).contains("error")) << body;
  }
  EXPECT_EQ(api_.patchCalls(), 0);
}

TEST_F(WebApiTest, Commands_EveryCommandReachesTheDaemon) {
  start();
  const std::vector<std::pair<std::string, CommandType>> cases = {
      {R"({"command":"auto"})", CommandType::Auto},
      {R"({"command":"manual","duty":30})", CommandType::Manual},
      {R"({"command":"off"})", CommandType::Off},
      {R"({"command":"limp_home"})", CommandType::LimpHome},
      {R"({"command":"limp_home_off"})", CommandType::LimpHomeOff},
      {R"({"command":"reenable_field"})", CommandType::ReenableField},
      {R"({"command":"reset_alarm_latch"})", CommandType::ResetAlarmLatch},
      {R"({"command":"reset_soc_gain"})", CommandType::ResetSocGain},
      {R"({"command":"reset_alt_zero"})", CommandType::ResetAltZero},
      {R"({"command":"set_soc","soc_pct":80.5})", CommandType::SetSoc},
      {R"({"command":"system_id_start"})", CommandType::SystemIdStart},
      {R"({"command":"tuning_commit"})", CommandType::TuningCommit},
      {R"({"command":"cv_tuning_commit"})", CommandType::CvTuningCommit},
      {R"({"command":"weather_mode","active":true})", CommandType::WeatherMode},
      {R"({"command":"acknowledge_alarm"})", CommandType::AcknowledgeAlarm},
  };
  for (const auto& [body, type] : cases) {
    const auto r = command(body);
    EXPECT_EQ(r.status, 200) << body << " " << r.body;
  }
  const auto got = api_.commands();
  ASSERT_EQ(got.size(), cases.size());
  for (std::size_t i = 0; i < cases.size(); ++i) EXPECT_EQ(got[i].type, cases[i].second) << cases[i].first;
  EXPECT_DOUBLE_EQ(got[1].value, 30.0);
  EXPECT_DOUBLE_EQ(got[9].value, 80.5);
  EXPECT_TRUE(got[13].flag);
  // The list endpoint names them all too.
  EXPECT_EQ(obj(get("/api/commands")).at("commands").as_array().size(), cases.size());
}

TEST_F(WebApiTest, Commands_BadRequestsGet400AndNeverReachTheDaemon) {
  start();
  for (const char* body :
       {R"({"command":"manual"})", R"({"command":"manual","duty":"30"})",
        R"({"command":"manual","duty":101})", R"({"command":"manual","duty":-1})",
        R"({"command":"set_soc","soc_pct":null})", R"({"command":"weather_mode","active":1})",
        R"({"command":"explode"})", R"({"command":42})", R"({"cmd":"auto"})",
        R"({"command":"auto","duty":10})", R"(["auto"])", "{"}) {
    const auto r = command(body);
    EXPECT_EQ(r.status, 400) << body;
    EXPECT_TRUE(obj(r).contains("error")) << body;
  }
  EXPECT_TRUE(api_.commands().empty());
  EXPECT_EQ(command(R"({"command":"auto"})", "").status, 401);
  EXPECT_EQ(command(R"({"command":"auto"})", "nope").status, 403);
  EXPECT_TRUE(api_.commands().empty());
}

TEST_F(WebApiTest, Commands_RefusedByDaemonIs409WithItsMessage) {
  start();
  api_.setRefuseCommands(true);
  const auto r = command(R"({"command":"tuning_commit"})");
  EXPECT_EQ(r.status, 409);
  EXPECT_EQ(obj(r).at("error").as_string(), "not legal now");
}

TEST_F(WebApiTest, Events_LimitAndBeforePage) {
  start();
  auto o = obj(get("/api/events?limit=5"));
  const auto& ev = o.at("events").as_array();
  ASSERT_EQ(ev.size(), 5u);
  EXPECT_EQ(ev[0].at("id").to_number<int>(), 250);
  EXPECT_EQ(ev[0].at("text").as_string(), "event 250");
  EXPECT_EQ(ev[0].at("code").as_string(), "ProtectionTrip");
  EXPECT_EQ(ev[1].at("code").as_string(), "StageChanged");
  const auto page = obj(get("/api/events?limit=3&before=100")).at("events").as_array();
  ASSERT_EQ(page.size(), 3u);
  EXPECT_EQ(page[0].at("id").to_number<int>(), 99);
  EXPECT_EQ(obj(get("/api/events")).at("events").as_array().size(), 100u);               // default limit
  EXPECT_EQ(obj(get("/api/events?limit=100000")).at("events").as_array().size(), 250u);  // clamped, all there
  EXPECT_EQ(get("/api/events?limit=0").status, 400);
  EXPECT_EQ(get("/api/events?limit=abc").status, 400);
  EXPECT_EQ(get("/api/events?before=1e3").status, 400);
}

TEST_F(WebApiTest, History_ReturnsSeriesAndValidatesQuery) {
  start();
  const auto r = get("/api/history?series=battery_v,alt_a&from=1000&to=2000&step=10");
  ASSERT_EQ(r.status, 200) << r.body;
  const auto o = obj(r);
  EXPECT_EQ(o.at("t").as_array().size(), 100u);
  EXPECT_EQ(o.at("series").at("battery_v").as_array().size(), 100u);
  EXPECT_EQ(o.at("series").at("alt_a").as_array().size(), 100u);
  const auto q = api_.lastHistory();
  EXPECT_DOUBLE_EQ(q.from_s, 1000);
  EXPECT_DOUBLE_EQ(q.step_s, 10);
  // Relative times: from=-600 means ten minutes before now.
  ASSERT_EQ(get("/api/history?series=battery_v&from=-600").status, 200);
  const auto rel = api_.lastHistory();
  EXPECT_NEAR(rel.to_s - rel.from_s, 600.0, 1e-6);
  EXPECT_EQ(get("/api/history").status, 400);
  EXPECT_EQ(get("/api/history?series=").status, 400);
  EXPECT_EQ(get("/api/history?series=battery_v,,alt_a").status, 400);
  EXPECT_EQ(get("/api/history?series=battery_v&from=x").status, 400);
  EXPECT_EQ(get("/api/history?series=battery_v&from=2000&to=1000").status, 400);
  EXPECT_EQ(get("/api/history?series=battery_v&from=0.5&to=1e9&step=1").status, 400);  // too many points
  EXPECT_EQ(get("/api/history?series=battery_v&step=0").status, 400);
  const auto unknown = get("/api/history?series=nonsense");
  EXPECT_EQ(unknown.status, 400);
  EXPECT_EQ(obj(unknown).at("error").as_string(), "unknown series 'nonsense'");
}

TEST_F(WebApiTest, System_VersionsProbesLoop) {
  api_.publish();
  start();
  const auto o = obj(get("/api/system"));
  EXPECT_EQ(o.at("versions").at("xregulatord").as_string(), "test");
  EXPECT_EQ(o.at("probes").as_array().size(), 2u);
  EXPECT_FALSE(o.at("probes").as_array()[1].at("ok").as_bool());
  EXPECT_DOUBLE_EQ(o.at("loop").at("period_p99_us").to_number<double>(), 2510);
}

TEST_F(WebApiTest, System_CanBusesOffByDefaultWithNullsNotZeros) {
  api_.publish();
  start();
  auto o = obj(get("/api/system"));
  const auto& bms = o.at("bms").as_object();
  EXPECT_EQ(bms.at("state").as_string(), "off");
  EXPECT_TRUE(bms.at("protocol").is_null());
  EXPECT_TRUE(bms.at("cvl_v").is_null());
  EXPECT_TRUE(bms.at("age_s").is_null());
  EXPECT_EQ(o.at("n2k").at("state").as_string(), "off");
  EXPECT_TRUE(o.at("n2k").at("address").is_null());
  EXPECT_FALSE(o.at("n2k").at("claimed").as_bool());
  CanState c;
  c.bms.protocol = "rec";
  c.bms.state = "talking";
  c.bms.cvl_v = 14.2;
  c.bms.ccl_a = 55.5;  // soc_pct stays unknown
  c.bms.age_s = 0.25;
  c.bms.bad_frames = 7;
  c.n2k.state = "claimed";
  c.n2k.claimed = true;
  c.n2k.address = 35;
  c.n2k.tx_frames = 120;
  api_.setCan(c);
  o = obj(get("/api/system"));
  EXPECT_EQ(o.at("bms").at("protocol").as_string(), "rec");
  EXPECT_EQ(o.at("bms").at("state").as_string(), "talking");
  EXPECT_DOUBLE_EQ(o.at("bms").at("cvl_v").to_number<double>(), 14.2);
  EXPECT_DOUBLE_EQ(o.at("bms").at("ccl_a").to_number<double>(), 55.5);
  EXPECT_TRUE(o.at("bms").at("soc_pct").is_null());
  EXPECT_DOUBLE_EQ(o.at("bms").at("age_s").to_number<double>(), 0.25);
  EXPECT_EQ(o.at("bms").at("bad_frames").to_number<std::uint64_t>(), 7u);
  EXPECT_EQ(o.at("n2k").at("address").to_number<int>(), 35);
  EXPECT_EQ(o.at("n2k").at("tx_frames").to_number<std::uint64_t>(), 120u);
}

TEST_F(WebApiTest, Metrics_PrometheusText) {
  api_.publish();
  start();
  (void)get("/api/status");
  const auto r = get("/metrics");
  ASSERT_EQ(r.status, 200);
  EXPECT_NE(r.headers["Content-Type"].find("text/plain; version=0.0.4"), std::string::npos);
  EXPECT_NE(r.body.find("# TYPE xregulator_battery_v gauge\nxregulator_battery_v 13."), std::string::npos);
  EXPECT_NE(r.body.find("xregulator_mode_info{value=\"MODE_NORMAL_AUTO_PID\"} 1"), std::string::npos);
  EXPECT_NE(r.body.find("xregulator_loop_overruns_total 5"), std::string::npos);
  EXPECT_NE(r.body.find("xregulator_http_requests_total "), std::string::npos);
  // Every non-comment line is "name[{labels}] value".
  std::istringstream in(r.body);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    EXPECT_EQ(std::count(line.begin(), line.end(), ' '), 1) << line;
  }
}

TEST_F(WebApiTest, Healthz_OkAnd503) {
  start();
  EXPECT_EQ(get("/healthz").status, 200);
  api_.setHealthy(false);
  const auto r = get("/healthz");
  EXPECT_EQ(r.status, 503);
  EXPECT_EQ(obj(r).at("detail").as_string(), "no tick for 5 s");
}

TEST_F(WebApiTest, Static_ServesFilesWithMimeTypesAndNoTraversal) {
  start();
  const auto index = get("/");
  EXPECT_EQ(index.status, 200);
  EXPECT_EQ(index.headers["Content-Type"], "text/html; charset=utf-8");
  EXPECT_NE(index.body.find("<title>xr</title>"), std::string::npos);
  EXPECT_EQ(get("/js/app.js").headers["Content-Type"], "text/javascript; charset=utf-8");
  EXPECT_EQ(get("/style.css").headers["Content-Type"], "text/css; charset=utf-8");
  for (const char* bad : {"/../secret.txt", "/js/../../secret.txt", "/%2e%2e/secret.txt", "/link.txt",
                          "/missing.html", "//etc/passwd", "/js/./app.js", "/..\\secret.txt"}) {
    const auto r = get(bad);
    EXPECT_EQ(r.status, 404) << bad;
    EXPECT_EQ(r.body.find("TOP SECRET"), std::string::npos) << bad;
  }
  // vendor/ (uPlot from npm) falls back to the assembled build/install assets.
  const auto uplot = get("/vendor/uPlot.iife.min.js");
  EXPECT_EQ(uplot.status, 200);
  EXPECT_NE(uplot.body.find("uPlot"), std::string::npos);
  EXPECT_EQ(get("/vendor/../../secret.txt").status, 404);
  const auto head = httpRequest(port_, bhttp::verb::head, "/js/app.js");
  EXPECT_EQ(head.status, 200);
  EXPECT_EQ(head.headers["Content-Length"], "15");
}

TEST_F(WebApiTest, Routing_UnknownAndWrongMethods) {
  start();
  EXPECT_EQ(get("/api/nothing").status, 404);
  EXPECT_EQ(
      httpRequest(port_, bhttp::verb::delete_, "/api/params", "", {{"Authorization", "Bearer x"}}).status,
      405);
  EXPECT_EQ(httpRequest(port_, bhttp::verb::post, "/api/status", "{}").status, 405);
  EXPECT_EQ(httpRequest(port_, bhttp::verb::put, "/index.html", "x").status, 405);
  EXPECT_EQ(get("/ws").status, 426);
}

TEST_F(WebApiTest, ReadsCanRequireTheToken) {
  api_.publish();
  WebServerOptions o;
  o.reads_require_token = true;
  start(o);
  EXPECT_EQ(get("/api/status").status, 401);
  EXPECT_EQ(get("/api/status", {{"Authorization", "Bearer wrong"}}).status, 403);
  EXPECT_EQ(get("/api/status", {{"Authorization", std::string("Bearer ") + kToken}}).status, 200);
  EXPECT_EQ(get("/metrics").status, 401);
  EXPECT_EQ(get("/healthz").status, 200);  // health stays open for supervisors
  EXPECT_EQ(get("/").status, 200);         // the dashboard must load to ask for the token
  EXPECT_EQ(wsUpgradeStatus(port_, "/ws", ""), 401);
  EXPECT_EQ(wsUpgradeStatus(port_, "/ws?token=bad", ""), 403);
  WsClient ws(port_, std::string("/ws?token=") + kToken);
  EXPECT_NE(ws.read().find("\"battery_v\""), std::string::npos);
}

// HEAD on an API route sends headers only, so a
// pipelined request behind it is read as a request, not as body bytes.
TEST_F(WebApiTest, Head_OnApiRoutesSendsNoBodyAndPipeliningWorks) {
  start();
  const std::string out =
      rawExchange(port_,
                  "HEAD /api/params HTTP/1.1\r\nHost: localhost\r\n\r\n"
                  "GET /api/nothing-here HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n");
  const auto first = out.find("HTTP/1.1 200");
  const auto second = out.find("HTTP/1.1 404");
  ASSERT_NE(first, std::string::npos) << out;
  ASSERT_NE(second, std::string::npos) << out;
  const auto headersEnd = out.find("\r\n\r\n", first);
  EXPECT_EQ(headersEnd + 4, second) << "bytes between the HEAD answer's headers and the next answer: " << out;
  EXPECT_NE(out.substr(first, headersEnd - first).find("Content-Length: "), std::string::npos);
}

TEST_F(WebApiTest, Limits_OversizedBodyAndHeadersAndGarbage) {
  WebServerOptions o;
  o.body_limit = 1024;
  o.header_limit = 1024;
  start(o);
  const std::string big = "{\"BulkVoltage\": 14.2, \"pad\": \"" + std::string(4096, 'x') + "\"}";
  EXPECT_EQ(patch(big).status, 413);
  EXPECT_EQ(get("/api/params", {{"X-Big", std::string(4096, 'y')}}).status, 431);
  const auto garbage = rawExchange(port_, "GARBAGE\x01\x02 / HTTP/9\r\n\r\n");
  EXPECT_EQ(garbage.substr(0, 12), "HTTP/1.1 400");
  EXPECT_EQ(api_.patchCalls(), 0);
  // The server still works afterwards.
  EXPECT_EQ(get("/healthz").status, 200);
}

TEST_F(WebApiTest, AnEmptyOrMissingHostHeaderIsAnsweredBadRequest) {
  start();
  EXPECT_EQ(rawExchange(port_, "GET /api/status HTTP/1.1\r\nHost: \r\n\r\n").substr(0, 12), "HTTP/1.1 400");
  EXPECT_EQ(rawExchange(port_, "GET /api/status HTTP/1.1\r\nConnection: close\r\n\r\n").substr(0, 12),
            "HTTP/1.1 400");
  EXPECT_EQ(rawExchange(port_, "GET /healthz HTTP/1.1\r\nHost: a\r\nHost: b\r\n\r\n").substr(0, 12),
            "HTTP/1.1 400");
  // An HTTP/1.0 tool without Host, and a proper request, are served.
  EXPECT_EQ(rawExchange(port_, "GET /healthz HTTP/1.0\r\n\r\n").substr(0, 12), "HTTP/1.0 200");
  EXPECT_EQ(rawExchange(port_, "GET /healthz HTTP/1.1\r\nHost: localhost\r\nConnection: close\r\n\r\n")
                .substr(0, 12),
            "HTTP/1.1 200");
}

TEST_F(WebApiTest, WebSocket_StreamsSharedFramesWithIncreasingSeq) {
  api_.publish();
  start();
  WsClient a(port_), b(port_);
  const auto first = json::parse(a.read()).as_object();
  EXPECT_TRUE(first.contains("battery_v"));
  json::parse(b.read());
  api_.publish();
  api_.publish();
  const auto seq0 = first.at("seq").to_number<std::uint64_t>();
  std::uint64_t seq = seq0;
  while (seq < seq0 + 2) {
    const auto next = json::parse(a.read()).as_object().at("seq").to_number<std::uint64_t>();
    EXPECT_GT(next, seq);
    seq = next;
  }
  EXPECT_EQ(server_->stats().ws_clients, 2u);
}

TEST_F(WebApiTest, WebSocket_SlowClientKeepsOnlyTheNewestFrame) {
  api_.publish();
  start();
  // A client with a tiny receive buffer that upgrades and then never reads.
  asio::io_context ioc;
  websocket::stream<tcp::socket> slow(ioc);
  slow.next_layer().open(tcp::v4());
  slow.next_layer().set_option(asio::socket_base::receive_buffer_size(4096));
  slow.next_layer().connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port_));
  slow.handshake("127.0.0.1:" + std::to_string(port_), "/ws");
  // Publish until the server has had to replace a pending frame (bounded loop;
  // the frames come at 20 Hz, so this is a few seconds).
  for (int i = 0; i < 2000 && server_->stats().ws_frames_dropped == 0; ++i) {
    api_.publish();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_GT(server_->stats().ws_frames_dropped, 0u);
  // Other clients and the API are unaffected.
  WsClient fast(port_);
  EXPECT_NE(fast.read().find("battery_v"), std::string::npos);
  EXPECT_EQ(get("/healthz").status, 200);
}

TEST_F(WebApiTest, WebSocket_OriginMustMatchHost) {
  api_.publish();
  start();
  EXPECT_EQ(wsUpgradeStatus(port_, "/ws", "http://evil.example"), 403);
  EXPECT_EQ(wsUpgradeStatus(port_, "/ws", "null"), 403);
  WsClient same(port_, "/ws", "http://127.0.0.1:" + std::to_string(port_));
  EXPECT_NE(same.read().find("battery_v"), std::string::npos);
  EXPECT_EQ(wsUpgradeStatus(port_, "/other", ""), 404);
}

TEST_F(WebApiTest, ConnectionCapRefusesExtraConnections) {
  WebServerOptions o;
  o.max_connections = 3;
  start(o);
  asio::io_context ioc;
  std::vector<tcp::socket> idle;
  for (int i = 0; i < 3; ++i) {
    idle.emplace_back(ioc);
    idle.back().connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port_));
  }
  const auto r = rawExchange(port_, "GET /healthz HTTP/1.1\r\nHost: localhost\r\n\r\n");
  EXPECT_EQ(r.substr(0, 12), "HTTP/1.1 503");
  EXPECT_GE(server_->stats().connections_refused, 1u);
  idle.clear();
}

TEST_F(WebApiTest, ManyConcurrentClients) {
  api_.publish();
  start();
  constexpr int kHttpThreads = 16, kRequests = 25, kWsClients = 16;
  std::atomic<int> ok{0}, wsOk{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kHttpThreads; ++t)
    threads.emplace_back([&, t] {
      for (int i = 0; i < kRequests; ++i) {
        const auto r = httpRequest(port_, bhttp::verb::get, (i + t) % 2 ? "/api/status" : "/api/params");
        if (r.status == 200) ++ok;
      }
    });
  for (int c = 0; c < kWsClients; ++c)
    threads.emplace_back([&] {
      WsClient ws(port_);
      if (json::parse(ws.read()).as_object().contains("soc_pct")) ++wsOk;
      ws.close();
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(ok.load(), kHttpThreads * kRequests);
  EXPECT_EQ(wsOk.load(), kWsClients);
}

TEST_F(WebApiTest, StartFailsCleanlyOnBadAddressOrNoToken) {
  WebServerOptions o;
  o.listen = "not-an-address";
  o.token = kToken;
  WebServer bad(api_, o);
  EXPECT_THROW(bad.start(), std::runtime_error);
  WebServerOptions n;
  n.port = 0;
  WebServer noToken(api_, n);
  EXPECT_THROW(noToken.start(), std::runtime_error);
}

}  // namespace
}  // namespace xr::web::test
