#pragma once
// Simulation output mirror (`--sim-outputs FILE`): the last PWM duty, field
// enable and buzzer state, rewritten in place as one fixed-width line every
// time an output changes, so tests can read back the final state after the
// daemon ends by any path:
//
//   duty_pct=  0.000 enable=0 buzzer=0 via=run     \n
//
// `via` says who wrote it last: run (the control cycle), stop (the clean stop
// path, after the field was turned off), fatal (a fatal signal,
// std::terminate or an escaped exception; written async-signal-safely).
// MirroredPwm / MirroredDigitalOutput decorate the simulated outputs.
#include <atomic>
#include <string>

#include "drivers/hal/outputs.h"

namespace xr::rt {

class OutputMirror {
 public:
  static constexpr std::size_t kLineLen = 48;

  // Opens (creates/truncates) path; throws std::runtime_error on failure.
  explicit OutputMirror(const std::string& path);
  ~OutputMirror();
  OutputMirror(const OutputMirror&) = delete;
  OutputMirror& operator=(const OutputMirror&) = delete;

  void setDuty(double pct) noexcept;
  void setEnable(bool on) noexcept;
  void setBuzzer(bool on) noexcept;
  // Rewrite the line with via=stop (clean stop path, after the field is off).
  void markStopped() noexcept;
  // Register the async-signal-safe "duty 0, enable 0, via=fatal" write.
  void registerFatalAction();

  int fd() const noexcept { return fd_; }
  // The line for these values (exactly kLineLen bytes, '\n' last).
  static std::string formatLine(double duty, bool enable, bool buzzer, const char* via);

 private:
  void write(const char* via) noexcept;
  int fd_ = -1;
  std::atomic<double> duty_{0.0};
  std::atomic<bool> enable_{false};
  std::atomic<bool> buzzer_{false};
  char fatalLine_[kLineLen + 1] = {};
};

class MirroredPwm final : public PwmOutput {
 public:
  MirroredPwm(PwmOutput& inner, OutputMirror& mirror) : inner_(inner), mirror_(mirror) {}
  bool setDutyPercent(double pct) noexcept override {
    const bool ok = inner_.setDutyPercent(pct);
    if (ok) mirror_.setDuty(pct);
    return ok;
  }
  bool setEnabled(bool on) noexcept override { return inner_.setEnabled(on); }

 private:
  PwmOutput& inner_;
  OutputMirror& mirror_;
};

class MirroredDigitalOutput final : public DigitalOutput {
 public:
  enum class Role { FieldEnable, Buzzer };
  MirroredDigitalOutput(DigitalOutput& inner, OutputMirror& mirror, Role role)
      : inner_(inner), mirror_(mirror), role_(role) {}
  bool set(bool high) noexcept override {
    const bool ok = inner_.set(high);
    if (ok) {
      if (role_ == Role::FieldEnable) mirror_.setEnable(high);
      else mirror_.setBuzzer(high);
    }
    return ok;
  }

 private:
  DigitalOutput& inner_;
  OutputMirror& mirror_;
  Role role_;
};

}  // namespace xr::rt
