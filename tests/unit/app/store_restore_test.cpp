// item 4 through the daemon's store service and web API: a damaged
// database comes back from the verified backup with the dashboard setting,
// lifetime energy and token, and the user is told once (an event, the
// System page's store line); a newer release's database is read, never
// written, and changes are refused.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>

#include "app/store_service.h"
#include "app/web_api.h"
#include "store/sqlite_db.h"
#include "store_test_util.h"

namespace xr::app {
namespace {

using ::testing::HasSubstr;
using xr::test::TempDir;
namespace fs = std::filesystem;

struct Daemon {
  Params params;
  rt::Handoffs handoffs{params};
  StoreService store;
  RecentEvents recent;
  std::unique_ptr<WebApi> api;
  BatteryLedger ledger;
  explicit Daemon(const std::string& db) : store(db, 300) {
    if (auto saved = store.loadLedger()) ledger = saved->ledger;
    params = store.applyOverrides(Params{}, NameSet{}).params;  // as daemon.cpp does at start
    WebApiContext ctx;
    ctx.handoffs = &handoffs;
    ctx.store = &store;
    ctx.events = &recent;
    api = std::make_unique<WebApi>(ctx);
  }
  ~Daemon() { store.stop(ledger, true); }
  int eventsWithCode(const std::string& code) {
    int n = 0;
    for (const auto& e : store.queryEvents(1000, std::nullopt)) n += e.code == code;
    return n;
  }
};

// The owner's data after a season: a dashboard setting, lifetime energy,
// the token; then one more start (the backup at open holds them).
std::string seasonOfUse(const std::string& db) {
  std::string token;
  {
    Daemon d(db);
    EXPECT_TRUE(d.api->patchParams({{findParam("MaxDuty"), -1, 80.0}}, "test").errors.empty());
    d.ledger.ChargedEnergy_AllTime_Wh = 98765.0;
    token = d.store.token();
  }
  { Daemon again(db); }
  return token;
}

TEST(StoreRestore, ADamagedDatabaseKeepsSettingEnergyAndTokenAndSaysSoOnce) {
  TempDir dir;
  const std::string db = dir.file("x.db");
  const std::string token = seasonOfUse(db);
  { std::ofstream(db, std::ios::binary | std::ios::trunc) << std::string(20000, '\x5a'); }
  {
    Daemon d(db);
    EXPECT_TRUE(d.store.openResult().restored) << d.store.openResult().message;
    EXPECT_STREQ(StoreService::alarmCode(d.store.openResult()), "StoreRestored");
    EXPECT_DOUBLE_EQ(d.params.MaxDuty, 80.0);                      // before: the file's value again
    EXPECT_DOUBLE_EQ(d.ledger.ChargedEnergy_AllTime_Wh, 98765.0);  // before: 0
    EXPECT_EQ(d.store.token(), token);                             // before: a new token
    auto v = d.api->versions();
    EXPECT_THAT(v["store"], HasSubstr("RESTORED FROM BACKUP"));
    EXPECT_THAT(v["store"], HasSubstr(".corrupt-"));
    EXPECT_THAT(v["store_backup"], HasSubstr("x.db.bak of "));
    EXPECT_EQ(d.eventsWithCode("StoreRestored"), 1);
    // Changes are saved again at once.
    EXPECT_TRUE(d.api->patchParams({{findParam("MaxDuty"), -1, 81.0}}, "test").errors.empty());
  }
  Daemon next(db);
  EXPECT_EQ(StoreService::alarmCode(next.store.openResult()), nullptr);
  EXPECT_THAT(next.api->versions()["store"], HasSubstr("ok: "));
  EXPECT_EQ(next.eventsWithCode("StoreRestored"), 1);  // told once
  EXPECT_DOUBLE_EQ(next.params.MaxDuty, 81.0);
}

TEST(StoreRestore, ANewerDatabaseIsReadNeverWrittenAndChangesAreRefused) {
  TempDir dir;
  const std::string db = dir.file("x.db");
  const std::string token = seasonOfUse(db);
  {
    sql::Db raw;
    ASSERT_EQ(raw.open(db), SQLITE_OK);
    ASSERT_EQ(raw.exec("PRAGMA user_version = 99"), SQLITE_OK);
  }
  const auto sizeBefore = fs::file_size(db);
  {
    Daemon d(db);
    EXPECT_STREQ(StoreService::alarmCode(d.store.openResult()), "StoreNewerSchema");
    EXPECT_DOUBLE_EQ(d.params.MaxDuty, 80.0);
    EXPECT_DOUBLE_EQ(d.ledger.ChargedEnergy_AllTime_Wh, 98765.0);
    EXPECT_EQ(d.store.token(), token);
    EXPECT_THAT(d.api->versions()["store"], HasSubstr("NOT SAVING"));
    EXPECT_THAT(d.api->versions()["store"], HasSubstr("schema v99"));
    EXPECT_EQ(d.eventsWithCode("StoreNewerSchema"), 1);
    const auto res = d.api->patchParams({{findParam("MaxDuty"), -1, 70.0}}, "test");
    ASSERT_EQ(res.errors.size(), 1u);
    EXPECT_EQ(res.errors[0].name, "store");
  }
  EXPECT_EQ(fs::file_size(db), sizeBefore);
  sql::Db raw;
  ASSERT_EQ(raw.open(db, SQLITE_OPEN_READONLY), SQLITE_OK);
  EXPECT_EQ(raw.queryInt("PRAGMA user_version"), 99);
  EXPECT_EQ(raw.queryInt("SELECT count(*) FROM events WHERE code = 'StoreNewerSchema'"), 0);
}

}  // namespace
}  // namespace xr::app
