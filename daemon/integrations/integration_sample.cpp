#include "integrations/integration_sample.h"

#include <cmath>
#include <limits>

namespace xr::integrations {

namespace {
// A missing reading stays NaN: each integration writes it as "no value"
// (JSON null), never as a plausible-looking 0.
double finiteOr(double v, double fallback) { return std::isfinite(v) ? v : fallback; }
}  // namespace

IntegrationSample sampleOf(const rt::RuntimeSnapshot& s, const owner::OwnerContext& ctx) {
  IntegrationSample o;
  o.valid = s.tick > 0;
  const Telemetry& t = s.telemetry;
  o.battery_v = t.battery_v;
  o.battery_a = t.bcur_a;
  o.alt_a = t.alt_a;
  o.alt_temp_c = (t.temp_f - 32.0) * 5.0 / 9.0;
  o.rpm = t.rpm;
  o.field_pct = t.duty_pct;
  o.field_on = t.field_enable;
  o.alarm = t.alarm;
  o.setpoint_v = t.target_v;
  o.setpoint_a = t.target_a;
  // The owner model: the one SoC rule (a SoC the regulator does not know is
  // not sent as a number: Signal K leaves the path out, Home Assistant gets
  // null), the state and the limits in words.
  const owner::OwnerModel m = owner::ownerModel(t, ctx);
  const bool socUnknown = !std::isfinite(m.soc.pct);
  o.soc_pct = m.soc.pct;
  o.socSource = std::string(m.soc.source);
  o.ownerState = m.state;
  o.limitedBy = owner::limitedByText(m);
  if (!m.limits.empty()) o.limitAmps = m.limits.front().amps;
  o.limits = m.limits;
  const double minutes = t.battery.timeToFullDischargeMin;
  o.time_to_empty_s = !socUnknown && std::isfinite(minutes) && minutes > 0 ? minutes * 60.0 : -1.0;
  o.power_w = o.battery_v * o.alt_a;
  o.charged_kwh = finiteOr(t.charged_wh_lifetime, 0.0) / 1000.0;
  o.capacity_measured_ah = t.battery.capacity_measured_ah;
  o.nominal_v = t.battery.nominalVoltage;
  o.battery_r_mohm = t.battery.battery_r_mohm;
  o.alt_run_hours = t.wear.alt_run_hours;
  o.alt_life_used_pct = t.wear.alt_life_used_pct;
  o.belt_slip_events = t.wear.belt_slip_events;
  o.mode = std::string(toString(t.mode));
  o.stage = std::string(toString(t.stage));
  o.reason = std::string(toString(t.reason));
  o.stageValue = t.stage;
  o.operatorOff = t.control.sysMode == SysMode::SYS_MODE_OFF;
  return o;
}

std::string_view signalKChargingMode(ChargeStage stage, bool fieldOn) {
  if (!fieldOn) return "other";
  switch (stage) {
    case ChargeStage::BULK:
      return "bulk";
    case ChargeStage::ABSORPTION:
      return "acceptance";
    case ChargeStage::FLOAT:
      return "float";
    case ChargeStage::IDLE:
      return "other";
  }
  return "other";
}

}  // namespace xr::integrations
