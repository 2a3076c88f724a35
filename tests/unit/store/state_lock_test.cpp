// One daemon per state database (store/state_lock.h): the second holder is
// refused and told who holds it; the lock goes with its holder.
#include "store/state_lock.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

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

TEST_F(StateLockTest, AnUnwritableDirectoryGivesNoLockButNoRefusal) {
  const std::string db = (dir / "missing-dir" / "state.db").string();
  StateLock l(db);
  EXPECT_EQ(l.result(), StateLock::Result::NoLockFile);
  EXPECT_NE(l.message().find("cannot create the lock file"), std::string::npos) << l.message();
}

}  // namespace
}  // namespace xr
