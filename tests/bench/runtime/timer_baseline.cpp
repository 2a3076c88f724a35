// What the platform itself allows (make bench, before the control-loop run):
// a thread with the control thread's scheduling (SCHED_FIFO 80 when
// permitted, memory locked) that only sleeps to absolute 2.5 ms deadlines
// and measures how late it wakes — a minimal cyclictest. If this thread
// misses deadlines, the daemon's overruns on the same machine are the
// platform's (VM vCPU scheduling, non-RT kernel), not the loop's.
// Usage: xr_timer_baseline [SECONDS] [PERIOD_US]
#include <sched.h>
#include <sys/mman.h>
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {
long long nowNs() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<long long>(t.tv_sec) * 1'000'000'000LL + t.tv_nsec;
}
}  // namespace

int main(int argc, char** argv) {
  const int seconds = argc > 1 ? std::atoi(argv[1]) : 20;
  const long long period = (argc > 2 ? std::atoll(argv[2]) : 2500) * 1000LL;
  if (seconds <= 0 || period <= 0) {
    std::fprintf(stderr, "usage: xr_timer_baseline [SECONDS] [PERIOD_US]\n");
    return 64;
  }
  sched_param sp{};
  sp.sched_priority = 80;
  const bool fifo = sched_setscheduler(0, SCHED_FIFO, &sp) == 0;
  const bool locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
  const auto n = static_cast<std::size_t>(seconds * 1'000'000'000LL / period);
  std::vector<long long> late;
  late.reserve(n);
  long long overruns = 0;
  long long next = nowNs();
  for (std::size_t i = 0; i < n; ++i) {
    next += period;
    timespec d{static_cast<time_t>(next / 1'000'000'000LL), static_cast<long>(next % 1'000'000'000LL)};
    clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &d, nullptr);
    const long long l = nowNs() - next;
    late.push_back(l);
    if (l >= period) {  // a whole period missed: skip, as the control loop does
      overruns += l / period;
      next += (l / period) * period;
    }
  }
  std::sort(late.begin(), late.end());
  auto q = [&](double p) {
    return late[std::min(late.size() - 1, static_cast<std::size_t>(p * late.size()))] / 1000;
  };
  std::printf(
      "timer baseline: %d s at %lld us, %s, %s: wake-up lateness p50/p99/max %lld/%lld/%lld us, overruns "
      "%lld\n",
      seconds, period / 1000, fifo ? "SCHED_FIFO 80" : "normal scheduling (SCHED_FIFO not permitted)",
      locked ? "memory locked" : "memory not locked", q(0.50), q(0.99), late.back() / 1000, overruns);
  return 0;
}
