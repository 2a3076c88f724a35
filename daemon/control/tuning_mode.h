#pragma once
// TuningMode (docs/control.md "SystemID, TuningMode and CVTuningMode"): square-wave
// current setpoint between TUNING_BASE_A and TUNING_BASE_A + waveAmplitude,
// toggling every wavePeriod/2. The score (ISE/T of setpointLimited -
// MeasuredAmps) accumulates only while the setpoint slews slower than
// 1 A/s, so it is independent of the slew rate itself. A record is committed
// to the 50-entry tuningLog on the operator's command (tuning_commit).
#include <array>

#include "core/time.h"
#include "params/constants.h"
#include "params/params.h"

namespace xr {

struct TuningRecord {
  TimeNs t = 0;
  double PidKp = 0.0, PidKi = 0.0, PidKd = 0.0;
  double waveAmplitude = 0.0, wavePeriod = 0.0;
  double score = 0.0;      // ISE / T, A^2
  double scoredSec = 0.0;  // time inside the scoring window
};

class TuningModeRunner {
 public:
  // Square-wave uTargetAmps for this tick (starts on the first call after reset).
  double waveTarget(TimeNs now, const Params& p);
  // Scoring, after the setpoint slew of this tick.
  void score(double setpointLimited, double measuredAmps, double dtSec);
  bool commit(TimeNs now, const Params& p);  // tuning_commit
  void reset();

  bool running() const { return running_; }
  bool highPhase() const { return high_; }
  bool scoringOpen() const { return scoringOpen_; }
  double currentScore() const { return scoredSec_ > 0 ? ise_ / scoredSec_ : 0.0; }
  double scoredSec() const { return scoredSec_; }
  int logCount() const { return logCount_; }
  const TuningRecord& record(int i) const {  // 0 = oldest
    return tuningLog_[static_cast<std::size_t>((logHead_ - logCount_ + i + 2 * k::TUNING_LOG_SIZE) %
                                               k::TUNING_LOG_SIZE)];
  }

 private:
  bool running_ = false, high_ = false, scoringOpen_ = false;  // a run, its HIGH phase, scoring open
  TimeNs start_ = 0;                                           // the run's start (the wave's phase)
  double lastSetpoint_ = 0.0;           // the setpoint of the last score (a step restarts it)
  bool haveLast_ = false;               // a score has run
  double ise_ = 0.0, scoredSec_ = 0.0;  // the squared error integrated, over this long
  std::array<TuningRecord, k::TUNING_LOG_SIZE> tuningLog_{};  // committed runs (a ring)
  int logCount_ = 0, logHead_ = 0;                            // the ring's fill and head
};

}  // namespace xr
