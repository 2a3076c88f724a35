// Not set up on any bank (docs/configuration.md "Not set up"): nobody has
// said which bank this is, so the bank class comes from the battery itself,
// read before any voltage trip is armed. Until the first battery-voltage
// reading the field stays off and the INA228's bus limit sits above every
// class (params/derived.h kBankReadingBovlV); then the not-set-up limits are
// scaled to the class of that reading. A reading that fits no class (18 V,
// 0 V, none within kBankReadingWait) keeps the 12 V limits: the smallest,
// so the safe side, and the telemetry says it did not fit.
#include <cmath>

#include "control/regulator.h"
#include "control/regulator_state.h"
#include "params/derived.h"

namespace xr {

namespace {
// Long enough for the INA228's slow (field-off) averaging to deliver its
// first result (~1 s), short enough that a missing chip is reported by the
// sensor checks soon after start.
constexpr TimeNs kBankReadingWait = 5'000'000'000;
}  // namespace

// True once the class is settled (this tick runs on with the scaled set);
// false while waiting, with the outputs safe.
bool Regulator::settleBankClass(const Tick& t) noexcept {
  State& s = *s_;
  const Reading& v = t.in.IBV;
  const bool reading = v.stamp != 0 && std::isfinite(v.value);
  if (!s.bankWaiting) {
    s.bankWaiting = true;
    s.bankWaitSince = t.in.now;
  }
  if (!reading && t.in.now - s.bankWaitSince < kBankReadingWait) {
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
  const std::optional<SystemClass> c = reading ? bankClassOfReading(v.value) : std::nullopt;
  const SystemClass used = c.value_or(SystemClass::V12);
  const Params p = withBankClass(s.p, used);
  s.p = p;
  s.prot.setParams(p);
  s.bat.setParams(p);
  s.bankWaiting = false;
  s.bank = {true, reading ? v.value : kNoValue, nominalVoltage(used), c.has_value()};
  s.out.inaBovlVolts = voltageHardwareLimit(p);
  return true;
}

}  // namespace xr
