#pragma once
// GpioLibgpiod (docs/install.md, wiring): libgpiod 1.6 lines with consumer
// "xregulatord": field enable (GPIO4) as an output requested with initial
// LOW (field off), buzzer (GPIO21) output initially LOW, BMS and ignition
// inputs with configurable polarity. The DigitalOutput / DigitalInput seams
// are small classes around a requested line; polarity logic is pure
// (`logicalLevel`, `physicalLevel`) and tested on its own.
#include <memory>
#include <string>

#include "config/settings.h"
#include "drivers/hal/outputs.h"

struct gpiod_chip;
struct gpiod_line;

namespace xr {

inline constexpr const char* kGpioConsumer = "xregulatord";

// Physical level for a logical "on" with an active-high/low line.
constexpr int physicalLevel(bool logicalOn, bool activeHigh) noexcept {
  return (logicalOn == activeHigh) ? 1 : 0;
}
// Logical level from a physical one; -1 stays -1 (error).
constexpr int logicalLevel(int physical, bool activeLow) noexcept {
  return physical < 0 ? -1 : ((physical != 0) != activeLow ? 1 : 0);
}

class GpioOutputLine final : public DigitalOutput {
 public:
  GpioOutputLine(gpiod_line* line, bool activeHigh) noexcept : line_(line), activeHigh_(activeHigh) {}
  ~GpioOutputLine() override;
  bool set(bool on) noexcept override;  // logical on/off (polarity applied)
  // For fatal-signal / std::terminate handlers (rt::fatal::addCallback with
  // ctx = this GpioOutputLine): drives the line to its OFF level. libgpiod
  // 1.6 gpiod_line_set_value() builds its request on the stack and issues
  // one ioctl on the line handle: no allocation, no locks.
  static void setOffSignalSafe(void* self) noexcept;

 private:
  gpiod_line* line_;
  bool activeHigh_;
};

class GpioInputLine final : public DigitalInput {
 public:
  GpioInputLine(gpiod_line* line, bool activeLow) noexcept : line_(line), activeLow_(activeLow) {}
  ~GpioInputLine() override;
  int get() noexcept override;

 private:
  gpiod_line* line_;
  bool activeLow_;
};

class GpioLibgpiod {
 public:
  GpioLibgpiod() = default;
  ~GpioLibgpiod();
  GpioLibgpiod(const GpioLibgpiod&) = delete;
  GpioLibgpiod& operator=(const GpioLibgpiod&) = delete;

  // Not RT. Opens the chip (name like "gpiochip0" or a /dev path) and
  // requests the configured lines; on failure `error()` says what to fix and
  // nothing stays requested. The field enable is requested LOW (off) first.
  bool open(const HardwareSettings& hw);
  const std::string& error() const noexcept { return error_; }

  GpioOutputLine* fieldEnable() noexcept { return fieldEnable_.get(); }  // also a DigitalOutput*
  GpioOutputLine* buzzer() noexcept { return buzzer_.get(); }
  // bms()->get(): 1 = "charge disabled" asserted (the level bms_active_low
  // names), 0 = charging allowed, -1 = read error. nullptr when not wired.
  DigitalInput* bms() noexcept { return bms_.get(); }
  // ignition()->get(): 1 = ignition on, 0 = off, -1 = error. nullptr when not wired.
  DigitalInput* ignition() noexcept { return ignition_.get(); }
  void close() noexcept;

 private:
  gpiod_chip* chip_ = nullptr;
  std::unique_ptr<GpioOutputLine> fieldEnable_, buzzer_;
  std::unique_ptr<GpioInputLine> bms_, ignition_;
  std::string error_;
};

// ADS1115 ALERT/RDY as a falling-edge event line (ReadyEdge pacing).
class AdsReadyLine {
 public:
  AdsReadyLine() = default;
  ~AdsReadyLine();
  AdsReadyLine(const AdsReadyLine&) = delete;
  AdsReadyLine& operator=(const AdsReadyLine&) = delete;
  bool open(const std::string& chipName, int line);
  const std::string& error() const noexcept { return error_; }
  // RT path: waits up to `timeoutNs` for an edge. Returns 1 and the kernel
  // timestamp (ns) of the edge, 0 on timeout, -1 on error. The kernel stamps
  // line events with CLOCK_MONOTONIC since Linux 5.7 (CLOCK_REALTIME before):
  // the runtime must compare it with a monotonic Clock, or stamp the edge
  // itself when it returns, for Ads1115Driver::onReadyEdge().
  int wait(long timeoutNs, long long* stampNs) noexcept;
  int fd() const noexcept;
  void close() noexcept;

 private:
  gpiod_chip* chip_ = nullptr;
  gpiod_line* line_ = nullptr;
  std::string error_;
};

}  // namespace xr
