#include "runtime/rt_setup.h"

#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <sys/utsname.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

namespace xr::rt {

namespace {
std::string errnoText(int e) { return std::string(std::strerror(e)); }
}  // namespace

bool setThreadName(const char* name) noexcept {
  char buf[16] = {};
  std::strncpy(buf, name, sizeof(buf) - 1);
  return pthread_setname_np(pthread_self(), buf) == 0;
}

void prefaultStack(std::size_t bytes) noexcept {
  // volatile so the compiler cannot drop the writes; alloca-free, bounded.
  constexpr std::size_t kChunk = 4096;
  volatile unsigned char* p = static_cast<volatile unsigned char*>(__builtin_alloca(bytes));
  for (std::size_t i = 0; i < bytes; i += kChunk) p[i] = 0;
}

RtSetupReport setupRealtimeThread(const RuntimeSettings& settings, const char* name, bool lockMemory,
                                  bool fifo) {
  RtSetupReport r;
  r.named = setThreadName(name);

  if (lockMemory) {
    if (mlockall(MCL_CURRENT | MCL_FUTURE) == 0) {
      r.memoryLocked = true;
    } else {
      r.warnings.push_back("mlockall(MCL_CURRENT|MCL_FUTURE) refused (" + errnoText(errno) +
                           "): page faults may delay the control loop; run as the service user with "
                           "LimitMEMLOCK=infinity or CAP_IPC_LOCK");
    }
  }
  prefaultStack(256 * 1024);
  r.stackPrefaulted = true;

  if (settings.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(settings.cpu, &set);
    const int e = pthread_setaffinity_np(pthread_self(), sizeof(set), &set);
    if (e == 0)
      r.pinned = true;
    else
      r.warnings.push_back("CPU affinity to cpu " + std::to_string(settings.cpu) + " refused (" +
                           errnoText(e) + ")");
  }

  if (!fifo) return r;
  const int lo = sched_get_priority_min(SCHED_FIFO);
  const int hi = sched_get_priority_max(SCHED_FIFO);
  sched_param sp{};
  sp.sched_priority = std::clamp(settings.rt_priority, lo, hi);
  const int e = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
  if (e == 0) {
    r.fifo = true;
    r.priority = sp.sched_priority;
  } else {
    r.warnings.push_back("SCHED_FIFO priority " + std::to_string(sp.sched_priority) + " refused (" +
                         errnoText(e) +
                         "): the control thread runs with normal scheduling (grant CAP_SYS_NICE or "
                         "LimitRTPRIO in the service unit)");
  }
  return r;
}

std::string RtSetupReport::summary() const {
  std::string s = fifo ? "SCHED_FIFO " + std::to_string(priority) : std::string("normal scheduling");
  s += memoryLocked ? ", memory locked" : ", memory not locked";
  if (stackPrefaulted) s += ", stack pre-faulted";
  s += pinned ? ", pinned" : ", not pinned";
  return s;
}

KernelRtInfo detectPreemptRt(const std::string& sysRealtimePath) {
  KernelRtInfo info;
  utsname u{};
  std::string version;
  if (uname(&u) == 0) {
    info.release = u.release;
    version = u.version;
  }
  std::ifstream f(sysRealtimePath);
  int flag = 0;
  if (f && (f >> flag)) {
    info.preemptRt = flag == 1;
    info.how = sysRealtimePath + " = " + std::to_string(flag);
    return info;
  }
  if (version.find("PREEMPT_RT") != std::string::npos || version.find("PREEMPT RT") != std::string::npos) {
    info.preemptRt = true;
    info.how = "uname -v: " + version;
  } else {
    info.how = "not detected (" + sysRealtimePath + " absent, uname -v: " + version + ")";
  }
  return info;
}

}  // namespace xr::rt
