#pragma once
// Pid: our own PID with the semantics docs/control.md expects of the specification's
// PID_v1_xeng library (Brett Beauregard's PID_v1 plus extensions):
//  - DIRECT / REVERSE action (REVERSE: rising input raises the output),
//  - output limits clamp both the output and the integrator (outputSum),
//  - MANUAL / AUTOMATIC; MANUAL -> AUTOMATIC initialises outputSum from the
//    current output and lastInput from the current input (bumpless),
//  - derivative on measurement (no derivative kick on setpoint steps),
//  - trackAppliedOutput(): back-calculation anti-windup pulling outputSum
//    toward the actuator's applied value at `trackingGain` per second,
//  - resetIntegratorTo(), and P/I/D term read-back for telemetry.
// Unlike the library, compute() takes the real dt of this compute, so the
// same gains give the same response at any tick rate (the library assumes its
// nominal SampleTime). Plain state, no allocation.
#include <algorithm>
#include <cmath>

namespace xr {

class Pid {
 public:
  enum Direction { DIRECT, REVERSE };
  enum Mode { MANUAL, AUTOMATIC };

  Pid(double kp, double ki, double kd, Direction dir);

  void setTunings(double kp, double ki, double kd) noexcept {
    if (kp < 0 || ki < 0 || kd < 0) return;  // library contract: gains are magnitudes
    kp_ = kp;
    ki_ = ki;
    kd_ = kd;
  }
  void setOutputLimits(double min, double max) noexcept {
    if (!(min < max)) return;
    outMin_ = min;
    outMax_ = max;
    output = clampOut(output);
    outputSum_ = clampOut(outputSum_);
  }
  void setTrackingGain(double perSecond) noexcept { trackingGain_ = perSecond; }
  void setMode(Mode mode) noexcept;  // bumpless on MANUAL -> AUTOMATIC
  Mode mode() const noexcept { return mode_; }

  // Runs one compute with the real elapsed time. Returns false (and changes
  // nothing) in MANUAL or when dtSec <= 0 or the input is not finite.
  // Real-time thread, every tick: neither allocates nor blocks (docs/architecture.md "Threads").
  bool compute(double dtSec) noexcept {
    if (mode_ != AUTOMATIC || !(dtSec > 0.0) || !std::isfinite(input) || !std::isfinite(setpoint))
      return false;
    const double sign = direction_ == DIRECT ? 1.0 : -1.0;
    const double error = setpoint - input;
    const double dInput = input - lastInput_;
    outputSum_ = clampOut(outputSum_ + sign * ki_ * error * dtSec);
    pTerm_ = sign * kp_ * error;
    dTerm_ = -sign * kd_ * dInput / dtSec;  // on measurement: no kick on setpoint steps
    output = clampOut(pTerm_ + outputSum_ + dTerm_);
    lastInput_ = input;
    return true;
  }

  // Anti-windup (back-calculation): outputSum += min(1, Kt*dt) *
  // ((applied - P - D) - outputSum). Neutral while the output is not clamped.
  void trackAppliedOutput(double applied, double dtSec) noexcept {
    if (!(dtSec > 0.0) || !std::isfinite(applied)) return;
    // Back-calculation: pulls outputSum toward the value that, with the present
    // P and D terms, reproduces what the actuator actually applied. Zero effect
    // while the output is not clamped downstream (applied == output), so the
    // linear loop keeps exactly its Kp/Ki/Kd.
    const double a = std::min(1.0, trackingGain_ * dtSec);
    const double wanted = applied - pTerm_ - dTerm_;
    outputSum_ = clampOut(outputSum_ + a * (wanted - outputSum_));
  }
  // Parks the integrator itself toward `target` at Kt per second (T0's
  // implied-penalty anti-windup: "parks it near where the constraints already
  // imply", without making the penalty act while the temperature is low).
  void trackIntegratorTo(double target, double dtSec) noexcept;
  // Pins the integrator (and the output) to v, e.g. every MANUAL tick.
  void resetIntegratorTo(double v) noexcept {
    if (!std::isfinite(v)) return;
    outputSum_ = clampOut(v);
    output = outputSum_;
    lastInput_ = std::isfinite(input) ? input : lastInput_;
  }

  double pTerm() const noexcept { return pTerm_; }
  double iTerm() const noexcept { return outputSum_; }
  double dTerm() const noexcept { return dTerm_; }

  // The library's three bound variables, held here instead of by pointer.
  double input = 0.0;
  double output = 0.0;
  double setpoint = 0.0;

 private:
  double clampOut(double v) const noexcept { return std::clamp(v, outMin_, outMax_); }
  double kp_, ki_, kd_;                   // the gains, per second
  Direction direction_;                   // DIRECT or REVERSE action
  Mode mode_ = MANUAL;                    // MANUAL: the output is written from outside
  double outMin_ = 0.0, outMax_ = 100.0;  // the output bounds
  double trackingGain_ = 0.0;             // per second: how fast the integrator tracks the applied output
  double outputSum_ = 0.0;                // the integrator
  double lastInput_ = 0.0;                // the last input (derivative on measurement)
  double pTerm_ = 0.0, dTerm_ = 0.0;      // the last compute's terms (telemetry)
};

}  // namespace xr
