#pragma once
// FastOvSupervisor: the voltage over-voltage throttling protections of
// docs/protections.md, on the AUTO path only: Group 1 (prediction), Group 2
// (measured), Group 3 (iExcess, IExcessGuard) and the load dump, all armed
// by the nearBulk gate (or FLOAT) and voltageControlActive, all acting
// through one FastOvAction: a cap on the current request, the CV
// integrator's action, the slew bypass.
//
// One input struct in (FastOvInputs, filled by the control side), one action
// out (FastOvAction, applied by the control side as it stands).
#include "core/fast_ov_verdict.h"
#include "core/inputs.h"
#include "core/time.h"
#include "params/params.h"
#include "protection/fast_samples.h"
#include "protection/iexcess_guard.h"

namespace xr {

// Control values the fast-OV supervisors read (AUTO path only).
struct FastOvInputs {
  bool voltageControlActive = false;
  bool floatStage = false;  // FLOAT arms the supervisors whatever its target
  double ChargingVoltageTarget = 0.0;
  double uTargetAmps = 0.0;            // fastOvBaseCap: the request before the fast-OV clamp
  double setpointLimited = 0.0;        // slewed setpoint of the previous tick
  double cv_I = 0.0;                   // CV integrator now
  double MeasuredAmps = 0.0;           // raw alternator current (A)
  double MeasuredAmps_filtered = 0.0;  // EMA(InputFilterTC)
  bool altCurrentFresh = false;        // a new CH1 sample this tick (feeds the MA window)
};

// The verdict the control law applies, and which supervisors gave it.
struct FastOvAction {
  // The cap reads 0 A until the first AUTO tick (telemetry); every update sets it.
  FastOvVerdict verdict{.fastOvCurrentCap = 0.0};
  bool nearBulk = false;  // the supervisors' gate: target within ProtectionProxGateV of BulkVoltage
  // Which supervisors acted (telemetry/tests).
  bool group1 = false, group2 = false, group3 = false, loadDump = false;
};

class FastOvSupervisor {
 public:
  // Every tick, from the detectors' step: the tick's time and the rates of
  // the fresh INA228 samples (dv/dt, dBcur/dt), whatever the mode.
  void sample(const Inputs& in, const Params& p) noexcept;
  // The AUTO path, once per tick after sample(). In every other mode it is
  // not called: a gap over kGap between calls starts the supervisors clean.
  const FastOvAction& update(const FastOvInputs& x, const Params& p) noexcept;

  // A gap longer than this between calls (another mode ran) starts the
  // supervisors clean: their counters describe consecutive control ticks.
  static constexpr TimeNs kGap = fromMs(100);

  const FastOvAction& last() const noexcept { return action_; }
  const FastSampleRates& rates() const noexcept { return rates_; }
  double Vpred() const noexcept { return Vpred_; }
  bool bypassLatched() const noexcept { return bypassLatched_; }

 private:
  void reset() noexcept;
  double voltageGroupsCap(const FastOvInputs& x, const Params& p) noexcept;
  void finish(double cap, double base, double target) noexcept;

  FastSampleRates rates_;       // dv/dt and dBcur/dt of the INA228 samples
  IExcessGuard group3_;         // Group 3 (iExcess) and its signal window
  TimeNs now_ = 0;              // this tick's time (from sample())
  double IBV_ = kNoValue;       // this tick's INA228 bus voltage (from sample())
  TimeNs lastCall_ = -1;        // the previous update(), -1 = none (the gap rule)
  bool wasActive_ = false;      // a supervisor acted on the previous update
  double cap_ = 0.0;            // the cap held while they act (it only falls)
  bool bypassLatched_ = false;  // slew bypass until IBV < target + CV_OVERSHOOT_RELEASE_V
  double Vpred_ = 0.0;          // Group 1's prediction IBV + TdPred * max(0, dvdt)
  FastOvAction action_;         // the last update's action (telemetry)
};

}  // namespace xr
