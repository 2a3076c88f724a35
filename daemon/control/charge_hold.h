#pragma once
// ChargeHoldDetector: charging held for long is an alarm (docs/protections.md
// "Charging held"). Whatever holds it (a BMS, DVCC, a cold battery, weather,
// a limit), once the engine has run kHoldS with the bank not full and
// nothing going into it, the owner gets one incident: a Warning naming what
// holds it, and an Info with how long when it ends. A moment of charge (a
// few seconds of current, a BMS releasing and holding again) does not end
// an episode: only kEndS without a hold does. The caller says what holds it
// (Regulator::chargeHoldCause); an owner's own choice (switched off, manual)
// is no hold. Pure: time comes in, nothing is allocated.
#include "core/charge_checks.h"
#include "core/events.h"

namespace xr {

struct ChargeHoldSample {
  bool engineRunning = false;
  bool bankFull = false;     // float, the idle stage, or the SoC at kFullSocPct
  bool ownerChoice = false;  // switched off, manual, limp home: no alarm
  double batteryA = 0.0;     // corrected battery current (NaN: unknown, nothing is judged)
  ChargeHold cause = ChargeHold::LIMIT;
};

class ChargeHoldDetector {
 public:
  static constexpr double kHoldS = 15.0 * 60.0;  // the 15 minutes of engine run
  static constexpr double kEndS = 60.0;          // this long not held ends the episode
  static constexpr double kNothingInA = 1.0;     // under this the bank takes nothing
  static constexpr double kFullSocPct = 95.0;

  // Once per tick; dt in seconds since the last tick.
  void update(TimeNs now, double dt, const ChargeHoldSample& s, EventBatch& ev) noexcept;

  bool held() const noexcept { return heldS_ > 0.0 && notHeldS_ == 0.0; }
  bool alarm() const noexcept { return reported_; }  // the alarm row
  double heldS() const noexcept { return heldS_; }
  // What holds it now (NONE when nothing does): the charge_held_by column.
  ChargeHold cause() const noexcept { return held() ? cause_ : ChargeHold::NONE; }

 private:
  double heldS_ = 0.0, notHeldS_ = 0.0;  // seconds held, and seconds free since
  ChargeHold cause_ = ChargeHold::NONE,
             reportedCause_ = ChargeHold::NONE;  // what holds now, what the alarm named
  bool reported_ = false;                        // the alarm is raised
};

}  // namespace xr
