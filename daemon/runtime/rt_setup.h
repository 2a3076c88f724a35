#pragma once
// Real-time setup of the control thread (docs/architecture.md): SCHED_FIFO at
// the configured priority, mlockall(MCL_CURRENT|MCL_FUTURE), a pre-faulted
// stack, CPU affinity, the thread name. Development runs as a normal user:
// whatever is not permitted is reported (the caller logs a warning) and the
// thread keeps normal scheduling.
#include <string>
#include <vector>

#include "config/settings.h"

namespace xr::rt {

struct RtSetupReport {
  bool named = false;
  bool fifo = false;  // SCHED_FIFO granted
  int priority = 0;   // the priority actually in effect
  bool memoryLocked = false;
  bool stackPrefaulted = false;
  bool pinned = false;                // CPU affinity applied (false also when cpu = -1)
  std::vector<std::string> warnings;  // one line per thing that was refused
  std::string summary() const;        // "SCHED_FIFO 80, memory locked, cpu 3" / "normal scheduling ..."
};

// Name the calling thread (<= 15 chars, Linux limit).
bool setThreadName(const char* name) noexcept;

// Apply the settings to the calling thread. lockMemory=false skips
// mlockall; fifo=false keeps normal scheduling. The simulator at --speed max
// wants neither: it has no deadlines, and a SCHED_FIFO thread that waits for
// its CSV writer with sched_yield() never lets that (normal) thread run on its
// core, so a full-speed run crawled and starved the machine
// (docs/performance.md "Simulator speed").
RtSetupReport setupRealtimeThread(const RuntimeSettings& settings, const char* name, bool lockMemory = true,
                                  bool fifo = true);

// Touch `bytes` of stack so later growth never page-faults in the loop.
void prefaultStack(std::size_t bytes) noexcept;

struct KernelRtInfo {
  bool preemptRt = false;
  std::string how;      // "/sys/kernel/realtime = 1" or "uname: ... PREEMPT_RT ..." or "not detected"
  std::string release;  // uname -r
};
// PREEMPT_RT detection: /sys/kernel/realtime, else the uname version string.
// sysRealtimePath is a seam for tests.
KernelRtInfo detectPreemptRt(const std::string& sysRealtimePath = "/sys/kernel/realtime");

}  // namespace xr::rt
