#include "runtime/output_mirror.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "runtime/fatal_guard.h"

namespace xr::rt {
namespace {

std::string tempPath(const char* tag) {
  return ::testing::TempDir() + "xr_mirror_" + tag + "_" + std::to_string(getpid());
}

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

struct NullPwm final : PwmOutput {
  bool setDutyPercent(double) noexcept override { return ok; }
  bool setEnabled(bool) noexcept override { return ok; }
  bool ok = true;
};
struct NullOut final : DigitalOutput {
  bool set(bool) noexcept override { return ok; }
  bool ok = true;
};

TEST(OutputMirror, LinesAreFixedWidth) {
  EXPECT_EQ(OutputMirror::formatLine(100.0, true, true, "fatal").size(), OutputMirror::kLineLen);
  EXPECT_EQ(OutputMirror::formatLine(0.0, false, false, "run").substr(0, 40),
            std::string("duty_pct=  0.000 enable=0 buzzer=0 via=r"));
}

TEST(OutputMirror, MirrorsTheLastSuccessfulWrites) {
  const auto path = tempPath("writes");
  {
    OutputMirror m(path);
    NullPwm pwm;
    NullOut en, bz;
    MirroredPwm mp(pwm, m);
    MirroredDigitalOutput me(en, m, MirroredDigitalOutput::Role::FieldEnable);
    MirroredDigitalOutput mb(bz, m, MirroredDigitalOutput::Role::Buzzer);
    mp.setDutyPercent(42.5);
    me.set(true);
    mb.set(true);
    EXPECT_EQ(slurp(path), OutputMirror::formatLine(42.5, true, true, "run"));
    pwm.ok = false;  // a failed write is not mirrored
    mp.setDutyPercent(80.0);
    EXPECT_EQ(slurp(path), OutputMirror::formatLine(42.5, true, true, "run"));
    me.set(false);
    mp.setDutyPercent(0.0);
    pwm.ok = true;
    mp.setDutyPercent(0.0);
    m.markStopped();
    EXPECT_EQ(slurp(path), OutputMirror::formatLine(0.0, false, true, "stop"));
  }
  std::remove(path.c_str());
}

TEST(OutputMirror, ThrowsAClearErrorWhenTheFileCannotBeOpened) {
  try {
    OutputMirror m("/nonexistent-dir/x/outputs");
    FAIL() << "expected an exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x/outputs"), std::string::npos);
  }
}

// A fatal signal in a child: the handler rewrites the mirror to duty 0 /
// enable 0 / via=fatal before the process dies.
void crashWithFieldOn(const std::string& path, int how) {
  fatal::clearActions();
  OutputMirror m(path);
  m.setDuty(75.0);
  m.setEnable(true);
  m.registerFatalAction();
  fatal::install();
  if (how == 0) raise(SIGSEGV);
  if (how == 1) std::abort();
  if (how == 2) std::terminate();
  if (how == 3) raise(SIGBUS);
}

class FatalPaths : public ::testing::TestWithParam<int> {};

TEST_P(FatalPaths, DriveTheMirroredOutputsToZero) {
#ifdef XR_TEST_EMULATOR
  // "threadsafe" re-executes the test binary, an arm binary that qemu-user
  // cannot exec (no binfmt_misc): fork only. Each ctest runs one test in its
  // own process, so no other thread is running here.
  GTEST_FLAG_SET(death_test_style, "fast");
#else
  GTEST_FLAG_SET(death_test_style, "threadsafe");
#endif
  // No pid in the name: the threadsafe death-test child is a new process.
  const auto path = ::testing::TempDir() + "xr_mirror_fatal_" + std::to_string(GetParam());
  EXPECT_DEATH(crashWithFieldOn(path, GetParam()), "");
  EXPECT_EQ(slurp(path), OutputMirror::formatLine(0.0, false, false, "fatal"));
  std::remove(path.c_str());
}

INSTANTIATE_TEST_SUITE_P(Signals, FatalPaths, ::testing::Values(0, 1, 2, 3));

TEST(FatalGuard, DriveSafeNowRunsRegisteredCallbacksAndWrites) {
  fatal::clearActions();
  static int calls = 0;
  calls = 0;
  ASSERT_TRUE(fatal::addCallback([](void* ctx) noexcept { *static_cast<int*>(ctx) += 1; }, &calls));
  const auto path = tempPath("cb");
  {
    OutputMirror m(path);
    m.setDuty(10);
    m.registerFatalAction();
    const int before = fatal::timesDriven();
    fatal::driveSafeNow();
    EXPECT_EQ(fatal::timesDriven(), before + 1);
  }
  EXPECT_EQ(calls, 1);
  EXPECT_EQ(slurp(path), OutputMirror::formatLine(0.0, false, false, "fatal"));
  fatal::clearActions();
  std::remove(path.c_str());
}

TEST(FatalGuard, RejectsTooManyActionsAndOversizedWrites) {
  fatal::clearActions();
  char big[fatal::kMaxBytes + 1] = {};
  EXPECT_FALSE(fatal::addWrite(1, big, sizeof(big), 0));
  EXPECT_FALSE(fatal::addWrite(-1, big, 1, 0));
  for (std::size_t i = 0; i < fatal::kMaxActions; ++i) EXPECT_TRUE(fatal::addWrite(1, big, 0, 0));
  EXPECT_FALSE(fatal::addWrite(1, big, 0, 0));
  fatal::clearActions();
}

}  // namespace
}  // namespace xr::rt
