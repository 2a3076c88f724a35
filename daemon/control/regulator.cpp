// Regulator: its state, parameters and operator commands. One tick's stages
// are regulator_step.cpp.
#include "control/regulator.h"

#include <cmath>
#include <optional>

#include "control/regulator_state.h"
#include "params/derived.h"

namespace xr {

Regulator::Regulator(const Params& params) : s_(std::make_unique<State>(params)) {
  s_->out.inaBovlVolts = voltageHardwareLimit(params);
}
Regulator::~Regulator() = default;

void Regulator::setParams(const Params& params) noexcept {
  // A new set reads the bank again when it asks to (bank_reading.h).
  s_->bank.restart();
  s_->p = params;
  s_->prot.setParams(params);
  s_->bat.setParams(params);
}
const Params& Regulator::params() const { return s_->p; }
const Outputs& Regulator::outputs() const { return s_->out; }
BatteryLedger Regulator::ledger() const {
  BatteryLedger l = s_->bat.ledger();
  l.wear = s_->wear.ledger();
  return l;
}
void Regulator::restoreLedger(const BatteryLedger& l) {
  s_->bat.restoreLedger(l);
  s_->wear.restore(l.wear);
}

bool Regulator::command(const Command& cmd) noexcept {
  State& s = *s_;
  const std::optional<bool> own = s.ops.apply(cmd);  // the operator's field commands
  const bool ok = own ? *own : applyToParts(cmd);
  EventCode code = ok ? EventCode::CommandApplied : EventCode::CommandRejected;
  if (ok && (cmd.type == CommandType::TuningCommit || cmd.type == CommandType::CvTuningCommit))
    code = EventCode::TuningCommitted;
  s.pending.queue(makeEvent(s.now, ok ? EventLevel::Info : EventLevel::Warning, code, Reason::NONE, cmd.value,
                            0.0, static_cast<int>(cmd.type)));
  return ok;
}

// The commands the protections, the battery and the control law carry out.
bool Regulator::applyToParts(const Command& cmd) noexcept {
  State& s = *s_;
  bool ok = true;
  switch (cmd.type) {
    case CommandType::ReenableField:
      s.prot.reenableField();
      break;
    case CommandType::ResetAlarmLatch:
      s.prot.resetAlarmLatch();
      break;
    case CommandType::ResetSocGain:
      s.bat.resetSocGain();
      break;
    case CommandType::ResetAltZero:
      s.bat.resetAltZero();
      break;
    case CommandType::SetSoc:
      ok = s.bat.setSoc(cmd.value);
      break;
    case CommandType::SystemIdStart:
      ok = !s.report.firstTick() && s.report.mode() == FieldControlMode::MODE_NORMAL_AUTO_PID &&
           s.report.field() && s.law.startSystemId(s.now, true);
      break;
    case CommandType::TuningCommit:
      ok = s.p.TuningMode && s.law.commitTuning(s.now, s.p);
      break;
    case CommandType::CvTuningCommit:
      ok = s.p.CVTuningMode && s.law.commitCvTuning(s.now, s.p);
      break;
    case CommandType::AcknowledgeAlarm:
      s.prot.acknowledgeAlarm();
      break;
    default:
      break;  // the operator's own (OperatorCommands)
  }
  return ok;
}

// Not set up on any bank (docs/configuration.md "Not set up"): until the
// bank class is read from the battery (bank_reading.h) the field stays off
// and the INA228's bus limit sits above every class (kBankReadingBovlV);
// then the not-set-up limits are scaled to that class. True once settled
// (this tick runs on with the scaled set); false while waiting.
bool Regulator::settleBankClass(const Tick& t) noexcept {
  State& s = *s_;
  const std::optional<SystemClass> used = s.bank.update(t.in.IBV, t.in.now);
  if (!used) {
    s.out.dutyPct = 0.0;
    s.out.fieldEnable = false;
    s.out.buzzer = false;
    s.out.inaFastMode = false;
    s.out.inaBovlVolts = kBankReadingBovlV;
    s.out.telemetry.now = t.in.now;
    // What the screens and the boat's network read meanwhile: no battery
    // reading yet (not 0 V), and the regulator in automatic (nobody turned it
    // off: the owner model must not say "Off").
    s.out.telemetry.ibv_v = kNoValue;
    s.out.telemetry.battery_v = kNoValue;
    s.out.telemetry.control.sysMode = SysMode::SYS_MODE_AUTO;
    return false;
  }
  const Params p = withBankClass(s.p, *used);
  s.p = p;
  s.prot.setParams(p);
  s.bat.setParams(p);
  s.out.inaBovlVolts = voltageHardwareLimit(p);
  return true;
}

}  // namespace xr
