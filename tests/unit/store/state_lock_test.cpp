// One daemon per state database (store/state_lock.h): the second holder is
// refused and told who holds it; the lock goes with its holder.
#include "store/state_lock.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>

namespace xr {
namespace {

struct StateLockTest : ::testing::Test {
  std::filesystem::path dir = std::filesystem::temp_directory_path() /
                              ("xr-lock-" + std::to_string(::getpid()) + "-" +
                               ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }
};

TEST_F(StateLockTest, ASecondHolderOfTheSameDatabaseIsRefusedWithTheHoldersPid) {
  const std::string db = (dir / "state.db").string();
  StateLock first(db);
  ASSERT_EQ(first.result(), StateLock::Result::Held) << first.message();
  StateLock second(db);
  EXPECT_EQ(second.result(), StateLock::Result::HeldByOther);
  EXPECT_NE(second.message().find("pid " + std::to_string(::getpid())), std::string::npos)
      << second.message();
}

TEST_F(StateLockTest, TheLockIsFreeOnceItsHolderIsGone) {
  const std::string db = (dir / "state.db").string();
  { StateLock first(db); }
  StateLock again(db);
  EXPECT_EQ(again.result(), StateLock::Result::Held);
}

TEST_F(StateLockTest, TwoDatabasesInOneDirectoryDoNotShareALock) {
  StateLock a((dir / "a.db").string());
  StateLock b((dir / "b.db").string());
  EXPECT_EQ(a.result(), StateLock::Result::Held);
  EXPECT_EQ(b.result(), StateLock::Result::Held);
}

// The reproducer: `--state-db dlink.db` where dlink.db links to the running
// daemon's d.db started a second daemon on the same file.
TEST_F(StateLockTest, ASymlinkToAHeldDatabaseIsRefused) {
  const auto db = dir / "d.db";
  { std::ofstream(db) << "x"; }
  std::filesystem::create_symlink(db, dir / "dlink.db");
  auto first = std::make_unique<StateLock>(db.string());
  ASSERT_EQ(first->result(), StateLock::Result::Held) << first->message();
  StateLock second((dir / "dlink.db").string());
  EXPECT_EQ(second.result(), StateLock::Result::HeldByOther);
  EXPECT_NE(second.message().find("(the file " + std::filesystem::canonical(db).string() + ")"),
            std::string::npos)
      << second.message();
  // And the other way round: the link first, then the real name.
  first.reset();
  first = std::make_unique<StateLock>((dir / "dlink.db").string());
  ASSERT_EQ(first->result(), StateLock::Result::Held);
  EXPECT_EQ(StateLock(db.string()).result(), StateLock::Result::HeldByOther);
}

TEST_F(StateLockTest, ADatabaseReachedThroughASymlinkedDirectoryIsRefused) {
  std::filesystem::create_directories(dir / "real");
  std::filesystem::create_directory_symlink(dir / "real", dir / "alias");
  StateLock first((dir / "real" / "state.db").string());  // not created yet: a first start
  ASSERT_EQ(first.result(), StateLock::Result::Held);
  EXPECT_EQ(StateLock((dir / "alias" / "state.db").string()).result(), StateLock::Result::HeldByOther);
  EXPECT_EQ(StateLock((dir / "alias" / ".." / "real" / "state.db").string()).result(),
            StateLock::Result::HeldByOther);
}

TEST_F(StateLockTest, AnUnwritableDirectoryGivesNoLockButNoRefusal) {
  const std::string db = (dir / "missing-dir" / "state.db").string();
  StateLock l(db);
  EXPECT_EQ(l.result(), StateLock::Result::NoLockFile);
  EXPECT_NE(l.message().find("cannot create the lock file"), std::string::npos) << l.message();
}

}  // namespace
}  // namespace xr
