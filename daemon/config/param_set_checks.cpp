// checkConsistency (config.h): the checks on a whole parameter set, the one
// home every layer calls (the file, the scenario's [config], the stored
// dashboard overrides, PATCH, MQTT): docs/configuration.md "Checks on the
// whole set".
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>

#include "config/battery_profiles.h"
#include "config/config.h"
#include "config/format.h"
#include "params/derived.h"

namespace xr {

namespace {

// "voltage.BulkVoltage": the key as the file writes it.
std::string dotted(const char* name) {
  const ParamSpec* s = findParam(name);
  return std::string(tomlTableName(s->group)) + "." + name;
}

using ErrFn = std::function<void(const char*, std::string)>;
constexpr double kMinDutyCeiling = 50.0;      // %
constexpr double kInsulationClassHF = 356.0;  // degF: 180 degC, IEC 60085 class H
// A value for the owner's eyes (the dashboard shows these messages): a
// temperature in °F also in °C, "degC" as °C; a margin ("dF": "+ 2 °F")
// stays °F only, as a margin does not convert with the offset.
std::string withUnit(double x, const char* unit) {
  const std::string u(unit);
  if (u == "degF")
    return formatNumber(x) + " °F (" + formatNumber(std::round((x - 32.0) * 5.0 / 9.0)) + " °C)";
  if (u == "dF") return formatNumber(x) + " °F";
  if (u == "degC") return formatNumber(x) + " °C";
  return formatNumber(x) + " " + u;
}
// "88 °C (190 °F)": the owner's unit first (the pages default to °C), the
// parameter's own beside it.
std::string tempText(double degF) {
  const double c = std::round((degF - 32.0) / 1.8 * 10.0) / 10.0;
  return formatNumber(c) + " \u00B0C (" + formatNumber(degF) + " \u00B0F)";
}

// Every absolute battery voltage belongs to the bank that BulkVoltage names:
// a 28.8 V value among 12 V ones would charge, trip or alarm a 12 V bank as
// if it were a 24 V one (docs/configuration.md "Checks on the whole set").
void checkBankClass(const Params& p, const ErrFn& err) {
  const int bank = nominalVoltage(systemClass(p));
  for (const ParamSpec& spec : catalogue()) {
    if (spec.kind == ParamKind::Table || spec.name == "BulkVoltage") continue;
    const double value = spec.get(p, 0);
    if (!isBankVoltage(spec, value)) continue;
    const int cls = nominalVoltage(bankClassOfVoltage(value));
    if (cls != bank)
      err(std::string(spec.name).c_str(), std::string(spec.name) + " " + withUnit(value, "V") + " is for a " +
                                              std::to_string(cls) + " V bank; BulkVoltage " +
                                              withUnit(p.BulkVoltage, "V") + " makes this a " +
                                              std::to_string(bank) + " V bank");
  }
}

// The alternator current alarm must sit clear of what the regulator is
// allowed to command: held at a 100 A cap, a 100 A alarm sounds every few
// seconds of a normal charge. 5 % clears the reading's ripple at the cap.
// 0 is derived above it (params/derived.h currentAlarmHighAmps).
void checkCurrentAlarm(const Params& p, const ErrFn& err) {
  constexpr double kAlarmMargin = 1.05;
  const double cap = maxCommandableAmps(p);
  if (p.CurrentAlarmHigh > 0.0 && p.CurrentAlarmHigh < cap * kAlarmMargin)
    err("CurrentAlarmHigh", "CurrentAlarmHigh " + withUnit(p.CurrentAlarmHigh, "A") +
                                " must be at least 5 % above the most current the regulator may command, " +
                                withUnit(cap, "A") + " (MaxTableValue and the RPM cap tables): at least " +
                                withUnit(std::ceil(cap * kAlarmMargin), "A"));
}

// Sets whose values are each in range but together unsafe or noisy
// (docs/configuration.md "Checks on the whole set").
void checkBankAndAlarmSet(const Params& p, const ErrFn& err) {
  checkBankClass(p, err);
  // The duty floor holds the field up whatever the voltage does: at or
  // above the ceiling there is no regulation at all, and above half field
  // a light load is overcharged at cruising speed.
  if (p.MinDuty >= p.MaxDuty)
    err("MinDuty", "MinDuty " + withUnit(p.MinDuty, "%") + " must be below MaxDuty " +
                       withUnit(p.MaxDuty, "%") + ": the field would not be regulated");
  else if (p.MinDuty > kMinDutyCeiling)
    err("MinDuty", "MinDuty " + withUnit(p.MinDuty, "%") + " is above " + withUnit(kMinDutyCeiling, "%") +
                       ": a floor that high charges whatever the battery voltage says");
  // An alarm at or inside what the regulator is allowed to do sounds in
  // normal operation, and the owner learns to ignore it.
  // Only a value the owner wrote can fail these: 0 derives one clear above
  // (params/derived.h).
  if (voltageAlarmHighV(p) <= p.BulkVoltage)
    err("VoltageAlarmHigh", "the high battery voltage alarm (VoltageAlarmHigh) " +
                                withUnit(voltageAlarmHighV(p), "V") + " must be above the bulk voltage " +
                                withUnit(p.BulkVoltage, "V") +
                                ": it would sound in every bulk charge; set it to 0 to follow the bank");
  if (tempAlarmF(p) <= p.TemperatureLimitF)
    err("TempAlarm", "the alternator temperature alarm (TempAlarm) " + tempText(tempAlarmF(p)) +
                         " must be above the alternator temperature limit " + tempText(p.TemperatureLimitF) +
                         ": the regulator holds the alternator at the limit, so the alarm would sound; set "
                         "it to 0 to follow the limit");
  checkCurrentAlarm(p, err);
  // The T3 cut may not lie beyond what any alternator's winding is rated
  // for: class H insulation, 180 degC (IEC 60085), the highest in use.
  const double t3 = p.TemperatureLimitF + p.TempCritExcess;
  if (t3 > kInsulationClassHF)
    err("TemperatureLimitF", "TemperatureLimitF " + withUnit(p.TemperatureLimitF, "degF") +
                                 " + TempCritExcess " + withUnit(p.TempCritExcess, "dF") + " = " +
                                 withUnit(t3, "degF") + " is above " + withUnit(kInsulationClassHF, "degF") +
                                 ", the class H insulation limit: the alternator would burn before the cut");
}

}  // namespace

std::vector<ConfigError> checkConsistency(const Params& p, std::string_view file) {
  std::vector<ConfigError> errs;
  const std::string f(file.empty() ? std::string_view("params") : file);
  auto err = [&](const char* key, std::string msg) {
    errs.push_back({f, 0, 0, dotted(key), std::move(msg)});
  };
  auto v = withUnit;

  if (p.AbsorptionVoltage > p.BulkVoltage)
    err("AbsorptionVoltage", v(p.AbsorptionVoltage, "V") + " is above BulkVoltage " + v(p.BulkVoltage, "V") +
                                 "; it must not exceed it");
  if (p.FloatVoltage > p.AbsorptionVoltage)
    err("FloatVoltage", v(p.FloatVoltage, "V") + " is above AbsorptionVoltage " +
                            v(p.AbsorptionVoltage, "V") + "; it must not exceed it");
  if (rebulkVoltageV(p) >= p.FloatVoltage)
    err("RebulkVoltage", v(rebulkVoltageV(p), "V") + " must be below FloatVoltage " + v(p.FloatVoltage, "V"));
  // A software trip at or below the charging target would trip in normal
  // bulk charging (docs/protections.md "Protections").
  if (p.AlternatorHardShutdownV != 0.0 && p.AlternatorHardShutdownV <= p.BulkVoltage)
    err("AlternatorHardShutdownV", v(p.AlternatorHardShutdownV, "V") + " must be above BulkVoltage " +
                                       v(p.BulkVoltage, "V") +
                                       " (or 0 for the first-boot default BulkVoltage + 0.3 V)");
  // The INA228 hardware limit is BulkVoltage + 0.3 V: a higher target would
  // trip the hardware ALERT in normal operation.
  if (targetVoltageSetpointV(p) > voltageHardwareLimit(p))
    err("TargetVoltageSetpoint", v(targetVoltageSetpointV(p), "V") + " is above the INA228 hardware limit " +
                                     v(voltageHardwareLimit(p), "V") + " (BulkVoltage + 0.3 V)");
  {
    const auto range = plausibleVoltageRange(p);
    if (p.FloatVoltage < range.min || rebulkVoltageV(p) < range.min)
      err("FloatVoltage",
          "FloatVoltage/RebulkVoltage must lie in the plausible range of the system class set by "
          "BulkVoltage (" +
              v(range.min, "V") + " to " + v(range.max, "V") + ")");
  }
  checkBankAndAlarmSet(p, err);
  if (voltageAlarmLowV(p) >= voltageAlarmHighV(p))
    err("VoltageAlarmLow",
        v(voltageAlarmLowV(p), "V") + " must be below VoltageAlarmHigh " + v(voltageAlarmHighV(p), "V"));
  if (p.TempAlarmLow != 0.0 && p.TempAlarmLow >= tempAlarmF(p))
    err("TempAlarmLow", tempText(p.TempAlarmLow) + " must be below the alternator temperature alarm " +
                            tempText(tempAlarmF(p)));
  if (p.TempWarnExcess >= p.TempCritExcess)
    err("TempWarnExcess", v(p.TempWarnExcess, "dF") + " must be below TempCritExcess " +
                              v(p.TempCritExcess, "dF") + " (T1 warning fires before T3 cut)");
  if (p.SOC_AllowRebulk_percent > p.SOC_BlockRebulk_percent)
    err("SOC_AllowRebulk_percent", v(p.SOC_AllowRebulk_percent, "%") + " is above SOC_BlockRebulk_percent " +
                                       v(p.SOC_BlockRebulk_percent, "%"));
  if (!(p.LoadDumpDtThresh1 >= p.LoadDumpDtThresh && p.LoadDumpDtThresh >= p.LoadDumpDtThresh3))
    err("LoadDumpDtThresh",
        "load dump tiers must satisfy LoadDumpDtThresh1 >= LoadDumpDtThresh >= LoadDumpDtThresh3 (" +
            formatNumber(p.LoadDumpDtThresh1) + ", " + formatNumber(p.LoadDumpDtThresh) + ", " +
            formatNumber(p.LoadDumpDtThresh3) + " A/s)");
  // The battery profile's own limits (docs/batteries.md): LiFePO4 cell voltage,
  // inverted temperature ranges.
  for (auto& pr : checkProfileLimits(p))
    errs.push_back({f, 0, 0, dotted(pr.name.c_str()), std::move(pr.message)});
  for (std::size_t i = 1; i < RPM_TABLE_SIZE; ++i) {
    if (p.rpmTableRPMPoints[i] <= p.rpmTableRPMPoints[i - 1]) {
      err("rpmTableRPMPoints", "breakpoints must be strictly ascending (element " + std::to_string(i) +
                                   " = " + formatNumber(p.rpmTableRPMPoints[i]) +
                                   " RPM is not above element " + std::to_string(i - 1) + " = " +
                                   formatNumber(p.rpmTableRPMPoints[i - 1]) + " RPM)");
      break;
    }
  }
  return errs;
}

}  // namespace xr
