// Store failure paths: migration from every earlier schema, corrupt file,
// read-only directory, full disk, newer schema.
#include <gtest/gtest.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "store/schema.h"
#include "store/store.h"
#include "store_test_util.h"

namespace xr {
namespace {

using test::kT0;
using test::TempDir;
namespace fs = std::filesystem;

// Builds a database exactly as release `version` left it, with data in that
// version's tables.
void writeOldDatabase(const std::string& path, int version) {
  sql::Db db;
  ASSERT_EQ(db.open(path), SQLITE_OK);
  ASSERT_EQ(store::createAtVersion(db, version), SQLITE_OK) << db.lastError();
  ASSERT_EQ(db.exec("INSERT INTO ledger(name, value) VALUES('ChargedEnergy_AllTime', 1234.5),"
                    "('CoulombCount_Ah', 150.0), ('DynamicShuntGainFactor', 1.03)"),
            SQLITE_OK);
  ASSERT_EQ(db.exec("INSERT INTO overrides(name, value) VALUES('BulkVoltage', '14.1')"), SQLITE_OK);
  ASSERT_EQ(db.exec("INSERT INTO events(t_ms, level, code, message) VALUES(1000, 'Info', 'Message', 'old')"),
            SQLITE_OK);
  if (version >= 2) {
    ASSERT_EQ(db.exec("INSERT INTO kv(key, value) VALUES('web_token', 'oldtoken')"), SQLITE_OK);
  }
  ASSERT_EQ(db.queryInt("PRAGMA user_version"), version);
}

class Migration : public ::testing::TestWithParam<int> {};

TEST_P(Migration, FromEarlierSchemaKeepsData) {
  TempDir d;
  const int from = GetParam();
  writeOldDatabase(d.file("x.db"), from);
  Store s;
  const OpenResult r = s.open(d.file("x.db"), kT0);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_FALSE(r.alarm());
  EXPECT_EQ(r.fromVersion, from);
  const auto saved = s.loadLedger();
  ASSERT_TRUE(saved.has_value());
  EXPECT_DOUBLE_EQ(saved->ledger.ChargedEnergy_AllTime_Wh, 1234.5);
  EXPECT_DOUBLE_EQ(saved->ledger.CoulombCount_Ah, 150.0);
  EXPECT_DOUBLE_EQ(saved->ledger.DynamicShuntGainFactor, 1.03);
  EXPECT_DOUBLE_EQ(saved->ledger.SolarChargedEnergy_AllTime_Wh, 0.0);  // absent field: default
  EXPECT_EQ(saved->savedAtMs, 0);                                      // unknown for old data
  const auto o = s.findOverride("BulkVoltage");
  ASSERT_TRUE(o.has_value());
  EXPECT_EQ(o->value, "14.1");
  const auto ev = s.queryEvents(10);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].message, "old");
  EXPECT_EQ(ev[0].reason, "NONE");
  if (from >= 2) {
    EXPECT_EQ(s.getOrCreateToken(), "oldtoken");
  }
  // An install that ran before "not set up" existed stays set up (v4); a v4
  // file had that mark set by its own upgrade, or was new then.
  if (from < 4) {
    EXPECT_EQ(s.getBlob("set_up_before_upgrade"), std::optional<std::string>("1"));
  }
  // The new tables work after migration.
  std::vector<double> v(defaultHistorySeries().size(), 1.0);
  ASSERT_TRUE(s.appendHistory(kT0, v).ok);
  ASSERT_TRUE(s.flushHistory().ok);
  EXPECT_TRUE(s.checkpoint(saved->ledger, "stop", kT0).ok);
  EXPECT_EQ(s.integrityCheck(), "ok");
  sql::Db db;
  ASSERT_EQ(db.open(d.file("x.db")), SQLITE_OK);
  EXPECT_EQ(db.queryInt("PRAGMA user_version"), store::kSchemaVersion);
}

INSTANTIATE_TEST_SUITE_P(EveryEarlierVersion, Migration, ::testing::Range(1, store::kSchemaVersion));

TEST(Migration, AFreshDatabaseIsNotSetUpByUpgrade) {
  TempDir d;
  Store s;
  ASSERT_TRUE(s.open(d.file("fresh.db"), kT0).ok);
  EXPECT_FALSE(s.getBlob("set_up_before_upgrade").has_value());
}

TEST(StoreFailure, GarbageFileIsKeptAsideAndStartsFresh) {
  TempDir d;
  {
    std::ofstream f(d.file("x.db"), std::ios::binary);
    for (int i = 0; i < 5000; ++i) f << "this is not a database " << i;
  }
  Store s;
  const OpenResult r = s.open(d.file("x.db"), kT0);
  EXPECT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(r.recovered);
  EXPECT_TRUE(r.alarm());
  ASSERT_FALSE(r.corruptCopy.empty());
  EXPECT_TRUE(fs::exists(r.corruptCopy));
  EXPECT_NE(r.corruptCopy.find(".corrupt-"), std::string::npos);
  EXPECT_FALSE(s.loadLedger().has_value());
  BatteryLedger l;
  l.ChargedEnergy_AllTime_Wh = 7.0;
  EXPECT_TRUE(s.checkpoint(l, "interval", kT0).ok);
  EXPECT_EQ(s.integrityCheck(), "ok");
}

TEST(StoreFailure, DamagedPagesAreDetected) {
  TempDir d;
  {
    Store s;
    ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
    std::vector<EventRecord> evs(2000,
                                 EventRecord{0, kT0, "Info", "Message", "NONE", std::string(200, 'x'), 0, 0});
    ASSERT_TRUE(s.appendEvents(evs).ok);
    BatteryLedger l;
    ASSERT_TRUE(s.checkpoint(l, "stop", kT0).ok);
  }  // close() checkpoints the WAL into the main file
  {
    // Keep the header (a valid "SQLite format 3" file), scribble over pages.
    std::fstream f(d.file("x.db"), std::ios::binary | std::ios::in | std::ios::out);
    ASSERT_TRUE(f.good());
    for (std::streamoff off = 4096; off < 200 * 1024; off += 8192) {
      f.seekp(off);
      f << std::string(600, '\xA5');
    }
  }
  Store s;
  const OpenResult r = s.open(d.file("x.db"), kT0 + 1000);
  EXPECT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(r.recovered) << r.message;
  EXPECT_TRUE(fs::exists(r.corruptCopy));
  EXPECT_EQ(s.integrityCheck(), "ok");
}

TEST(StoreFailure, NewerSchemaIsNotTouchedInPlace) {
  TempDir d;
  {
    sql::Db db;
    ASSERT_EQ(db.open(d.file("x.db")), SQLITE_OK);
    ASSERT_EQ(store::createAtVersion(db, store::kSchemaVersion), SQLITE_OK);
    ASSERT_EQ(db.exec("PRAGMA user_version = 99"), SQLITE_OK);
  }
  Store s;
  const OpenResult r = s.open(d.file("x.db"), kT0);
  // A newer release's data is neither migrated down nor moved aside (issue
  // 26, item 4): read into memory, and nothing of this run is saved.
  EXPECT_FALSE(r.recovered);
  EXPECT_TRUE(r.corruptCopy.empty());
  EXPECT_TRUE(r.newerSchema);
  EXPECT_TRUE(r.inMemory);
  EXPECT_TRUE(r.alarm());
  EXPECT_TRUE(fs::exists(d.file("x.db")));
}

// Runs f in a child process without root's permission override; returns its
// exit status. The directory is made read-only for that user.
template <typename F>
int asUnprivilegedChild(F&& f) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (geteuid() == 0) {
      if (setgid(65534) != 0 || setuid(65534) != 0) _exit(90);
    }
    _exit(f());
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 100 + WTERMSIG(status);
}

TEST(StoreFailure, ReadOnlyDirectoryRunsInMemoryWithAlarm) {
  TempDir d;
  fs::permissions(d.path, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                              fs::perms::others_read | fs::perms::others_exec);
  if (geteuid() != 0) fs::permissions(d.path, fs::perms::owner_write, fs::perm_options::remove);
  const std::string path = d.file("x.db");
  const int rc = asUnprivilegedChild([&] {
    Store s;
    const OpenResult r = s.open(path, kT0);
    if (r.ok) return 1;
    if (!r.inMemory || !r.alarm()) return 2;
    // Everything still answers; nothing crashes.
    BatteryLedger l;
    l.ChargedEnergy_AllTime_Wh = 3.0;
    if (!s.checkpoint(l, "interval", kT0).ok) return 3;
    if (!s.loadLedger() || s.loadLedger()->ledger.ChargedEnergy_AllTime_Wh != 3.0) return 4;
    if (!s.setOverride("BulkVoltage", "14.0", "14.5", kT0).ok) return 5;
    if (s.getOrCreateToken().size() != 64) return 6;
    return 0;
  });
  EXPECT_EQ(rc, 0);
  EXPECT_FALSE(fs::exists(path));
}

TEST(StoreFailure, ReadOnlyDirectoryStillRestoresLastCheckpoint) {
  TempDir d;
  const std::string path = d.file("x.db");
  {
    Store s;
    ASSERT_TRUE(s.open(path, kT0).ok);
    BatteryLedger l;
    l.ChargedEnergy_AllTime_Wh = 4321.0;
    ASSERT_TRUE(s.checkpoint(l, "stop", kT0).ok);
    ASSERT_TRUE(s.setOverride("BulkVoltage", "14.1", "14.5", kT0).ok);
  }
  fs::permissions(
      path, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read);
  fs::permissions(d.path, fs::perms::owner_all | fs::perms::group_read | fs::perms::group_exec |
                              fs::perms::others_read | fs::perms::others_exec);
  if (geteuid() != 0) {
    fs::permissions(d.path, fs::perms::owner_write, fs::perm_options::remove);
    fs::permissions(path, fs::perms::owner_write, fs::perm_options::remove);
  }
  const int rc = asUnprivilegedChild([&] {
    Store s;
    const OpenResult r = s.open(path, kT0);
    if (r.ok || !r.inMemory) return 1;
    const auto saved = s.loadLedger();
    if (!saved || saved->ledger.ChargedEnergy_AllTime_Wh != 4321.0) return 2;
    if (!s.findOverride("BulkVoltage")) return 3;
    BatteryLedger l = saved->ledger;
    l.ChargedEnergy_AllTime_Wh += 1.0;
    if (!s.checkpoint(l, "interval", kT0).ok) return 4;  // into memory, no crash
    return 0;
  });
  EXPECT_EQ(rc, 0);
  Store s;  // the file itself is untouched
  fs::permissions(d.path, fs::perms::owner_all, fs::perm_options::add);
  fs::permissions(path, fs::perms::owner_write, fs::perm_options::add);
  ASSERT_TRUE(s.open(path, kT0).ok);
  EXPECT_DOUBLE_EQ(s.loadLedger()->ledger.ChargedEnergy_AllTime_Wh, 4321.0);
}

TEST(StoreFailure, UnreadableExistingFileWithoutWriteAccess) {
  TempDir d;
  const std::string path = d.file("x.db");
  {
    Store s;
    ASSERT_TRUE(s.open(path, kT0).ok);
    BatteryLedger l;
    ASSERT_TRUE(s.checkpoint(l, "stop", kT0).ok);
  }
  fs::permissions(path, fs::perms::owner_read | fs::perms::owner_write);  // 0600, owned by us
  const int rc = asUnprivilegedChild([&] {
    Store s;
    const OpenResult r = s.open(path, kT0);
    return (!r.ok && r.inMemory) ? 0 : 1;
  });
  if (geteuid() == 0) {
    EXPECT_EQ(rc, 0);
  }
  // The file itself is untouched.
  Store s;
  EXPECT_TRUE(s.open(path, kT0).ok);
  EXPECT_TRUE(s.loadLedger().has_value());
}

TEST(StoreFailure, FullDiskIsAnErrorValueNotACrash) {
  TempDir d;
  StoreOptions opt;
  opt.maxPageCount = 40;  // a tiny quota: the "disk" fills up quickly
  opt.historyFlushS = 1;
  Store s(opt);
  ASSERT_TRUE(s.open(d.file("x.db"), kT0).ok);
  BatteryLedger l;
  l.valid = true;
  l.ChargedEnergy_AllTime_Wh = 5.0;
  ASSERT_TRUE(s.checkpoint(l, "interval", kT0).ok);
  bool sawFull = false;
  for (int i = 0; i < 200 && !sawFull; ++i) {
    std::vector<EventRecord> evs(
        20, EventRecord{0, kT0 + i, "Info", "Message", "NONE", std::string(500, 'e'), 0, 0});
    const StoreStatus st = s.appendEvents(evs);
    if (!st.ok) {
      EXPECT_TRUE(st.diskFull) << st.error;
      EXPECT_FALSE(st.error.empty());
      sawFull = true;
    }
  }
  ASSERT_TRUE(sawFull);
  // History keeps failing cleanly too, and the old ledger is intact.
  std::vector<double> v(opt.historySeries.size(), 1.0);
  for (int i = 0; i < 5; ++i) s.appendHistory(kT0 + i * 1000, v);
  const auto saved = s.loadLedger();
  ASSERT_TRUE(saved.has_value());
  EXPECT_EQ(saved->ledger, l);
  EXPECT_EQ(s.integrityCheck(), "ok");
  // Room again (old events compacted away): writing works again.
  sql::Db db;
  ASSERT_EQ(db.open(d.file("x.db")), SQLITE_OK);
  ASSERT_EQ(db.exec("DELETE FROM events"), SQLITE_OK);
  db.close();
  l.ChargedEnergy_AllTime_Wh = 10.0;
  EXPECT_TRUE(s.checkpoint(l, "interval", kT0).ok);
}

}  // namespace
}  // namespace xr
