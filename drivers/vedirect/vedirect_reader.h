#pragma once
// VE.Direct reader (docs/install.md, wiring): a non-RT thread opens the serial port
// (termios 19200 8N1, raw), parses blocks and publishes {current A, voltage V,
// ppv W, stamp} through a SeqLock (latest(): status, tests) and, with each new
// block, to its sink, which writes the control cycle's hand-off from this
// thread (Inputs::VictronCurrent/VictronVoltage/solarPowerW; BatteryCurrentSource
// = 3 and solar energy). Unplug (read error/EOF/hang-up) closes the port and
// re-opens it every `reopenPeriod`.
#include <atomic>
#include <functional>
#include <string>
#include <thread>

#include "core/seqlock.h"
#include "core/time.h"
#include "drivers/vedirect/vedirect_parser.h"

namespace xr {

struct VeDirectSample {
  double currentA = 0.0;  // + = charging
  double voltageV = 0.0;
  double ppvW = 0.0;
  bool hasCurrent = false, hasVoltage = false, hasPpv = false;
  TimeNs stamp = 0;  // monotonic time of the last valid block (0 = never)
  std::uint32_t frames = 0;
  std::uint32_t badChecksums = 0;
  bool portOpen = false;
};

// Configures an open tty fd: 19200 baud, 8N1, raw, no flow control. 0 or errno.
int configureVeDirectTty(int fd) noexcept;

class VeDirectReader {
 public:
  using NowFn = std::function<TimeNs()>;
  explicit VeDirectReader(std::string port, NowFn now = {}, TimeNs reopenPeriod = 2'000'000'000);
  ~VeDirectReader();
  VeDirectReader(const VeDirectReader&) = delete;
  VeDirectReader& operator=(const VeDirectReader&) = delete;

  // Called on the reader's thread with the sample after each new valid
  // block, after latest() has it: the consumer's own hand-off is written
  // once, by this thread. Set before start().
  using Sink = std::function<void(const VeDirectSample&)>;
  void onSample(Sink sink) { sink_ = std::move(sink); }

  void start();
  void stop() noexcept;
  // RT-safe: the newest published sample.
  VeDirectSample latest() const noexcept { return out_.load(); }
  std::uint64_t version() const noexcept { return out_.version(); }

 private:
  void run();
  static void onFrame(void* ctx, const vedirect::Frame& f);
  std::string port_;
  NowFn now_;
  TimeNs reopenPeriod_;
  vedirect::Parser parser_;
  VeDirectSample state_;
  SeqLock<VeDirectSample> out_;
  Sink sink_;
  std::atomic<bool> stop_{false};
  int wakeFd_[2] = {-1, -1};
  std::thread thread_;
};

}  // namespace xr
