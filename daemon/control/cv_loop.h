#pragma once
// The voltage CV loop (docs/control.md "Voltage CV loop",
// a position-form PI): computes Icv, the current setpoint fed to the inner
// PID while voltageControlActive.
#include "core/time.h"
#include "params/params.h"

namespace xr {

struct CvLoopInputs {
  TimeNs now = 0;
  double dtSec = 0.0;  // this control tick
  bool voltageControlActive = false;
  double ChargingVoltageTarget = 0.0;
  double IBV = 0.0;              // INA228 bus voltage
  double cvDSlope = 0.0;         // dV/dt of getFiltV() between fresh IBV samples (slope bleed only)
  double g_pidI_filtered = 0.0;  // inner-loop feedback (bumpless start value / tracker)
  double uTargetAmps = 0.0;      // ceiling after fastOvCurrentCap
  double uTargetRaw = 0.0;       // ceiling before fastOvCurrentCap (uTargetRaw_cached)
  bool fastOvClampActive = false;
};

class VoltageCvLoop {
 public:
  // One control tick. Returns Icv.
  // Real-time thread, every tick: neither allocates nor blocks (docs/architecture.md "Threads").
  double update(const CvLoopInputs& in, const Params& p) noexcept;

  // Protection hooks (Groups 3 / load dump act on cv_I).
  void setCvI(double v) noexcept;
  double cv_I() const noexcept { return cv_I_; }
  // Bumpless restore (SystemID): integrator and tracker to v.
  void restore(double v) noexcept;
  // After a protection event (fast-OV clamp cleared, back in AUTO): the next
  // active update starts cv_I afresh as on CV entry (bumpless, AW cap cleared)
  // instead of crawling back from the event's state.
  void requestReseed() noexcept { reseedPending_ = true; }
  // The same, with the current the alternator should make now (instead of
  // the inner loop's filtered feedback, which still holds the pre-event
  // current for a while): Icv starts at `amps`.
  void requestReseedAt(double amps) noexcept {
    reseedPending_ = true;
    reseedAmps_ = amps;
  }
  void reset() noexcept;

  double Icv() const noexcept { return Icv_; }
  double cv_I_track() const noexcept { return cv_I_track_; }
  double cv_I_aw_cap() const noexcept { return cv_I_aw_cap_; }
  double voltageTargetSlewed() const noexcept { return voltageTargetSlewed_; }
  int g_awState() const noexcept { return g_awState_; }
  double cvDSlope() const noexcept { return cvDSlope_; }
  double g_voltLoopActualIntervalMs() const noexcept { return g_voltLoopActualIntervalMs_; }
  double lastError() const noexcept { return e_; }

 private:
  void seedOnEntry(const CvLoopInputs& in, const Params& p) noexcept;
  void fire(const CvLoopInputs& in, const Params& p, double dtSec) noexcept;
  double slewedTarget(const CvLoopInputs& in, const Params& p) const noexcept;

  bool wasActive_ = false;            // the loop ran last tick (the CV-entry edge)
  TimeNs lastVoltageLoopNs_ = 0;      // 0: fires on the enteringCV edge
  TimeNs awSeedProtectStartNs_ = -1;  // the last entry / reseed: the AW cap is held off for a while
  double cv_I_ = 0.0, cv_I_track_ = 0.0, cv_I_aw_cap_ = -1.0;  // aw cap < 0: not initialised
  double Icv_ = 0.0, e_ = 0.0;        // the command and the voltage error of the last firing
  double voltageTargetSlewed_ = 0.0;  // the target after its own slew (no step into the loop)
  int g_awState_ = 4;                 // which anti-windup branch acted (telemetry)
  double cvDSlope_ = 0.0;             // dV/dt taken in (slope bleed)
  bool reseedPending_ = false;        // the next active update starts afresh (after a protection event)
  double reseedAmps_ = -1.0;          // < 0: start from g_pidI_filtered
  double g_voltLoopActualIntervalMs_ = 0.0;  // the real interval of the last firing (telemetry)
};

}  // namespace xr
