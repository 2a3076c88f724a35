// The owner model's state, hero value, SoC and BMS words (owner_model.h);
// the limits are owner_limits.cpp's.
#include "owner/owner_model.h"

#include <cmath>
#include <cstdio>

namespace xr::owner {

namespace {

bool isNum(double v) { return std::isfinite(v); }

// Regulating: the field follows a loop or the owner's hand, not a ramp down.
bool regulating(FieldControlMode m) {
  return m == FieldControlMode::MODE_NORMAL_AUTO_PID || m == FieldControlMode::MODE_NORMAL_MANUAL ||
         m == FieldControlMode::MODE_LIMP_HOME;
}

// More than this from the alternator is "charging" (a field that is on but
// barely excited is not).
constexpr double kChargingA = 0.5;

bool charging(const Telemetry& t) { return t.field_enable && isNum(t.alt_a) && t.alt_a > kChargingA; }

std::string_view modeWord(FieldControlMode m) {
  switch (m) {
    case FieldControlMode::MODE_CRITICAL_RAMP:
      return "Shutting down (fault)";
    case FieldControlMode::MODE_WARNING_RAMP_AND_LOCKOUT:
      return "Pausing (protection)";
    case FieldControlMode::MODE_LOCKOUT_RAMP:
      return "Cooling down";
    default:
      return "Switching off";
  }
}

// "Charging · Bulk", "Alternator on · Bulk" (the loads still take more than
// it gives), "Stopping · Alternator too hot", "Not charging · Weather mode:
// solar first"; "limited by" names the first limit while a cap holds bulk.
std::string stateWords(const Telemetry& t, const std::vector<OwnerLimit>& limits) {
  std::string why(reasonTitle(t.reason));
  if (why.empty() && t.control.sysMode == SysMode::SYS_MODE_OFF) why = "Switched off";
  if (charging(t) && !regulating(t.mode))
    return "Stopping · " + (why.empty() ? std::string(modeWord(t.mode)) : why);
  if (!charging(t)) return why.empty() ? "Not charging" : "Not charging · " + why;
  if (t.mode == FieldControlMode::MODE_NORMAL_MANUAL) return "Charging · Manual";
  if (t.mode == FieldControlMode::MODE_LIMP_HOME) return "Charging · Limp home";
  const bool stillDischarging = isNum(t.bcur_a) && t.bcur_a < -kChargingA;
  std::string s =
      std::string(stillDischarging ? "Alternator on" : "Charging") + " · " + std::string(stageWord(t.stage));
  // In bulk without the voltage loop the current cap is what sets the charge.
  const bool capSets = t.stage == ChargeStage::BULK && !t.control.voltageControlActive;
  if (capSets && !limits.empty() && isNum(limits.front().amps)) s += " · limited by " + limits.front().what;
  return s;
}

// The one number: the battery current while charging, else the SoC when
// known, else the battery voltage.
OwnerHero hero(const Telemetry& t, const OwnerSoc& soc) {
  if (charging(t)) {
    if (isNum(t.bcur_a))
      return {std::fabs(t.bcur_a), "A", t.bcur_a >= 0 ? "into the battery" : "out of the battery"};
    return {t.alt_a, "A", "from the alternator"};
  }
  if (isNum(soc.pct)) return {soc.pct, "%", "state of charge"};
  return {t.battery_v, "V", "battery"};
}

std::string_view bmsSourceWord(BmsSource s) {
  switch (s) {
    case BmsSource::Can:
      return "CAN";
    case BmsSource::VictronGx:
      return "Victron GX";
    case BmsSource::Sim:
      return "simulated";
    case BmsSource::None:
      break;
  }
  return "";
}

OwnerBms bms(const Telemetry& t) {
  const std::string via = std::string(bmsSourceWord(t.caps.bmsSource));
  const std::string suffix = via.empty() ? "" : " (" + via + ")";
  switch (t.bms_state) {
    case BmsState::OFF:
      return {"none", "no BMS"};
    case BmsState::OK:
      return {"talking", "talking" + suffix};
    case BmsState::WARNING:
      return {"warning", "talking, warns" + suffix};
    case BmsState::CHARGE_DISABLED:
      return {"no_charge", "asks for no charge" + suffix};
    case BmsState::STALE:
      return {"silent", "silent: no limits received" + suffix};
  }
  return {"none", "no BMS"};
}

}  // namespace

std::string_view stageWord(ChargeStage s) {
  switch (s) {
    case ChargeStage::BULK:
      return "Bulk";
    case ChargeStage::ABSORPTION:
      return "Absorption";
    case ChargeStage::FLOAT:
      return "Float";
    case ChargeStage::IDLE:
      return "Resting";
  }
  return "Bulk";
}

OwnerSoc ownerSoc(const Telemetry& t) {
  const SocShown s = socShown(t);
  switch (s.source) {
    case SocShownSource::BMS:
      return {s.pct, "bms"};
    case SocShownSource::COUNTED:
      return {s.pct, "counted"};
    case SocShownSource::OCV_ESTIMATE:
      return {s.pct, "ocv_estimate"};
    case SocShownSource::UNKNOWN:
      break;
  }
  return {kNoValue, "unknown"};
}

OwnerModel ownerModel(const Telemetry& t, const OwnerContext& ctx) {
  OwnerModel m;
  m.limits = ownerLimits(t, ctx);
  m.soc = ownerSoc(t);
  m.hero = hero(t, m.soc);
  m.bms = bms(t);
  m.state = (ctx.setUp ? "" : "Not set up · ") + stateWords(t, m.limits);
  if (!ctx.setUp) m.notice = setupBankNotice(t.setupBank);
  return m;
}

std::string setupBankNotice(const Telemetry::SetupBank& b) {
  if (!b.fromBattery) return "";
  char v[32];
  std::snprintf(v, sizeof v, "%.1f V", b.readV);
  if (b.fits)
    return std::string("The bank reads ") + v + ": choose " + std::to_string(b.classV) +
           " V on the set-up page.";
  const std::string read = std::isfinite(b.readV)
                               ? std::string("The bank reads ") + v + ", which fits no 12, 24 or 48 V bank"
                               : std::string("No battery voltage reading yet");
  return read +
         ": charging stays within the 12 V limits. Check the battery voltage wire, then choose the "
         "bank on the set-up page.";
}

std::string limitedByText(const OwnerModel& m) {
  if (m.limits.empty()) return "nothing";
  const OwnerLimit& l = m.limits.front();
  if (!isNum(l.amps)) return l.what;
  char amps[32];
  std::snprintf(amps, sizeof amps, "%.0f A", l.amps);
  return l.what + ": " + amps;
}

}  // namespace xr::owner

namespace xr::owner {

// The same titles as the dashboard's banners (web/www/js/names.js).
std::string_view reasonTitle(Reason r) {
  switch (r) {
    case Reason::NONE:
      return "";
    case Reason::REASON_INA_OVERVOLTAGE:
      return "Battery over-voltage";
    case Reason::REASON_HARD_OVERCURRENT:
      return "Alternator over-current";
    case Reason::REASON_TEMP_CRITICAL:
      return "Alternator far too hot";
    case Reason::REASON_RPM_LOW:
      return "Engine stopped or idling";
    case Reason::REASON_ALT_HARD_SHUTDOWN:
      return "Battery voltage too high";
    case Reason::REASON_VOLTAGE_DISAGREE_WARNING:
      return "Voltage sensors disagree";
    case Reason::REASON_VOLTAGE_DISAGREE_CRITICAL:
      return "Voltage sensors far apart";
    case Reason::REASON_VOLTAGE_IMPLAUSIBLE:
      return "Battery voltage makes no sense";
    case Reason::REASON_TEMP_WARNING:
      return "Alternator too hot";
    case Reason::REASON_TEMP_SUSTAINED:
      return "Alternator stayed too hot";
    case Reason::REASON_TEMP_STALE:
      return "Temperature sensor not answering";
    case Reason::REASON_CURRENT_STALE:
      return "Current sensor not answering";
    case Reason::REASON_LOCKOUT:
      return "Cooling down after a shutdown";
    case Reason::REASON_AUTO_ZERO:
      return "Re-zeroing the current sensor";
    case Reason::REASON_IGNITION_OFF:
      return "Ignition off";
    case Reason::REASON_ONOFF_DISABLED:
      return "Charging switched off in the settings";
    case Reason::REASON_BMS_DISABLED:
      return "Battery management asks to stop";
    case Reason::REASON_WEATHER_MODE:
      return "Weather mode: solar first";
    case Reason::REASON_IDLE_STAGE:
      return "Battery full, resting";
    case Reason::REASON_SYS_OFF:
      return "Switched off";
    case Reason::REASON_LIMP_HOME:
      return "Limp home";
    case Reason::REASON_SYSTEM_ID:
      return "Measuring the alternator";
    case Reason::REASON_BMS_STALE:
      return "Battery management silent";
    case Reason::REASON_BATTERY_COLD:
      return "Battery too cold to charge";
    case Reason::REASON_BATTERY_HOT:
      return "Battery too hot to charge";
    case Reason::REASON_TEMP_SOAK:
      return "Alternator cooling after the engine stop";
    case Reason::REASON_BANK_MISMATCH:
      return "Settings are for another bank size";
  }
  return "";
}

}  // namespace xr::owner
