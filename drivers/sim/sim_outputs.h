#pragma once
// Simulated actuators and discrete inputs behind the drivers/hal seams. Each
// output records every change with its (virtual) time, so tests can assert
// "the field enable went LOW at t" and the plant can read the levels.
// The log keeps the newest `capacity` changes (a long run changes the duty
// every tick) in a ring; counts cover the whole run.
#include <cstddef>
#include <cstdint>
#include <memory>

#include "core/time.h"
#include "drivers/hal/outputs.h"

namespace xr::sim {

struct Change {
  TimeNs t = 0;
  double value = 0.0;
};

// A ring of the newest `capacity` changes, allocated when the log is made:
// a long run that changes the duty every tick costs two stores and a wrap
// per change (no deque node push and pop, no vector growth). Never at the
// first change: that is the control thread's tick, under mlockall, and
// faulting in a 1 MiB ring there cost milliseconds of its CPU at the first
// engine start (docs/performance.md, the soak's RSS step and its worst tick).
class ChangeLog {
 public:
  explicit ChangeLog(std::size_t capacity = 1u << 16)
      : cap_(capacity), ring_(capacity > 0 ? std::make_unique<Change[]>(capacity) : nullptr) {}
  void record(TimeNs t, double v) noexcept {
    ++count_;
    if (cap_ == 0) return;
    ring_[head_] = {t, v};
    head_ = head_ + 1 == cap_ ? 0 : head_ + 1;
  }
  // The kept changes, oldest first: [0, size()). The ring holds the newest
  // min(count, capacity) changes, so its fill level is not tracked apart.
  std::size_t size() const noexcept { return count_ < cap_ ? static_cast<std::size_t>(count_) : cap_; }
  bool empty() const noexcept { return size() == 0; }
  const Change& operator[](std::size_t i) const noexcept {
    const std::size_t k = (count_ < cap_ ? 0 : head_) + i;  // the oldest is at head_ once full
    return ring_[k < cap_ ? k : k - cap_];
  }
  const Change& back() const noexcept { return ring_[head_ == 0 ? cap_ - 1 : head_ - 1]; }
  std::uint64_t count() const noexcept { return count_; }

 private:
  std::size_t cap_;
  std::unique_ptr<Change[]> ring_;
  std::size_t head_ = 0;  // where the next change goes
  std::uint64_t count_ = 0;
};

class SimPwm final : public PwmOutput {
 public:
  explicit SimPwm(const TimeNs* now) : now_(now) {}
  bool setDutyPercent(double pct) noexcept override;
  bool setEnabled(bool on) noexcept override;
  double duty() const noexcept { return duty_; }
  bool enabled() const noexcept { return enabled_; }
  // Effective drive 0..1: duty while the PWM channel is enabled.
  double drive() const noexcept { return enabled_ ? duty_ / 100.0 : 0.0; }
  void setFailing(bool f) noexcept { failing_ = f; }
  const ChangeLog& dutyLog() const noexcept { return dutyLog_; }

 private:
  const TimeNs* now_;
  double duty_ = 0.0;
  bool enabled_ = true;  // a started sysfs channel is enabled
  bool failing_ = false;
  ChangeLog dutyLog_, enableLog_;
};

class SimDigitalOutput final : public DigitalOutput {
 public:
  explicit SimDigitalOutput(const TimeNs* now) : now_(now) {}
  bool set(bool high) noexcept override;
  bool level() const noexcept { return level_; }
  const ChangeLog& log() const noexcept { return log_; }

 private:
  const TimeNs* now_;
  bool level_ = false;
  ChangeLog log_;
};

// A discrete input the world drives (ignition, BMS charge-enable line).
class SimDigitalInput final : public DigitalInput {
 public:
  explicit SimDigitalInput(bool level = true) : level_(level) {}
  int get() noexcept override { return level_ ? 1 : 0; }
  void setLevel(bool l) noexcept { level_ = l; }

 private:
  bool level_;
};

class SimWatchdog final : public Watchdog {
 public:
  explicit SimWatchdog(const TimeNs* now, TimeNs timeout = fromSec(16.0)) : now_(now), timeout_(timeout) {}
  bool keepAlive() noexcept override;
  void closeClean() noexcept override;
  std::uint64_t kicks() const noexcept { return kicks_; }
  // True if at time t the board would have been reset (no kick for timeout).
  bool wouldHaveFired(TimeNs t) const noexcept { return kicks_ > 0 && !closed_ && t - last_ > timeout_; }
  TimeNs longestGap() const noexcept { return longestGap_; }

 private:
  const TimeNs* now_;
  TimeNs timeout_;
  TimeNs last_ = 0;
  TimeNs longestGap_ = 0;
  std::uint64_t kicks_ = 0;
  bool closed_ = false;
};

}  // namespace xr::sim
