// the state database holds the web token, so it is created
// without access for other users even outside systemd (whose UMask=0027
// would otherwise be the only thing keeping it private).
#include "app/store_service.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <sstream>

#include "app/config_check.h"
#include "store_test_util.h"

namespace xr::app {
namespace {

using xr::test::TempDir;

mode_t modeOf(const std::string& path) {
  struct stat st {};
  EXPECT_EQ(stat(path.c_str(), &st), 0) << path;
  return st.st_mode & 0777;
}

TEST(StoreServiceFiles, ANewDatabaseIsPrivateUnderAPermissiveUmask) {
  TempDir d;
  const std::string db = d.file("x.db");
  const mode_t old = umask(022);  // a shell's usual umask: files 0644
  {
    StoreService svc(db, 300);
    ASSERT_TRUE(svc.openResult().ok);
    EXPECT_EQ(svc.token().size(), 64u);
    EXPECT_EQ(modeOf(db) & 0077, 0u) << std::oct << modeOf(db);
    EXPECT_EQ(modeOf(db + "-wal") & 0077, 0u);
    svc.stop(BatteryLedger{}, false);
  }
  umask(old);
}

TEST(StoreServiceFiles, AnOldWorldReadableDatabaseLosesAccessForOthers) {
  TempDir d;
  const std::string db = d.file("x.db");
  { std::ofstream(db).flush(); }  // an empty file is an empty SQLite database
  ASSERT_EQ(chmod(db.c_str(), 0644), 0);
  StoreService svc(db, 300);
  EXPECT_EQ(modeOf(db), 0640u);
  svc.stop(BatteryLedger{}, false);
}

TEST(StoreServiceFiles, PrintTokenReadsTheStoredTokenReadOnly) {
  TempDir d;
  const std::string db = d.file("x.db");
  std::string token;
  {
    StoreService svc(db, 300);
    token = svc.token();
    svc.stop(BatteryLedger{}, false);
  }
  std::ostringstream out, err;
  EXPECT_EQ(printTokenMain(std::nullopt, db, out, err), 0);
  EXPECT_EQ(out.str(), token + "\n");
  std::ostringstream out2, err2;
  EXPECT_EQ(printTokenMain(std::nullopt, d.file("none.db"), out2, err2), 1);
  EXPECT_EQ(out2.str(), "");
}

}  // namespace
}  // namespace xr::app
