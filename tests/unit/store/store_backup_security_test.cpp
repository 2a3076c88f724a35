// What an owner would lose reaches the verified backup within seconds of
// the change (docs/operations.md "The daemon's own backup"): the first
// run's token, a paired device, a setting changed a minute before the card
// was damaged; and a wall clock set back does not stop the copies
// (docs/security.md "The clock").
#include <gtest/gtest.h>
#include <sqlite3.h>

#include <filesystem>
#include <fstream>

#include "store/sqlite_db.h"
#include "store/store.h"
#include "store_test_util.h"

namespace xr {
namespace {

namespace fs = std::filesystem;
using test::kT0;
using test::TempDir;

std::string inBackup(const std::string& db, const std::string& sql) {
  sql::Db b;
  if (b.open(db + ".bak", SQLITE_OPEN_READONLY) != SQLITE_OK) return "?";
  return b.queryText(sql);
}

void damage(const std::string& db) {
  const auto size = fs::file_size(db);
  std::ofstream f(db, std::ios::binary | std::ios::trunc);
  for (std::size_t i = 0; i < size; ++i) f.put(static_cast<char>((i * 131 + 7) & 0xff));
  fs::remove(db + "-wal");
  fs::remove(db + "-shm");
}

TEST(StoreBackupSecurity, TokenPairedDeviceAndARecentSettingSurviveADamagedFile) {
  TempDir d;
  const std::string db = d.file("x.db");
  std::string token;
  {
    Store s;
    ASSERT_TRUE(s.open(db, kT0).ok);  // the first start: the copy at open is empty
    token = s.getOrCreateToken();
    ASSERT_TRUE(s.putBlob("device:0123abcd", "phone-row").ok);
    ASSERT_TRUE(s.setOverride("FloatVoltage", "13.4", "13.5", kT0 + 5'000).ok);
    // The daemon's 1 Hz housekeeping, ten seconds after the first start.
    EXPECT_TRUE(s.backupIfDue(kT0 + 9'999).ok);
    EXPECT_EQ(inBackup(db, "SELECT value FROM kv WHERE key = 'web_token'"), "") << "copied before the delay";
    EXPECT_TRUE(s.backupIfDue(kT0 + 10'000).ok);
    EXPECT_EQ(inBackup(db, "SELECT value FROM kv WHERE key = 'web_token'"), token);
    s.close();
  }
  damage(db);
  Store s;
  const OpenResult r = s.open(db, kT0 + 60'000);
  ASSERT_TRUE(r.ok) << r.message;
  ASSERT_TRUE(r.restored) << r.message;
  EXPECT_EQ(s.getOrCreateToken(), token);
  EXPECT_EQ(s.getBlob("device:0123abcd").value_or(""), "phone-row");
  ASSERT_TRUE(s.findOverride("FloatVoltage"));
  EXPECT_EQ(s.findOverride("FloatVoltage")->value, "13.4");
}

TEST(StoreBackupSecurity, ARevocationReachesTheBackupSoTheRestoreDoesNotBringTheDeviceBack) {
  TempDir d;
  const std::string db = d.file("x.db");
  Store s;
  ASSERT_TRUE(s.open(db, kT0).ok);
  ASSERT_TRUE(s.putBlob("device:0123abcd", "phone-row").ok);
  ASSERT_TRUE(s.backupIfDue(kT0 + 10'000).ok);
  ASSERT_EQ(inBackup(db, "SELECT count(*) FROM kv WHERE key = 'device:0123abcd'"), "1");
  ASSERT_TRUE(s.eraseBlob("device:0123abcd").ok);
  ASSERT_TRUE(s.backupIfDue(kT0 + 20'000).ok);
  EXPECT_EQ(inBackup(db, "SELECT count(*) FROM kv WHERE key = 'device:0123abcd'"), "0");
}

TEST(StoreBackupSecurity, AClockSetBackByHoursDoesNotStopTheCopies) {
  TempDir d;
  const std::string db = d.file("x.db");
  Store s;
  ASSERT_TRUE(s.open(db, kT0).ok);
  ASSERT_TRUE(s.setOverride("FloatVoltage", "13.4", "13.5", kT0).ok);
  const std::int64_t back = kT0 - 5 * 3'600'000;  // the clock jumps 5 h back
  EXPECT_TRUE(s.backupIfDue(back).ok);
  EXPECT_EQ(inBackup(db, "SELECT value FROM overrides WHERE name = 'FloatVoltage'"), "13.4");
  EXPECT_EQ(s.lastBackupMs(), back);  // the count restarts from the new time
  ASSERT_TRUE(s.setOverride("FloatVoltage", "13.3", "13.5", back).ok);
  EXPECT_TRUE(s.backupIfDue(back + 10'000).ok);
  EXPECT_EQ(inBackup(db, "SELECT value FROM overrides WHERE name = 'FloatVoltage'"), "13.3");
}

TEST(StoreBackupSecurity, AClockSetForwardByHoursMakesOneCopyNotOneASecond) {
  TempDir d;
  const std::string db = d.file("x.db");
  Store s;
  ASSERT_TRUE(s.open(db, kT0).ok);
  const std::int64_t ahead = kT0 + 30LL * 24 * 3'600'000;  // a month forward: the daily copy is due
  EXPECT_TRUE(s.backupIfDue(ahead).ok);
  EXPECT_EQ(s.lastBackupMs(), ahead);
  EXPECT_TRUE(s.backupIfDue(ahead + 1'000).ok);
  EXPECT_EQ(s.lastBackupMs(), ahead);
}

}  // namespace
}  // namespace xr
