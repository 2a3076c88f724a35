// The limits of the owner model (docs/dashboard.md "Owner model"): every cap
// on the current command acting now, from the control law's telemetry
// (CommandCaps), and every hold that keeps the field off by the owner's or
// the battery's wish, each with its amps and its cause in words.
#include <algorithm>
#include <cmath>

#include "owner/owner_model.h"

namespace xr::owner {

namespace {

// Within this of each other two caps are the same number (the telemetry is
// rounded to a tenth on the pages).
constexpr double kSameA = 0.5;

bool isNum(double v) { return std::isfinite(v); }

OwnerLimit limit(std::string id, std::string what, double amps, std::string why) {
  return OwnerLimit{std::move(id), std::move(what), amps, std::move(why)};
}

// The battery-temperature rules' cap (docs/batteries.md "Temperature rules").
void addBatteryTemp(const CommandCaps& c, std::vector<OwnerLimit>& out) {
  switch (c.batteryTempCause) {
    case BatteryTempCap::NO_PROBE:
      out.push_back(limit("battery_temp_required", "C/10 without a battery probe", c.batteryTempA,
                          "This battery type must not be charged fast without its temperature "
                          "(BatteryTempRequired) and no battery temperature sensor reads it, so the "
                          "charge is held to a tenth of the capacity. Fit a battery temperature sensor "
                          "to charge at the full rate."));
      break;
    case BatteryTempCap::WAITING_PROBE:
      out.push_back(limit("battery_temp_waiting", "Waiting for the battery temperature", c.batteryTempA,
                          "The battery temperature sensor has not answered yet; this battery type is not "
                          "charged until it does."));
      break;
    case BatteryTempCap::COLD_RAMP:
      out.push_back(limit("battery_cold_ramp", "Cold battery", c.batteryTempA,
                          "The battery is just above its lowest charging temperature; the current rises "
                          "as it warms (ChargeMinTempC to ChargeFullCurrentTempC)."));
      break;
    case BatteryTempCap::NONE:
      break;
  }
}

// The BMS's battery-current cap: its CCL, a warning ramp, the silent
// fallback; a Victron GX's limits are DVCC (docs/integrations.md).
void addBms(const Telemetry& t, std::vector<OwnerLimit>& out) {
  const CommandCaps& c = t.caps;
  if (!isNum(c.bmsA)) return;
  if (c.bmsSource == BmsSource::VictronGx && t.bms_state == BmsState::OK) {
    out.push_back(limit("dvcc", "DVCC (Victron GX)", c.bmsA,
                        "The Victron GX's distributed voltage and current control allows at most this "
                        "into the battery."));
    return;
  }
  switch (t.bms_state) {
    case BmsState::STALE:
      out.push_back(limit("bms_silent", "BMS silent", c.bmsA,
                          "The battery's management system stopped sending its limits; charging goes on "
                          "at a safe current (BmsFallbackCapA) until they come back."));
      break;
    case BmsState::WARNING:
      out.push_back(limit("bms_warning", "BMS warning", c.bmsA,
                          "The battery's management system warns; the charge ramps down before it would "
                          "disconnect the battery."));
      break;
    default:
      out.push_back(limit("bms_ccl", "BMS charge limit (CCL)", c.bmsA,
                          "The battery's management system allows at most this into the battery."));
      break;
  }
}

// The command path's caps while AUTO regulates (docs/control.md "Command path").
void addCommandPath(const CommandCaps& c, std::vector<OwnerLimit>& out) {
  const double rating = isNum(c.ratingA) ? c.ratingA : 1e300;
  if (isNum(c.rpmTableA) && isNum(c.rpmTableTopA) && c.rpmTableA < c.rpmTableTopA - kSameA)
    out.push_back(limit("rpm_table", "Engine speed", c.rpmTableA,
                        "At this engine speed the RPM table (rpmCapCurrentTable) allows this much; more "
                        "engine speed allows more."));
  else if (isNum(c.rpmTableTopA) && c.rpmTableTopA < rating - kSameA)
    out.push_back(limit("belt", "Belt limit", c.rpmTableTopA,
                        "The most the belt takes for long, set on the set-up page (the top of the RPM "
                        "table)."));
  if (isNum(c.thermalA))
    out.push_back(limit("thermal_derate", "Alternator hot", c.thermalA,
                        "The alternator is near its temperature limit (TemperatureLimitF); the current is "
                        "reduced to keep it there."));
  if (isNum(c.batteryMaxA) && c.batteryMaxA < rating - kSameA)
    out.push_back(limit("battery_max", "Battery current limit", c.batteryMaxA,
                        "The most the battery may take (MaximumAllowedBatteryAmps)."));
  if (isNum(c.warmupA))
    out.push_back(limit("warmup", "Warm-up", c.warmupA,
                        "Just after the field turns on, the current is held lower so a cold alternator "
                        "and belt are not loaded at once (WarmupCeilingAmps)."));
  if (isNum(c.fastOvA))
    out.push_back(limit("voltage_spike", "Voltage spike guard", c.fastOvA,
                        "The battery voltage rose fast or too high; the current is cut back until it "
                        "settles."));
  if (c.zeroBatteryHold)
    out.push_back(limit("zero_battery_current", "Battery held at 0 A", 0.0,
                        "The alternator carries the boat's loads and nothing goes into the battery "
                        "(MaintainMode, or resting after the charge with IdleZeroCurrent)."));
}

// A field held off by a wish, not a fault: weather, the owner, the BMS, the
// battery's temperature. Faults are the protections' banners; an engine at
// rest or a full battery is the state word, not a limit.
void addHold(const Telemetry& t, std::vector<OwnerLimit>& out) {
  switch (t.reason) {
    case Reason::REASON_WEATHER_MODE:
      out.push_back(limit("weather_hold", "Weather hold", 0.0,
                          "Weather mode leaves charging to solar today while the battery is above "
                          "WeatherModeMinSoC; switch weather mode off to charge from the engine."));
      break;
    case Reason::REASON_SYS_OFF:
      out.push_back(limit("switched_off", "Switched off", 0.0,
                          "You switched the regulator off; press Auto to charge."));
      break;
    case Reason::REASON_ONOFF_DISABLED:
      out.push_back(limit("onoff", "Charging switched off", 0.0, "The OnOff setting is off."));
      break;
    case Reason::REASON_BMS_DISABLED:
      out.push_back(limit("bms_stop", "BMS asks to stop", 0.0,
                          "The battery's management system asks for no charge (full, cold or protecting "
                          "its cells)."));
      break;
    case Reason::REASON_BATTERY_COLD:
    case Reason::REASON_BATTERY_HOT:
      out.push_back(limit(t.reason == Reason::REASON_BATTERY_COLD ? "battery_cold" : "battery_hot",
                          std::string(reasonTitle(t.reason)), 0.0,
                          "Charging waits until the battery temperature is back inside its charging range "
                          "(ChargeMinTempC to ChargeMaxTempC)."));
      break;
    default:
      break;
  }
}

}  // namespace

std::vector<OwnerLimit> ownerLimits(const Telemetry& t, const OwnerContext& ctx) {
  std::vector<OwnerLimit> out;
  if (t.mode == FieldControlMode::MODE_NORMAL_MANUAL)
    out.push_back(limit("manual", "Manual mode", kNoValue,
                        "The field is set by hand; the charging stages and current limits wait until you "
                        "press Auto."));
  if (t.mode == FieldControlMode::MODE_LIMP_HOME)
    out.push_back(limit("limp_home", "Limp home", kNoValue,
                        "A fixed field without the sensors' loops; press \"Limp home off\" once the sensors "
                        "are fixed."));
  if (!ctx.setUp)
    out.push_back(
        limit("not_set_up", "Not set up", kNoValue,
              "No battery type is chosen, so charging stays within limits every common battery "
              "takes" +
                  (ctx.setupLimits.empty() ? std::string() : " (" + ctx.setupLimits + ")") + ". " +
                  (t.setupBank.fromBattery ? setupBankNotice(t.setupBank)
                                           : std::string("Choose the battery on the set-up page."))));
  addHold(t, out);
  addBatteryTemp(t.caps, out);
  addBms(t, out);
  if (t.mode == FieldControlMode::MODE_NORMAL_AUTO_PID) addCommandPath(t.caps, out);
  // A cap at or above the alternator's rating holds nothing back (a 200 A
  // CCL on a 120 A alternator).
  const double rating = t.caps.ratingA;
  if (isNum(rating))
    std::erase_if(out, [&](const OwnerLimit& l) { return isNum(l.amps) && l.amps >= rating - kSameA; });
  if (t.mode == FieldControlMode::MODE_NORMAL_AUTO_PID) {
    // Nothing below the alternator's rating: the rating is what limits.
    const bool capped =
        std::any_of(out.begin(), out.end(), [](const OwnerLimit& l) { return isNum(l.amps); });
    const CommandCaps& c = t.caps;
    if (!capped && isNum(c.ratingA) && isNum(c.commandA) && c.commandA >= c.ratingA - kSameA)
      out.push_back(limit("alternator_rating", "Alternator rating", c.ratingA,
                          "The most this alternator is asked for (MaxTableValue)."));
  }
  // Most restrictive first: the limits that are not a current (manual, not
  // set up) lead, then by amps; equal amps keep the chain's order.
  std::stable_sort(out.begin(), out.end(), [](const OwnerLimit& a, const OwnerLimit& b) {
    if (isNum(a.amps) != isNum(b.amps)) return !isNum(a.amps);
    return isNum(a.amps) && a.amps < b.amps - 1e-9;
  });
  return out;
}

}  // namespace xr::owner
