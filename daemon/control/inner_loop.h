#pragma once
// InnerLoop: the current PID and the governor after it (docs/control.md
// "Inner loop", "Governor"): the duty request, the applied duty and the slew
// mode it went through. Every path that sets the duty (AUTO, MANUAL, Limp
// Home, the shutdown sequencer, SystemID, a cut, a field rest) goes through
// here, so the PID always tracks the duty actually applied (bumpless).
#include "control/pid.h"
#include "core/inputs.h"
#include "core/modes.h"
#include "params/params.h"

namespace xr {

// What the PID reads each fresh CH1 tick in AUTO.
struct InnerInputs {
  TimeNs now = 0;
  double dtSec = 0.0;
  double input = 0.0;      // the PID's process value (alternator current, or the zero-hold selector)
  double setpoint = 0.0;   // setpointLimited
  double pidSignal = 0.0;  // the alternator current the PID sees (the BMS snap scales by it)
  bool bmsCapActive = false;
  double bmsAltCap = 1e300;  // the BMS's cap carried to the alternator
};

class InnerLoop {
 public:
  explicit InnerLoop(const Params& p);

  // One fresh CH1 tick in AUTO: PID (every PidSampleDivisor-th sample), the
  // BMS step snap, the governor; returns the applied duty.
  double update(const InnerInputs& in, const Params& p) noexcept;

  // The tach floor of this tick (rpmMinDutyTable).
  void setRpmFloor(double duty) noexcept { rpmMinDuty_ = duty; }
  void setGovMode(GovMode m) noexcept { govMode_ = m; }
  // The governor from the last applied duty toward `request` (no state change).
  double governorStep(const Params& p, double request, GovMode mode, double dtSec) const noexcept;
  // MANUAL / Limp Home: `request` asked, `duty` applied, AUTO re-entry bumpless.
  void applyOpenLoop(double request, double duty) noexcept;
  // Someone else owns the duty (shutdown sequencer, SystemID): track it.
  void track(double request, double duty) noexcept;
  // The field rests: everything waits at zero.
  void rest() noexcept;
  // The universal immediate cut: duty 0, PID in MANUAL at 0.
  void cut() noexcept;
  // Leaving AUTO (OFF, MANUAL, FAULT): PID in MANUAL at the applied duty.
  void enterManual() noexcept;
  // Entering AUTO: PID re-seeded at the applied duty, sample cadence restarted.
  void enterAuto(const Params& p, double pidSignal) noexcept;
  // A SystemID run pins the PID in MANUAL; its end hands it back.
  void pinManual() noexcept { pid_.setMode(Pid::MANUAL); }
  void resumeAuto(const Params& p) noexcept;

  const Pid& pid() const noexcept { return pid_; }
  double dutyRequest() const noexcept { return dutyRequest_; }
  double lastAppliedDuty() const noexcept { return lastAppliedDuty_; }
  double rpmMinDuty() const noexcept { return rpmMinDuty_; }
  GovMode govMode() const noexcept { return govMode_; }

 private:
  // A BMS alternator cap falling more than this between control ticks is a
  // step (snap the duty); slower falls are followed by the PID.
  static constexpr double kBmsSnapStepA = 3.0;

  void configure(const Params& p) noexcept;
  void snapToBmsStep(const InnerInputs& in) noexcept;

  Pid pid_;                       // currentPID: setpointLimited -> duty
  int pidSampleCounter_ = 0;      // fresh CH1 samples since the last compute
  TimeNs lastPidCompute_ = -1;    // the last compute (-1: restart the cadence)
  double bmsAltCapPrev_ = 1e300;  // the BMS alternator cap at the last fresh CH1 (the snap compares)
  double dutyRequest_ = 0.0;      // what the PID (or the mode) asked of the governor
  double lastAppliedDuty_ = 0.0;  // what the governor applied last
  double rpmMinDuty_ = 0.0;       // the tach floor (rpmMinDutyTable) of the last tick
  GovMode govMode_ = GovMode::GOV_NORMAL_SLEW;  // the governor's slew mode of this tick
};

}  // namespace xr
