// What the daemon checks at start before anything is driven
// (app/daemon_start.cpp): the stored health ledger against the capacity in
// force, and, while not set up, the file's voltage targets against the
// lowered set (docs/security.md "Hardening, round 3").
#include <gtest/gtest.h>

#include <string>

#include "app/daemon_start.h"
#include "app/store_service.h"
#include "config/config.h"
#include "store_test_util.h"

namespace xr::app {
namespace {

using xr::test::TempDir;

StartState start(const std::string& toml, const std::string& db) {
  const LoadResult r = loadConfigString(toml, "test.toml");
  EXPECT_TRUE(r.ok());
  CliOptions cli;
  cli.stateDb = db;
  Settings settings = r.config->settings;
  return loadStartState(*r.config, cli, settings);
}

int eventsWithCode(StoreService& s, const std::string& code) {
  int n = 0;
  for (const auto& e : s.queryEvents(100, std::nullopt)) n += e.code == code;
  return n;
}

// The reproducer: edited ledger rows gave 100,000,000,000 Ah, offered in one tap.
TEST(StartChecks, AnImplausibleStoredCapacityIsDroppedWithAnEvent) {
  TempDir d;
  const std::string db = d.file("x.db");
  {
    StoreService s(db, 300);
    BatteryLedger l;
    l.valid = true;
    l.capacity.SumAh = 1e11;
    l.capacity.SumSwing = 1.0;
    l.capacity.Cycles = 3.0;
    s.stop(l, true);
  }
  StartState st = start("[battery]\nBatteryProfile = \"agm\"\nBatteryCapacity_Ah = 200\n", db);
  ASSERT_EQ(st.exitCode, 0);
  ASSERT_TRUE(st.restored.has_value());
  EXPECT_EQ(st.restored->capacity.SumAh, 0.0);
  EXPECT_EQ(st.restored->capacity.Cycles, 0.0);
  EXPECT_EQ(eventsWithCode(*st.store, "LedgerDropped"), 1);
  st.store->stop(*st.restored, true);
}

TEST(StartChecks, APlausibleStoredCapacityIsKeptWithoutAWord) {
  TempDir d;
  const std::string db = d.file("x.db");
  {
    StoreService s(db, 300);
    BatteryLedger l;
    l.valid = true;
    l.capacity.SumAh = 170.0;
    l.capacity.SumSwing = 1.0;
    l.capacity.Cycles = 3.0;
    s.stop(l, true);
  }
  StartState st = start("[battery]\nBatteryProfile = \"agm\"\nBatteryCapacity_Ah = 200\n", db);
  ASSERT_TRUE(st.restored.has_value());
  EXPECT_EQ(st.restored->capacity.SumAh, 170.0);
  EXPECT_EQ(eventsWithCode(*st.store, "LedgerDropped"), 0);
  st.store->stop(*st.restored, true);
}

TEST(StartChecks, NotSetUpAFileTargetAboveTheLoweredSetIsRefusedBeforeAnyOutput) {
  TempDir d;
  StartState st = start("[voltage]\nTargetVoltageSetpoint = 14.9\nBulkVoltage = 14.6\n", d.file("x.db"));
  EXPECT_EQ(st.exitCode, kExitConfig);
  StartState fine = start("[voltage]\nTargetVoltageSetpoint = 14.0\n", d.file("y.db"));
  EXPECT_EQ(fine.exitCode, 0);
  EXPECT_DOUBLE_EQ(fine.running.SetupCeilingV, 14.0);
  if (fine.store) fine.store->stop(BatteryLedger{}, false);
}

}  // namespace
}  // namespace xr::app
