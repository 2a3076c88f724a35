#pragma once
// CVTuningMode (docs/control.md "SystemID, TuningMode and CVTuningMode"):
// square wave on ChargingVoltageTarget (LOW = the normal target, HIGH =
// + cvWaveAmplitudeV) with asymmetric ISE/T scoring and a settle time.
//  HIGH: overshoot beyond CV_HIGH_DEADBAND_V weighted cvKOvershoot,
//        undershoot (during the rise) weighted 1.
//  LOW:  voltage above target weighted 1 (one-sided); undershoot weighted by
//        a ramp from 0 to 1 over CV_LOW_RAMP_SEC after CV_LOW_GRACE_SEC.
// Settle time: from the phase edge until |IBV - target| <= CV_SETTLE_V_THRESH
// for cvConsecutiveReads consecutive ticks. Committed to cvTuningLog on
// cv_tuning_commit.
#include <array>

#include "core/time.h"
#include "params/constants.h"
#include "params/params.h"

namespace xr {

struct CvTuningRecord {
  TimeNs t = 0;
  double VoltageKp = 0.0, VoltageKi = 0.0;
  double cvWaveAmplitudeV = 0.0, cvWavePeriod = 0.0;
  double score = 0.0;       // weighted ISE / T, V^2
  double settleSec = -1.0;  // mean settle time of the phases that settled (-1: none)
};

class CvTuningModeRunner {
 public:
  // Target for this tick from the normal (LOW phase) target.
  double target(TimeNs now, double normalTarget, const Params& p);
  void score(double IBV, double dtSec, const Params& p);
  bool commit(TimeNs now, const Params& p);
  void reset();

  bool running() const { return running_; }
  bool highPhase() const { return high_; }
  double currentScore() const { return T_ > 0 ? ise_ / T_ : 0.0; }
  double lastSettleSec() const { return lastSettleSec_; }
  int logCount() const { return logCount_; }
  const CvTuningRecord& record(int i) const {  // 0 = oldest
    return cvTuningLog_[static_cast<std::size_t>((logHead_ - logCount_ + i + 2 * k::TUNING_LOG_SIZE) %
                                                 k::TUNING_LOG_SIZE)];
  }

 private:
  bool running_ = false, high_ = false, settledThisPhase_ = false;  // a run, its HIGH phase, settled in it
  TimeNs start_ = 0, phaseStart_ = 0, now_ = 0;    // the run's, the phase's start, the last tick
  double target_ = 0.0;                            // the target the wave asks now
  double ise_ = 0.0, T_ = 0.0;                     // the squared error integrated, over this long
  int consecutive_ = 0;                            // samples inside the settle band in a row
  double lastSettleSec_ = -1.0, settleSum_ = 0.0;  // the last settle time, and their sum
  int settleCount_ = 0;                            // settles counted
  std::array<CvTuningRecord, k::TUNING_LOG_SIZE> cvTuningLog_{};  // committed runs (a ring)
  int logCount_ = 0, logHead_ = 0;                                // the ring's fill and head
};

}  // namespace xr
