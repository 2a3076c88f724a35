#pragma once
// The xr-control thread (docs/architecture.md "Threads"): SCHED_FIFO on a
// board, the control loop, and the safe state when the loop throws. The
// destructor aborts and joins a thread still running, so no way out of
// Daemon::run leaves it behind.
#include <atomic>
#include <string>
#include <thread>

#include "config/settings.h"
#include "runtime/control_cycle.h"
#include "runtime/control_loop.h"
#include "runtime/rt_setup.h"

namespace xr::app {

class ControlThread {
 public:
  // Starts the thread and returns once its real-time set-up is done (said in
  // the journal). `realtime`: SCHED_FIFO and locked memory (a board, or a
  // paced simulation).
  ControlThread(rt::ControlLoop& loop, rt::ControlCycle& cycle, const RuntimeSettings& runtime,
                bool realtime);
  ~ControlThread();
  ControlThread(const ControlThread&) = delete;
  ControlThread& operator=(const ControlThread&) = delete;

  void join() {
    if (thread_.joinable()) thread_.join();
  }
  // The loop threw: the field was driven LOW on the thread; error() says why.
  bool failed() const { return failed_; }
  const std::string& error() const { return error_; }

 private:
  void body(const RuntimeSettings& runtime, bool realtime);

  rt::ControlLoop& loop_;
  rt::ControlCycle& cycle_;
  rt::RtSetupReport report_;
  std::atomic<bool> ready_{false};
  std::atomic<bool> failed_{false};
  std::string error_;
  std::thread thread_;
};

}  // namespace xr::app
