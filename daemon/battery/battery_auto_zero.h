#pragma once
// AltCurrentAutoZero: the alternator current sensor's zero, measured with the
// field held off (docs/batteries.md "Auto-zero"). It owns the zero itself,
// the trigger state (hourly timer, temperature baseline) and the sampling
// window. Pure: no clock, no I/O; time comes from AutoZeroInput::now.
#include <cstdint>

#include "core/events.h"
#include "core/inputs.h"
#include "core/time.h"

namespace xr {

namespace battery_k {
// Field held off this long for an auto-zero (the first 2 s are the settle
// window and are not sampled). 10 s gives ~8 s of samples: at the ADS1115's
// CH1 rate that is hundreds of samples, enough to average Hall noise away,
// while a 10 s charging gap once an hour costs < 0.3 % of charge.
inline constexpr std::int64_t AUTO_ZERO_DURATION_MS = 10000;
// Largest Hall zero offset accepted from an auto-zero. A bigger value means
// current was really flowing (field not off, wiring fault): keep the old zero.
inline constexpr double AUTO_ZERO_MAX_OFFSET_A = 10.0;
}  // namespace battery_k

// What one tick hands the auto-zero.
struct AutoZeroInput {
  TimeNs now = 0;
  bool enabled = false;     // AutoAltCurrentZero
  double tempF = kNoValue;  // the alternator temperature in use (NaN: none)
  double rpm = kNoValue;    // engine speed: no auto-zero below AUTO_ZERO_MIN_RPM
  Reading altCurrentRaw;    // raw CH1 (A), sampled while the window runs
};

class AltCurrentAutoZero {
 public:
  // The hourly timer starts at the monitor's first tick.
  void begin(TimeNs now) noexcept { lastRun_ = now; }
  // Starts a window when enabled, not running, RPM >= AUTO_ZERO_MIN_RPM and
  // (the hourly interval elapsed or the temperature moved >= 20 degF since
  // the last run). The temperature baseline is the first valid temperature.
  // Emits AutoZeroStarted. True when a window started.
  bool checkTriggers(const AutoZeroInput& in, EventBatch& ev) noexcept;
  // While a window runs: samples fresh CH1 after the settle time and returns
  // true (the caller holds the field off). At its end sets the zero to the
  // mean (detail 0), keeps the old one with no samples (1) or an
  // implausible mean (2), emits AutoZeroDone and returns false.
  bool update(const AutoZeroInput& in, EventBatch& ev) noexcept { return active_ && sample(in, ev); }
  bool active() const noexcept { return active_; }

  double zero() const noexcept { return zero_; }
  double corrected(double rawAmps) const noexcept { return rawAmps - zero_; }
  void reset() noexcept { zero_ = 0.0; }
  // A saved zero: NaN restores 0, beyond ±AUTO_ZERO_MAX_OFFSET_A is clamped.
  void restore(double zero) noexcept;

 private:
  bool sample(const AutoZeroInput& in, EventBatch& ev) noexcept;

  double zero_ = 0.0;      // DynamicAltCurrentZero: subtracted from raw CH1 (A)
  bool active_ = false;    // a field-off window is running
  TimeNs start_ = 0;       // when the running window started
  TimeNs lastRun_ = 0;     // the last window's end (or the first tick): the hourly timer
  bool haveTemp_ = false;  // lastTemp_ holds a valid temperature
  double lastTemp_ = 0.0;  // temperature at the last run (degF): the 20 degF trigger
  double sum_ = 0.0;       // CH1 samples summed in the running window (A)
  long count_ = 0;         // samples in sum_
};

}  // namespace xr
