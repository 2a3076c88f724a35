#include "app/control_thread.h"

#include <spdlog/spdlog.h>

#include <chrono>
#include <exception>

#include "runtime/fatal_guard.h"

namespace xr::app {

ControlThread::ControlThread(rt::ControlLoop& loop, rt::ControlCycle& cycle, const RuntimeSettings& runtime,
                             bool realtime)
    : loop_(loop), cycle_(cycle) {
  thread_ = std::thread([this, runtime, realtime] { body(runtime, realtime); });
  while (!ready_) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  spdlog::info("control thread: {} period {} us", report_.summary(), runtime.control_period_us);
  for (const auto& w : report_.warnings) spdlog::warn("control thread: {}", w);
}

ControlThread::~ControlThread() {
  if (!thread_.joinable()) return;
  loop_.requestAbort();
  thread_.join();
}

void ControlThread::body(const RuntimeSettings& runtime, bool realtime) {
  report_ = rt::setupRealtimeThread(runtime, "xr-control", /*lockMemory=*/realtime, /*fifo=*/realtime);
  ready_ = true;
  rt::fatal::installAltStackForThisThread();
  try {
    loop_.run();
  } catch (const std::exception& e) {
    error_ = e.what();
    failed_ = true;
  } catch (...) {
    error_ = "unknown exception";
    failed_ = true;
  }
  if (failed_) {
    cycle_.driveSafeState();
    rt::fatal::driveSafeNow();
  }
}

}  // namespace xr::app
