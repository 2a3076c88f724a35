// the user's data (dashboard settings, lifetime energy,
// cycles, the web token) survives a damaged, lost or newer-schema database,
// through the verified backup <db>.bak. Real SQLite files throughout.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "store/backup.h"
#include "store/schema.h"
#include "store/store.h"
#include "store_test_util.h"

namespace xr {
namespace {

using test::kT0;
using test::TempDir;
namespace fs = std::filesystem;

constexpr std::int64_t kDayMs = 24 * 3600 * 1000LL;

std::string readAll(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>()};
}

// What the user would lose: a dashboard setting, lifetime energy and cycles,
// the token. Written, then the store is opened once more so the backup taken
// at open holds them (as after any restart of the daemon).
struct UserData {
  std::string token;
};

UserData writeUserData(const std::string& db) {
  UserData u;
  {
    Store s;
    EXPECT_TRUE(s.open(db, kT0).ok);
    EXPECT_TRUE(s.setOverride("FloatVoltage", "13.4", "13.5", kT0).ok);
    BatteryLedger l;
    l.ChargedEnergy_AllTime_Wh = 123456.5;
    l.DischargedEnergy_AllTime_Wh = 321.25;  // the cycle count derives from it
    EXPECT_TRUE(s.checkpoint(l, "stop", kT0).ok);
    u.token = s.getOrCreateToken();
    // Enough events that the file has many pages (a truncation hits data).
    std::vector<EventRecord> evs(1500,
                                 EventRecord{0, kT0, "info", "Message", "NONE", std::string(200, 'e'), 0, 0});
    EXPECT_TRUE(s.appendEvents(evs).ok);
  }
  Store again;
  EXPECT_TRUE(again.open(db, kT0 + 1000).ok);  // the backup at open
  EXPECT_TRUE(fs::exists(db + ".bak"));
  return u;
}

void expectUserData(Store& s, const UserData& u) {
  const auto o = s.findOverride("FloatVoltage");
  ASSERT_TRUE(o.has_value()) << "the dashboard setting is gone";
  EXPECT_EQ(o->value, "13.4");
  const auto saved = s.loadLedger();
  ASSERT_TRUE(saved.has_value()) << "lifetime energy is gone";
  EXPECT_DOUBLE_EQ(saved->ledger.ChargedEnergy_AllTime_Wh, 123456.5);
  EXPECT_DOUBLE_EQ(saved->ledger.DischargedEnergy_AllTime_Wh, 321.25);
  EXPECT_EQ(s.getOrCreateToken(), u.token) << "a new token was made";
}

std::vector<std::string> filesWith(const TempDir& d, const std::string& part) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(d.path))
    if (e.path().filename().string().find(part) != std::string::npos) out.push_back(e.path().string());
  return out;
}

// ---------------------------------------------------------------- damage

enum class Damage { Truncated, Garbage, Empty, Missing, ScribbledPages };

class DamagedDatabase : public ::testing::TestWithParam<Damage> {};

TEST_P(DamagedDatabase, SettingsLifetimeEnergyAndTokenSurviveFromTheBackup) {
  TempDir d;
  const std::string db = d.file("x.db");
  const UserData u = writeUserData(db);
  const auto size = fs::file_size(db);
  ASSERT_GT(size, 200u * 1024);
  switch (GetParam()) {
    case Damage::Truncated:
      ASSERT_EQ(::truncate(db.c_str(), static_cast<off_t>(size / 2)), 0);
      break;
    case Damage::Garbage: {
      std::ofstream f(db, std::ios::binary | std::ios::trunc);
      for (std::size_t i = 0; i < size; ++i) f.put(static_cast<char>((i * 131 + 7) & 0xff));
      break;
    }
    case Damage::Empty:
      ASSERT_EQ(::truncate(db.c_str(), 0), 0);
      break;
    case Damage::Missing:
      fs::remove(db);
      break;
    case Damage::ScribbledPages: {
      std::fstream f(db, std::ios::binary | std::ios::in | std::ios::out);
      for (std::streamoff off = 4096; off < 200 * 1024; off += 8192) {
        f.seekp(off);
        f << std::string(600, '\xA5');
      }
      break;
    }
  }
  Store s;
  const OpenResult r = s.open(db, kT0 + kDayMs);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(r.restored) << r.message;
  EXPECT_TRUE(r.alarm());
  EXPECT_EQ(r.backupUsed, db + ".bak");
  EXPECT_NE(r.message.find("restored from the verified backup"), std::string::npos) << r.message;
  if (GetParam() == Damage::Missing) {
    EXPECT_FALSE(r.recovered);
  } else {
    // The damaged file is kept for a look, never deleted.
    EXPECT_TRUE(r.recovered);
    ASSERT_FALSE(r.corruptCopy.empty());
    EXPECT_TRUE(fs::exists(r.corruptCopy));
  }
  expectUserData(s, u);
  EXPECT_EQ(s.integrityCheck(), "ok");
  // The restored database is a working one, written in WAL mode again.
  BatteryLedger l;
  l.ChargedEnergy_AllTime_Wh = 123457.0;
  EXPECT_TRUE(s.checkpoint(l, "interval", kT0 + kDayMs).ok);
  EXPECT_TRUE(s.setOverride("BulkVoltage", "14.2", "14.4", kT0).ok);
  s.close();
  Store next;
  const OpenResult r2 = next.open(db, kT0 + 2 * kDayMs);
  EXPECT_TRUE(r2.ok);
  EXPECT_FALSE(r2.alarm()) << "told once, not at every start: " << r2.message;
  EXPECT_DOUBLE_EQ(next.loadLedger()->ledger.ChargedEnergy_AllTime_Wh, 123457.0);
}

INSTANTIATE_TEST_SUITE_P(EveryKind, DamagedDatabase,
                         ::testing::Values(Damage::Truncated, Damage::Garbage, Damage::Empty, Damage::Missing,
                                           Damage::ScribbledPages),
                         [](const auto& info) {
                           switch (info.param) {
                             case Damage::Truncated:
                               return std::string("Truncated");
                             case Damage::Garbage:
                               return std::string("Garbage");
                             case Damage::Empty:
                               return std::string("Empty");
                             case Damage::Missing:
                               return std::string("Missing");
                             case Damage::ScribbledPages:
                               return std::string("ScribbledPages");
                           }
                           return std::string("?");
                         });

TEST(StoreBackup, ADamagedFileWithADamagedBackupStartsFreshAndSaysSo) {
  TempDir d;
  const std::string db = d.file("x.db");
  writeUserData(db);
  { std::ofstream(db, std::ios::binary | std::ios::trunc) << std::string(9000, 'x'); }
  { std::ofstream(db + ".bak", std::ios::binary | std::ios::trunc) << std::string(9000, 'y'); }
  Store s;
  const OpenResult r = s.open(db, kT0 + kDayMs);
  EXPECT_TRUE(r.ok);
  EXPECT_TRUE(r.recovered);
  EXPECT_FALSE(r.restored);
  EXPECT_NE(r.message.find("no usable backup"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("reset"), std::string::npos) << r.message;
  EXPECT_FALSE(s.loadLedger().has_value());
}

TEST(StoreBackup, AFirstStartHasNoAlarm) {
  TempDir d;
  Store s;
  const OpenResult r = s.open(d.file("x.db"), kT0);
  EXPECT_TRUE(r.ok);
  EXPECT_FALSE(r.alarm()) << r.message;
  EXPECT_TRUE(fs::exists(d.file("x.db.bak")));
}

// ---------------------------------------------------------------- a newer schema

void makeNewer(const std::string& db, int version, const char* extraSql = nullptr) {
  sql::Db raw;
  ASSERT_EQ(raw.open(db), SQLITE_OK);
  if (extraSql) {
    ASSERT_EQ(raw.exec(extraSql), SQLITE_OK) << raw.lastError();
  }
  ASSERT_EQ(raw.exec("PRAGMA user_version = " + std::to_string(version)), SQLITE_OK);
  ASSERT_EQ(raw.exec("PRAGMA wal_checkpoint(TRUNCATE)"), SQLITE_OK);
}

TEST(StoreBackup, ANewerSchemaIsNeverWrittenMovedOrMigratedAndItsDataIsRead) {
  TempDir d;
  const std::string db = d.file("x.db");
  const UserData u = writeUserData(db);
  makeNewer(db, 99);
  const std::string fileBefore = readAll(db);
  const std::string bakBefore = readAll(db + ".bak");
  const auto mtimeBefore = fs::last_write_time(db);
  {
    Store s;
    const OpenResult r = s.open(db, kT0 + kDayMs);
    EXPECT_TRUE(r.newerSchema) << r.message;
    EXPECT_TRUE(r.inMemory);
    EXPECT_TRUE(r.alarm());
    EXPECT_FALSE(r.recovered);
    EXPECT_EQ(r.fromVersion, 99);
    EXPECT_NE(r.message.find("NOTHING IS SAVED"), std::string::npos) << r.message;
    EXPECT_EQ(r.message.find("not an error"), std::string::npos) << r.message;
    expectUserData(s, u);
    // This run's changes go to memory only.
    EXPECT_TRUE(s.setOverride("FloatVoltage", "13.2", "13.5", kT0).ok);
    BatteryLedger l;
    EXPECT_TRUE(s.checkpoint(l, "stop", kT0 + kDayMs).ok);
    EXPECT_FALSE(s.backup(kT0 + kDayMs).ok);  // and no backup over the older release's copy
    EXPECT_TRUE(s.backupIfDue(kT0 + 9 * kDayMs).ok);
  }
  EXPECT_TRUE(filesWith(d, ".corrupt-").empty());
  EXPECT_EQ(readAll(db), fileBefore) << "the newer release's file was changed";
  EXPECT_EQ(fs::last_write_time(db), mtimeBefore);
  EXPECT_EQ(readAll(db + ".bak"), bakBefore);
  sql::Db raw;
  ASSERT_EQ(raw.open(db), SQLITE_OK);
  EXPECT_EQ(raw.queryInt("PRAGMA user_version"), 99);
}

TEST(StoreBackup, ANewerSchemaThisReleaseCannotReadRunsFromTheBackup) {
  TempDir d;
  const std::string db = d.file("x.db");
  const UserData u = writeUserData(db);
  // The newer release renamed a table this release reads.
  makeNewer(db, store::kSchemaVersion + 1, "ALTER TABLE overrides RENAME TO settings");
  const std::string fileBefore = readAll(db);
  Store s;
  const OpenResult r = s.open(db, kT0 + kDayMs);
  EXPECT_TRUE(r.newerSchema);
  EXPECT_TRUE(r.inMemory);
  EXPECT_EQ(r.backupUsed, db + ".bak");
  EXPECT_NE(r.message.find("cannot read it"), std::string::npos) << r.message;
  expectUserData(s, u);
  s.close();
  EXPECT_EQ(readAll(db), fileBefore);
}

TEST(StoreBackup, ABackupWrittenByANewerReleaseIsNeverReplaced) {
  TempDir d;
  const std::string db = d.file("x.db");
  writeUserData(db);
  makeNewer(db + ".bak", 7);
  const std::string bakBefore = readAll(db + ".bak");
  Store s;
  const OpenResult r = s.open(db, kT0 + kDayMs);
  EXPECT_TRUE(r.ok);
  EXPECT_NE(r.message.find("is kept as it is"), std::string::npos) << r.message;
  EXPECT_TRUE(s.setOverride("FloatVoltage", "13.3", "13.5", kT0).ok);
  EXPECT_TRUE(s.backupIfDue(kT0 + 9 * kDayMs).ok);
  EXPECT_FALSE(s.backup(kT0 + 9 * kDayMs).ok);
  EXPECT_EQ(readAll(db + ".bak"), bakBefore);
}

// ---------------------------------------------------------------- when copies are made

TEST(StoreBackup, BeforeAMigrationTheOldSchemaIsCopiedAndVerified) {
  TempDir d;
  const std::string db = d.file("x.db");
  {
    sql::Db raw;
    ASSERT_EQ(raw.open(db), SQLITE_OK);
    ASSERT_EQ(store::createAtVersion(raw, 2), SQLITE_OK);
    ASSERT_EQ(raw.exec("INSERT INTO kv(key, value) VALUES('web_token', 'v2token')"), SQLITE_OK);
  }
  Store s;
  const OpenResult r = s.open(db, kT0);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_EQ(r.fromVersion, 2);
  const store::BackupCheck c = store::checkBackup(db + ".bak-v2", 2);
  EXPECT_TRUE(c.usable) << c.why;
  EXPECT_EQ(c.version, 2);
  sql::Db old;
  ASSERT_EQ(old.open(db + ".bak-v2", SQLITE_OPEN_READONLY), SQLITE_OK);
  EXPECT_EQ(old.queryText("SELECT value FROM kv WHERE key = 'web_token'"), "v2token");
  // The regular backup holds the migrated data.
  EXPECT_EQ(store::checkBackup(db + ".bak", store::kSchemaVersion).version, store::kSchemaVersion);
}

TEST(StoreBackup, TheCopyIsOneVerifiedFilePrivateToItsOwner) {
  TempDir d;
  const std::string db = d.file("x.db");
  const mode_t old = ::umask(022);  // a shell's usual umask
  const UserData u = writeUserData(db);
  ::umask(old);
  struct stat st {
  }, dbSt{};
  ASSERT_EQ(::stat((db + ".bak").c_str(), &st), 0);
  ASSERT_EQ(::stat(db.c_str(), &dbSt), 0);
  // Never readable by other users; the group reads it only when it may read
  // the database (0640 under systemd's UMask=0027).
  EXPECT_EQ(st.st_mode & 0007, 0u) << std::oct << (st.st_mode & 0777);
  EXPECT_EQ(st.st_mode & 0070, dbSt.st_mode & 0040) << std::oct << (st.st_mode & 0777);
  EXPECT_EQ(st.st_mode & 0600, 0600u);
  EXPECT_FALSE(fs::exists(db + ".bak.tmp"));
  EXPECT_FALSE(fs::exists(db + ".bak-wal"));
  const store::BackupCheck c = store::checkBackup(db + ".bak", store::kSchemaVersion);
  EXPECT_TRUE(c.usable) << c.why;
  // Self-contained: a rollback-journal file, readable alone.
  sql::Db b;
  ASSERT_EQ(b.open(db + ".bak", SQLITE_OPEN_READONLY), SQLITE_OK);
  EXPECT_EQ(b.queryText("PRAGMA journal_mode"), "delete");
  EXPECT_EQ(b.queryText("SELECT value FROM kv WHERE key = 'web_token'"), u.token);
}

std::string backedUpFloat(const std::string& db) {
  sql::Db b;
  if (b.open(db + ".bak", SQLITE_OPEN_READONLY) != SQLITE_OK) return "?";
  return b.queryText("SELECT value FROM overrides WHERE name = 'FloatVoltage'");
}

TEST(StoreBackup, DailyCopyIsDueAtTheIntervalNotJustBefore) {
  TempDir d;
  const std::string db = d.file("x.db");
  StoreOptions o;
  o.backupIntervalS = 24 * 3600;
  o.settingsBackupS = 24 * 3600;  // only the daily rule here
  Store s(o);
  ASSERT_TRUE(s.open(db, kT0).ok);
  EXPECT_EQ(s.lastBackupMs(), kT0);
  ASSERT_TRUE(s.setOverride("FloatVoltage", "13.4", "13.5", kT0).ok);
  EXPECT_TRUE(s.backupIfDue(kT0 + kDayMs - 1).ok);
  EXPECT_EQ(backedUpFloat(db), "") << "copied before it was due";
  EXPECT_TRUE(s.backupIfDue(kT0 + kDayMs).ok);
  EXPECT_EQ(backedUpFloat(db), "13.4");
  EXPECT_EQ(s.lastBackupMs(), kT0 + kDayMs);
}

TEST(StoreBackup, ASettingsChangeIsCopiedAfterTheSettingsDelay) {
  TempDir d;
  const std::string db = d.file("x.db");
  StoreOptions o;
  o.settingsBackupS = 600;
  Store s(o);
  ASSERT_TRUE(s.open(db, kT0).ok);
  // Without a change nothing is copied before the day is over.
  EXPECT_TRUE(s.backupIfDue(kT0 + 700'000).ok);
  EXPECT_EQ(s.lastBackupMs(), kT0);
  ASSERT_TRUE(s.setOverride("FloatVoltage", "13.4", "13.5", kT0).ok);
  EXPECT_TRUE(s.backupIfDue(kT0 + 599'999).ok);
  EXPECT_EQ(backedUpFloat(db), "");
  EXPECT_TRUE(s.backupIfDue(kT0 + 600'000).ok);
  EXPECT_EQ(backedUpFloat(db), "13.4");
  // The change is now in the copy: not copied again until the next change.
  EXPECT_TRUE(s.backupIfDue(kT0 + 1'300'000).ok);
  EXPECT_EQ(s.lastBackupMs(), kT0 + 600'000);
}

TEST(StoreBackup, AFailedCopyLeavesThePreviousOneAndIsRetriedAnHourLater) {
  TempDir d;
  const std::string db = d.file("x.db");
  Store s;
  ASSERT_TRUE(s.open(db, kT0).ok);
  ASSERT_TRUE(s.setOverride("FloatVoltage", "13.4", "13.5", kT0).ok);
  const std::string before = readAll(db + ".bak");
  // The temp name is taken by a directory that cannot be removed.
  fs::create_directories(db + ".bak.tmp/keep");
  const StoreStatus st = s.backupIfDue(kT0 + kDayMs);
  EXPECT_FALSE(st.ok);
  EXPECT_NE(st.error.find(".bak.tmp"), std::string::npos) << st.error;
  EXPECT_EQ(readAll(db + ".bak"), before);
  EXPECT_TRUE(s.backupIfDue(kT0 + kDayMs + 3'599'999).ok);  // not retried every second
  fs::remove_all(db + ".bak.tmp");
  EXPECT_TRUE(s.backupIfDue(kT0 + kDayMs + 3'600'000).ok);
  EXPECT_EQ(backedUpFloat(db), "13.4");
}

// The journal line of a newer schema read "datatype mismatch (not an error)".
TEST(StoreBackup, AnErrorWeRaiseDoesNotBorrowTheConnectionsMessage) {
  sql::Db db;
  ASSERT_EQ(db.open(":memory:"), SQLITE_OK);
  db.setError(SQLITE_MISMATCH, "schema");
  EXPECT_EQ(db.lastError(), "schema: datatype mismatch");
  // A real error still carries SQLite's own words.
  EXPECT_NE(db.exec("SELECT * FROM nope"), SQLITE_OK);
  EXPECT_NE(db.lastError().find("no such table: nope"), std::string::npos) << db.lastError();
}

}  // namespace
}  // namespace xr
