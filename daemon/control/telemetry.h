#pragma once
// Telemetry of one tick: the CSV columns of docs/operations.md at the top level, then the
// per-module detail. Plain data: copied out of the RT thread whole. It lives
// beside the Regulator, where control, protection and battery meet: the
// aggregate needs all three, and daemon/core (below them) must not.
#include <cmath>
#include <string_view>
#include <variant>

#include "battery/battery_telemetry.h"
#include "control/bms_limiter.h"
#include "control/command_caps.h"
#include "control/control_telemetry.h"
#include "core/charge_checks.h"
#include "core/inputs.h"
#include "core/modes.h"
#include "core/time.h"
#include "health/alternator_wear.h"
#include "protection/protection_telemetry.h"

namespace xr {

struct Telemetry {
  TimeNs now = 0;
  FieldControlMode mode = FieldControlMode::MODE_DISABLED_RAMP;
  ChargeStage stage = ChargeStage::BULK;
  Reason reason = Reason::NONE;
  double ibv_v = 0.0;
  double battery_v = 0.0;
  double bcur_a = 0.0;
  double alt_a = 0.0;
  double rpm = 0.0;
  double temp_f = 0.0;
  double duty_pct = 0.0;
  bool field_enable = false;
  double setpoint_a = 0.0;         // setpointLimited
  double target_a = 0.0;           // uTargetAmps
  double target_v = 0.0;           // ChargingVoltageTarget
  double thermal_penalty_a = 0.0;  // thermalPenaltyAmps
  bool fast_ov_active = false;     // fastOvClampActive
  double soc_pct = 0.0;
  bool alarm = false;  // buzzer
  double charged_wh_lifetime = 0.0;
  double alt_charged_wh_lifetime = 0.0;
  // A BMS's limits as last received (NaN when none or stale) and what the
  // regulator makes of them (bms_limiter.h).
  double bms_cvl_v = kBmsNoValue;
  double bms_ccl_a = kBmsNoValue;
  double bms_soc_pct = kBmsNoValue;
  BmsState bms_state = BmsState::OFF;
  double battery_temp_c = kNoValue;  // NaN while no sample was ever read
  bool ignition_on = true;           // the ignition input this tick (pairing by presence, docs/security.md)
  // Never silently not charging (docs/protections.md): what of the BMS does
  // not fit the bank (the episode reported), what holds the charge now and
  // for how long (minutes, while held).
  BmsMismatch bms_mismatch = BmsMismatch::NONE;
  ChargeHold charge_held_by = ChargeHold::NONE;
  double charge_held_min = 0.0;

  // Not set up, the bank class read from the battery (docs/configuration.md
  // "Not set up"): fromBattery once read; readV the reading (NaN: none came);
  // classV the class the limits are scaled to; fits: the reading fits it.
  struct SetupBank {
    bool fromBattery = false;
    double readV = kNoValue;
    int classV = 0;
    bool fits = false;
  } setupBank;

  ControlTelemetry control;
  CommandCaps caps;  // what holds the current command back, for the owner model
  ProtectionTelemetry protection;
  BatteryTelemetry battery;
  WearTelemetry wear;
};

// The one SoC rule (docs/batteries.md "State of charge", docs/dashboard.md
// "Owner model"): a talking BMS's SoC, else the counted SoC, else the
// rested-voltage estimate, else unknown (NaN: no number anywhere, the CSV
// cell empty). Every reader of a SoC takes it from here.
enum class SocShownSource { UNKNOWN, BMS, COUNTED, OCV_ESTIMATE };
struct SocShown {
  double pct = kNoValue;
  SocShownSource source = SocShownSource::UNKNOWN;
};
inline SocShown socShown(const Telemetry& t) {
  const bool bmsTalking = t.bms_state == BmsState::OK || t.bms_state == BmsState::WARNING ||
                          t.bms_state == BmsState::CHARGE_DISABLED;
  if (bmsTalking && std::isfinite(t.bms_soc_pct)) return {t.bms_soc_pct, SocShownSource::BMS};
  if (t.battery.socSource == SocSource::Counted) return {t.soc_pct, SocShownSource::COUNTED};
  if (t.battery.socSource == SocSource::OcvEstimate) return {t.soc_pct, SocShownSource::OCV_ESTIMATE};
  return {};
}

// A column value: a number, a flag (0/1) or a name (mode, stage, reason).
using ColumnValue = std::variant<double, bool, std::string_view>;

// Visits the telemetry columns of docs/operations.md in a fixed order: f(name, ColumnValue).
// t_s is seconds since `start`. The CSV writer and /api/status both use this,
// so the names are spelled once.
template <typename F>
void visitTelemetryColumns(const Telemetry& t, TimeNs start, F&& f) {
  f("t_s", ColumnValue{toSec(t.now - start)});
  f("mode", ColumnValue{toString(t.mode)});
  f("stage", ColumnValue{toString(t.stage)});
  f("reason", ColumnValue{toString(t.reason)});
  f("ibv_v", ColumnValue{t.ibv_v});
  f("battery_v", ColumnValue{t.battery_v});
  f("bcur_a", ColumnValue{t.bcur_a});
  f("alt_a", ColumnValue{t.alt_a});
  f("rpm", ColumnValue{t.rpm});
  f("temp_f", ColumnValue{t.temp_f});
  f("duty_pct", ColumnValue{t.duty_pct});
  f("field_enable", ColumnValue{t.field_enable});
  f("setpoint_a", ColumnValue{t.setpoint_a});
  f("target_a", ColumnValue{t.target_a});
  f("target_v", ColumnValue{t.target_v});
  f("thermal_penalty_a", ColumnValue{t.thermal_penalty_a});
  f("fast_ov_active", ColumnValue{t.fast_ov_active});
  f("soc_pct", ColumnValue{socShown(t).pct});
  f("alarm", ColumnValue{t.alarm});
  f("charged_wh_lifetime", ColumnValue{t.charged_wh_lifetime});
  f("alt_charged_wh_lifetime", ColumnValue{t.alt_charged_wh_lifetime});
  f("bms_cvl_v", ColumnValue{t.bms_cvl_v});
  f("bms_ccl_a", ColumnValue{t.bms_ccl_a});
  f("bms_soc_pct", ColumnValue{t.bms_soc_pct});
  f("bms_state", ColumnValue{toString(t.bms_state)});
  f("battery_temp_c", ColumnValue{t.battery_temp_c});
  // What the regulator learns (docs/batteries.md, docs/operations.md "Alternator wear").
  f("capacity_measured_ah", ColumnValue{t.battery.capacity_measured_ah});
  f("capacity_cycles", ColumnValue{static_cast<double>(t.battery.capacity_cycles)});
  f("battery_r_mohm", ColumnValue{t.battery.battery_r_mohm});
  f("battery_r_spread_mohm", ColumnValue{t.battery.battery_r_spread_mohm});
  f("alt_run_hours", ColumnValue{t.wear.alt_run_hours});
  f("alt_hours_above_150f", ColumnValue{t.wear.alt_hours_above[0]});
  f("alt_hours_above_175f", ColumnValue{t.wear.alt_hours_above[1]});
  f("alt_hours_above_200f", ColumnValue{t.wear.alt_hours_above[2]});
  f("alt_hours_above_225f", ColumnValue{t.wear.alt_hours_above[3]});
  f("alt_life_used_pct", ColumnValue{t.wear.alt_life_used_pct});
  f("belt_slip_events", ColumnValue{t.wear.belt_slip_events});
  f("bms_mismatch", ColumnValue{toString(t.bms_mismatch)});
  f("charge_held_by", ColumnValue{toString(t.charge_held_by)});
  f("charge_held_min", ColumnValue{t.charge_held_min});
}

}  // namespace xr
