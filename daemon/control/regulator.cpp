// Regulator: its state, parameters and operator commands. One tick's stages
// are regulator_step.cpp.
#include "control/regulator.h"

#include <cmath>

#include "control/regulator_state.h"
#include "params/derived.h"

namespace xr {

Regulator::Regulator(const Params& params) : s_(std::make_unique<State>(params)) {
  s_->out.inaBovlVolts = voltageHardwareLimit(params);
}
Regulator::~Regulator() = default;

void Regulator::setParams(const Params& params) noexcept {
  // A new set reads the bank again when it asks to (bank_reading.cpp).
  s_->bank = {};
  s_->bankWaiting = false;
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
  bool ok = true;
  switch (cmd.type) {
    case CommandType::Auto:
      s.opManual = false;
      s.opOff = false;
      break;
    case CommandType::Manual:
      ok = std::isfinite(cmd.value) && cmd.value >= 0.0 && cmd.value <= 100.0;
      if (ok) {
        s.opManual = true;
        s.opManualDuty = cmd.value;
        s.opOff = false;
      }
      break;
    case CommandType::Off:
      s.opOff = true;
      break;
    case CommandType::LimpHome:
      s.limpHome = true;
      break;
    case CommandType::LimpHomeOff:
      s.limpHome = false;
      break;
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
      ok = !s.firstTick && s.lastMode == FieldControlMode::MODE_NORMAL_AUTO_PID && s.lastField &&
           s.law.startSystemId(s.now, true);
      break;
    case CommandType::TuningCommit:
      ok = s.p.TuningMode && s.law.commitTuning(s.now, s.p);
      break;
    case CommandType::CvTuningCommit:
      ok = s.p.CVTuningMode && s.law.commitCvTuning(s.now, s.p);
      break;
    case CommandType::WeatherMode:
      s.currentWeatherMode = cmd.flag;
      break;
    case CommandType::AcknowledgeAlarm:
      s.prot.acknowledgeAlarm();
      break;
  }
  EventCode code = ok ? EventCode::CommandApplied : EventCode::CommandRejected;
  if (ok && (cmd.type == CommandType::TuningCommit || cmd.type == CommandType::CvTuningCommit))
    code = EventCode::TuningCommitted;
  s.queue(makeEvent(s.now, ok ? EventLevel::Info : EventLevel::Warning, code, Reason::NONE, cmd.value, 0.0,
                    static_cast<int>(cmd.type)));
  return ok;
}

}  // namespace xr
