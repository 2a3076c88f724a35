// kill -9 at random moments during a fast checkpoint loop (persistence
// issue): after every kill the database passes integrity_check, the lifetime
// energy never decreases, and nothing acknowledged as committed is lost (the
// loss is bounded by the one checkpoint in flight).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "store/store.h"
#include "store_test_util.h"

namespace xr {
namespace {

using test::kT0;
using test::TempDir;

// The helper's command line. A cross build's test runs under qemu-user
// (`make test-arm64`), which cannot exec an arm binary by itself (no
// binfmt_misc): the helper is then started through the same emulator, a host
// program the kernel runs, and SIGKILL reaches it as before.
std::vector<std::string> helperCommand(const std::string& db) {
  std::vector<std::string> argv;
#ifdef XR_TEST_EMULATOR
  std::istringstream emulator(XR_TEST_EMULATOR);
  for (std::string word; emulator >> word;) argv.push_back(word);
#endif
  argv.push_back(XR_STORE_CRASH_HELPER);
  argv.push_back(db);
  return argv;
}

struct ChildRun {
  double restored = -1.0;       // "R" line
  double lastCommitted = -1.0;  // last "C" line
  int commits = 0;
  std::string errors;
};

// Starts the helper, waits until it acknowledged `commitsFirst` checkpoints
// (so every run really is killed inside the write loop, whatever the load of
// the machine), then waits `delay` more and sends SIGKILL.
ChildRun runAndKill(const std::string& db, int commitsFirst, std::chrono::microseconds delay) {
  int fds[2];
  ChildRun out;
  // Built before fork: the child only execs.
  std::vector<std::string> words = helperCommand(db);
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  if (pipe(fds) != 0) {
    out.errors = "pipe failed";
    return out;
  }
  const pid_t pid = fork();
  if (pid == 0) {
    dup2(fds[1], STDOUT_FILENO);
    close(fds[0]);
    close(fds[1]);
    execv(argv[0], argv.data());
    _exit(127);
  }
  close(fds[1]);
  std::string text;
  char buf[4096];
  ssize_t n;
  int seen = 0;
  while (seen < commitsFirst) {
    n = read(fds[0], buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // the helper ended by itself: reported below
    text.append(buf, static_cast<std::size_t>(n));
    seen = 0;
    for (std::size_t p = text.find("\nC "); p != std::string::npos; p = text.find("\nC ", p + 1)) ++seen;
  }
  std::this_thread::sleep_for(delay);
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  while ((n = read(fds[0], buf, sizeof buf)) > 0 || (n < 0 && errno == EINTR))
    if (n > 0) text.append(buf, static_cast<std::size_t>(n));
  close(fds[0]);
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.size() < 3) continue;  // a line cut by the kill
    if (line[0] == 'R')
      out.restored = std::stod(line.substr(2));
    else if (line[0] == 'C') {
      out.lastCommitted = std::stod(line.substr(2));
      ++out.commits;
    } else if (line[0] == 'E')
      out.errors += line + "\n";
  }
  if (WIFEXITED(status))
    out.errors += "helper exited by itself: " + std::to_string(WEXITSTATUS(status)) + "\n";
  return out;
}

TEST(StoreCrash, KillNineAtRandomMomentsSixtyTimes) {
  TempDir d;
  const std::string db = d.file("crash.db");
  std::mt19937 rng(20261121);
  std::uniform_int_distribution<int> commitsFirst(0, 6);
  std::uniform_int_distribution<int> delayUs(0, 8000);
  double previous = 0.0;  // lifetime energy found after the previous kill
  int totalCommits = 0;
  for (int i = 0; i < 60; ++i) {
    const int atLeast = commitsFirst(rng);
    const ChildRun run = runAndKill(db, atLeast, std::chrono::microseconds(delayUs(rng)));
    EXPECT_GE(run.commits, atLeast) << "run " << i;
    ASSERT_TRUE(run.errors.empty()) << "run " << i << ": " << run.errors;
    totalCommits += run.commits;
    // The helper restored what the previous run left (when it got that far).
    if (run.restored >= 0.0) {
      EXPECT_DOUBLE_EQ(run.restored, previous) << "run " << i;
    }

    Store s;
    const OpenResult r = s.open(db, kT0);
    ASSERT_TRUE(r.ok) << "run " << i << ": " << r.message;
    ASSERT_FALSE(r.recovered) << "run " << i << ": " << r.message;
    ASSERT_EQ(s.integrityCheck(), "ok") << "run " << i;
    const auto saved = s.loadLedger();
    const double now = saved ? saved->ledger.ChargedEnergy_AllTime_Wh : 0.0;
    EXPECT_GE(now, previous) << "lifetime energy decreased across restart " << i;
    if (run.lastCommitted >= 0.0) {
      // Everything acknowledged survived; at most the checkpoint in flight
      // (one step of 1 Wh) is lost, never more.
      EXPECT_GE(now, run.lastCommitted) << "run " << i;
      EXPECT_LE(now, run.lastCommitted + 1.0) << "run " << i;
    }
    if (saved) {
      EXPECT_DOUBLE_EQ(saved->ledger.AlternatorChargedEnergy_AllTime_Wh, now / 2.0)
          << "torn ledger, run " << i;
    }
    previous = now;
  }
  // Every acknowledged commit is in the final value (1 Wh per commit).
  EXPECT_GE(previous, static_cast<double>(totalCommits));
}

}  // namespace
}  // namespace xr
