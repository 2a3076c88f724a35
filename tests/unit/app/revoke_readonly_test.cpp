// A revocation is a write (docs/security.md "Round 3"): with a state
// database this run cannot write, DELETE /api/pair/devices[/<id>] answers
// 503 like PATCH and pairing, and the device list stays what the database
// holds, so the next start cannot give a "revoked" phone its access back.
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <boost/json.hpp>
#include <memory>
#include <string>
#include <vector>

#include "app/store_auth.h"
#include "app/store_service.h"
#include "store/sqlite_db.h"
#include "store_test_util.h"
#include "tests/web/http_client.h"
#include "web/server/pairing.h"
#include "web/server/web_server.h"
#include "web_api_rig.h"

namespace xr::app {
namespace {

using xr::test::TempDir;
namespace wt = xr::web::test;
constexpr const char* kToken = "revoke-test-installer-token-0123";

// Two phones paired and saved; then the file is one this release must not
// write (a newer schema: read into memory, nothing saved), the same state as
// a database owned by another user, whatever user the test runs as.
std::vector<std::string> pairTwoThenMakeUnwritable(const std::string& db) {
  std::vector<std::string> ids;
  {
    StoreService store(db, 300);
    web::Pairing pairing(std::make_shared<StoreAuthStore>(store));
    for (const char* name : {"owner phone", "guest phone"}) {
      const auto r = pairing.pair(pairing.newCode().code, name);
      EXPECT_EQ(r.kind, web::Pairing::Outcome::Paired);
      ids.push_back(r.device.id);
    }
    store.stop(BatteryLedger{}, false);
  }
  sql::Db raw;
  EXPECT_EQ(raw.open(db), SQLITE_OK);
  EXPECT_EQ(raw.exec("PRAGMA user_version = 99"), SQLITE_OK);
  return ids;
}

TEST(RevokeReadOnly, TheStoreRefusesToForgetADeviceItCannotKeepForgotten) {
  TempDir d;
  const std::string db = d.file("x.db");
  const auto ids = pairTwoThenMakeUnwritable(db);
  StoreService store(db, 300);
  ASSERT_FALSE(store.status().persistent);
  StoreAuthStore auth(store);
  ASSERT_EQ(auth.loadDevices().size(), 2u);
  EXPECT_FALSE(auth.removeDevice(ids[1]));  // before: true, in memory only
  EXPECT_EQ(auth.loadDevices().size(), 2u);
  store.stop(BatteryLedger{}, false);
}

TEST(RevokeReadOnly, DeleteAnswers503AndTheDevicesKeepTheirAccessAcrossARestart) {
  TempDir d;
  const std::string db = d.file("x.db");
  const auto ids = pairTwoThenMakeUnwritable(db);
  const std::map<std::string, std::string> installer{{"Authorization", std::string("Bearer ") + kToken}};
  for (int run = 0; run < 2; ++run) {  // this start, and the next
    test::WebApiRig rig(db);
    ASSERT_FALSE(rig.store->status().persistent);
    web::WebServerOptions o;
    o.listen = "127.0.0.1";
    o.port = 0;
    o.token = kToken;
    o.auth_store = std::make_shared<StoreAuthStore>(*rig.store);
    web::WebServer server(*rig.api, o);
    server.start();
    const auto one = wt::httpRequest(server.port(), wt::bhttp::verb::delete_, "/api/pair/devices/" + ids[1],
                                     "", installer);
    EXPECT_EQ(one.status, 503) << one.body;
    EXPECT_NE(one.body.find("cannot be saved"), std::string::npos) << one.body;
    const auto all =
        wt::httpRequest(server.port(), wt::bhttp::verb::delete_, "/api/pair/devices", "", installer);
    EXPECT_EQ(all.status, 503) << all.body;
    EXPECT_NE(all.body.find("only 0 revocation(s)"), std::string::npos) << all.body;
    const auto list =
        wt::httpRequest(server.port(), wt::bhttp::verb::get, "/api/pair/devices", "", installer);
    ASSERT_EQ(list.status, 200);
    EXPECT_EQ(boost::json::parse(list.body).at("devices").as_array().size(), 2u) << "run " << run;
    server.stop();
  }
}

}  // namespace
}  // namespace xr::app
