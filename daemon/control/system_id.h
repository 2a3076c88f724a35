#pragma once
// SystemID (docs/control.md "SystemID, TuningMode and CVTuningMode"): plant-delay step test. The duty is
// held at sysIDBaseDuty for sysIDDurationMs, then stepped to sysIDStepDuty for
// sysIDDurationMs, with the governor in GOV_BYPASS_SLEW. The alternator
// current response gives dead time (10 % of the final change), rise time
// (10 % -> 90 %) and slope (A/s over the rise). Samples go to a fixed buffer
// (decimated to fit), so the test never allocates.
#include <array>

#include "core/time.h"
#include "params/params.h"

namespace xr {

struct SystemIdSnapshot {
  bool autoRunning = false;  // sysMode AUTO in MODE_NORMAL_AUTO_PID
  double setpointLimited = 0.0;
  double lastAppliedDuty = 0.0;
  double cv_I = 0.0;
  bool voltageControlActive = false;
};

struct SystemIdResult {
  bool valid = false;
  double deadTimeMs = 0.0, riseTimeMs = 0.0, slopeAps = 0.0;
  double I0 = 0.0, I1 = 0.0;
};

class SystemId {
 public:
  // Legal only while running normally in AUTO.
  bool start(TimeNs now, const SystemIdSnapshot& pre) noexcept;
  // While running: returns sysIDDutyOut. Sets `finished` on the falling edge.
  double systemIdTick(TimeNs now, double measuredAmps, const Params& p, bool& finished) noexcept;
  void abort() noexcept { running_ = false; }

  bool systemIdRunning() const noexcept { return running_; }
  const SystemIdSnapshot& snapshot() const noexcept { return pre_; }
  const SystemIdResult& result() const noexcept { return result_; }
  bool stepped() const noexcept { return stepped_; }

 private:
  void analyse() noexcept;
  static constexpr int kSamples = 1024;
  bool running_ = false, stepped_ = false;          // a run, past its duty step
  TimeNs start_ = 0, stepAt_ = 0, lastSample_ = 0;  // the run's start, the step, the last sample
  SystemIdSnapshot pre_;                            // the loops' state before the run (restored after)
  SystemIdResult result_;                           // the last run's dead and rise time
  double baseSum_ = 0.0;                            // the current before the step, summed
  int baseCount_ = 0;                               // ... over this many samples
  std::array<float, kSamples> amps_{};              // the current after the step
  std::array<float, kSamples> tMs_{};               // ... and when
  int n_ = 0;                                       // samples taken
};

}  // namespace xr
