#pragma once
// Actuator seams: PWM, digital outputs. Linux: sysfs pwmchip and libgpiod.
// Simulated: record every change with its (virtual) time.
namespace xr {

class PwmOutput {
 public:
  virtual ~PwmOutput() = default;
  // 0..100 %. Returns false on an I/O error (the caller drives the safe state).
  virtual bool setDutyPercent(double pct) noexcept = 0;
  virtual bool setEnabled(bool on) noexcept = 0;
};

class DigitalOutput {
 public:
  virtual ~DigitalOutput() = default;
  virtual bool set(bool high) noexcept = 0;
};

class DigitalInput {
 public:
  virtual ~DigitalInput() = default;
  // Logical level after polarity correction; false on error is not allowed:
  // returns -1 on error, 0 or 1 otherwise.
  virtual int get() noexcept = 0;
};

class Watchdog {
 public:
  virtual ~Watchdog() = default;
  virtual bool keepAlive() noexcept = 0;
  // Magic close ('V'): only on a clean stop after the field is off.
  virtual void closeClean() noexcept = 0;
};

}  // namespace xr
