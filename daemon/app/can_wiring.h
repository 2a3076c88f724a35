#pragma once
// The CAN service on a board (docs/integrations.md): the xr-can thread polls
// canlink::CanService every 10 ms, off the RT control thread. It opens
// [can] bms_interface on SocketCAN (retried with backoff when missing: the
// regulator runs on, with the stale fallback) and writes --can-log. In
// --sim the one sim rig runs the same service on the loop's thread
// (sim_rig/sim_can_rig.h); this file is the board's half.
#include <atomic>
#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <thread>

#include "canlink/can_service.h"
#include "config/settings.h"
#include "drivers/hal/clock.h"
#include "runtime/handoffs.h"

namespace xr::app {

// Opens --can-log for writing; throws std::runtime_error naming the file and
// the OS error. The daemon opens it before anything runs and stops with
// kExitConfig when it cannot, like --telemetry-csv.
std::unique_ptr<std::ofstream> openCanLog(const std::string& path);

class CanThread {
 public:
  // Starts the thread; `clock` is the control loop's (limits are stamped on it).
  CanThread(const Settings& s, rt::Handoffs& h, Clock& clock, std::unique_ptr<std::ofstream> log);
  ~CanThread();
  CanThread(const CanThread&) = delete;
  CanThread& operator=(const CanThread&) = delete;

 private:
  void run();
  Clock& clock_;
  std::unique_ptr<std::ofstream> log_;
  std::unique_ptr<can::CandumpSink> sink_;
  canlink::CanService service_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Null when there is nothing to do (no [can] interface and no --can-log).
// `canLog`: --can-log, already open (null = none).
std::unique_ptr<CanThread> startCanThread(const Settings& s, rt::Handoffs& h, Clock& clock,
                                          std::unique_ptr<std::ofstream> canLog);

}  // namespace xr::app
