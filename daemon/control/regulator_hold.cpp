// Regulator: never silently not charging (docs/protections.md "Charging
// held", "BMS plausibility"). After the SoC update and before the alarms:
// what holds the charge, the held-charging detector, and the alarm rows of
// both checks.
#include <cmath>

#include "control/regulator.h"
#include "control/regulator_state.h"
#include "core/freshness.h"

namespace xr {

namespace {
constexpr double kCvlHoldsV = 0.05;  // a CVL ceiling this close over the pack holds the charge
}  // namespace

// What holds the charge this tick, first the field's own reason (the mode
// selection said why the field is off), then the caps on a running field.
ChargeHold Regulator::chargeHoldCause(const Tick& t) const noexcept {
  const State& s = *s_;
  const bool viaGx = t.in.bms.source == BmsSource::VictronGx;
  const ChargeHold bms = viaGx ? ChargeHold::DVCC : ChargeHold::BMS;
  switch (t.d.reason) {
    case Reason::NONE:
    case Reason::REASON_BMS_STALE:
      break;
    case Reason::REASON_BMS_DISABLED:
      return bms;
    case Reason::REASON_WEATHER_MODE:
      return ChargeHold::WEATHER;
    case Reason::REASON_BATTERY_COLD:
      return ChargeHold::BATTERY_COLD;
    case Reason::REASON_BATTERY_HOT:
      return ChargeHold::BATTERY_HOT;
    case Reason::REASON_TEMP_CRITICAL:
    case Reason::REASON_TEMP_WARNING:
    case Reason::REASON_TEMP_SUSTAINED:
    case Reason::REASON_TEMP_SOAK:
      return ChargeHold::ALTERNATOR_TEMP;
    default:
      return ChargeHold::PROTECTION;
  }
  const BmsLimiter& b = s.law.bms();
  const bool cvlHolds = std::isfinite(b.cvlCeilingV()) && std::isfinite(t.in.IBV.value) &&
                        b.cvlCeilingV() <= t.in.IBV.value + kCvlHoldsV;
  if (b.state() != BmsState::OFF &&
      (b.state() != BmsState::OK || b.batteryCapA() < ChargeHoldDetector::kNothingInA || cvlHolds ||
       b.cellHigh()))
    return bms;
  const BatteryTempDecision& bt = s.batTemp.decision();
  if (bt.currentCapA < ChargeHoldDetector::kNothingInA)
    return bt.hot ? ChargeHold::BATTERY_HOT : ChargeHold::BATTERY_COLD;
  if (s.law.thermalPenaltyAmps() > 0.0) return ChargeHold::ALTERNATOR_TEMP;
  return ChargeHold::LIMIT;
}

void Regulator::updateChargeChecks(const Tick& t) noexcept {
  State& s = *s_;
  const Inputs& in = t.in;
  const double dt = s.lastHoldTick != 0 && in.now > s.lastHoldTick ? toSec(in.now - s.lastHoldTick) : 0.0;
  s.lastHoldTick = in.now;
  ChargeHoldSample h;
  // The engine runs: the ignition on and the tach (or the engine's own
  // speed) turning; with the field off a W-terminal tach reads nothing, so
  // the ignition alone says it then. Stopped or idling under the cut-in
  // (REASON_RPM_LOW) is no hold.
  const bool turning = fresh::engineTurning(in.rpm.value) ||
                       (fresh::engineRpm(in.engineRpm, in.now) && fresh::engineTurning(in.engineRpm.value));
  h.engineRunning = in.ignitionOn && t.d.reason != Reason::REASON_RPM_LOW &&
                    t.d.reason != Reason::REASON_IGNITION_OFF && (turning || !s.out.fieldEnable);
  const ChargingStageMachine& st = s.law.stages();
  // A resting field is no sign of a full bank: a BMS's CVL under the pack
  // rests it too (the voltage over its target, no current asked).
  h.bankFull = st.inFloatStage() || st.inIdleStage() ||
               (s.bat.socKnown() && s.bat.socPercent() >= ChargeHoldDetector::kFullSocPct);
  h.ownerChoice = t.snap.manualMode || s.ops.off() || !s.p.OnOff || s.p.MaintainMode ||
                  t.d.reason == Reason::REASON_ONOFF_DISABLED || t.d.reason == Reason::REASON_SYS_OFF ||
                  t.d.mode == FieldControlMode::MODE_LIMP_HOME || t.d.reason == Reason::REASON_SYSTEM_ID ||
                  t.d.reason == Reason::REASON_AUTO_ZERO;
  h.batteryA = t.cs.Bcur;
  h.cause = chargeHoldCause(t);
  s.hold.update(in.now, dt, h, s.out.events);
  s.prot.setChargeChecks(s.law.bms().plausibility().active(), s.hold.alarm());
}

}  // namespace xr
