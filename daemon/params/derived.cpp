#include "params/derived.h"

#include <algorithm>

#include "params/constants.h"

namespace xr {

SystemClass bankClassOfVoltage(double volts) {
  if (volts < 18.0) return SystemClass::V12;
  if (volts <= 36.0) return SystemClass::V24;
  return SystemClass::V48;
}

SystemClass systemClass(const Params& p) { return bankClassOfVoltage(p.BulkVoltage); }

bool isBankVoltage(const ParamSpec& spec, double value) {
  if (spec.unit != "V") return false;
  if (spec.min >= 8.0) return true;
  const bool zeroMeansDerived = spec.name == "AlternatorHardShutdownV" || isDerivedWhenZero(spec.name);
  return zeroMeansDerived && value > 0.0;
}

bool isDerivedWhenZero(std::string_view name) {
  return name == "VoltageAlarmHigh" || name == "VoltageAlarmLow" || name == "ChargedVoltage" ||
         name == "RebulkVoltage" || name == "TargetVoltageSetpoint" || name == "TempAlarm";
}

double bankScale(const Params& p) { return nominalVoltage(systemClass(p)) / 12.0; }

// The 12 V figures are the specification's / catalogue's former defaults
// (docs/parameters.md), scaled with the bank like the battery profiles.
double voltageAlarmHighV(const Params& p) {
  if (p.VoltageAlarmHigh > 0.0) return p.VoltageAlarmHigh;
  const double s = bankScale(p);
  return std::max(15.0 * s, p.BulkVoltage + k::HARD_SHUTDOWN_DEFAULT_OFFSET_V * s);
}

double voltageAlarmLowV(const Params& p) {
  return p.VoltageAlarmLow > 0.0 ? p.VoltageAlarmLow : 11.0 * bankScale(p);
}

double chargedVoltageV(const Params& p) {
  return p.ChargedVoltage > 0.0 ? p.ChargedVoltage : std::min(13.8 * bankScale(p), p.AbsorptionVoltage);
}

double rebulkVoltageV(const Params& p) {
  if (p.RebulkVoltage > 0.0) return p.RebulkVoltage;
  const double s = bankScale(p);
  return std::min(12.9 * s, p.FloatVoltage - 0.1 * s);
}

double targetVoltageSetpointV(const Params& p) {
  return p.TargetVoltageSetpoint > 0.0 ? p.TargetVoltageSetpoint
                                       : std::min(13.6 * bankScale(p), p.BulkVoltage);
}

double tempAlarmF(const Params& p) {
  return p.TempAlarm > 0.0 ? p.TempAlarm : p.TemperatureLimitF + kTempAlarmDerivedMarginF;
}

int nominalVoltage(SystemClass c) { return static_cast<int>(c); }

std::optional<SystemClass> bankClassOfReading(double volts) {
  for (SystemClass c : {SystemClass::V12, SystemClass::V24, SystemClass::V48}) {
    const double k = nominalVoltage(c) / 12.0;
    if (volts >= kBankReadingLowV12 * k && volts <= kBankReadingHighV12 * k) return c;
  }
  return std::nullopt;  // NaN lands here too
}

Params withBankClass(const Params& in, SystemClass c) {
  Params p = in;
  const double k = double(nominalVoltage(c)) / nominalVoltage(systemClass(in));
  for (const ParamSpec& spec : catalogue()) {
    if (spec.kind != ParamKind::Float) continue;
    const double v = spec.get(in, 0);
    if (isBankVoltage(spec, v)) spec.set(p, 0, v * k);
  }
  p.SetupCeilingV = in.SetupCeilingV * k;
  p.SetupBankFromBattery = false;
  return p;
}

VoltageRange plausibleVoltageRange(const Params& p) {
  // docs/protections.md "Protections": the specification's table, which
  // already includes its 0.5 V buffer.
  switch (systemClass(p)) {
    case SystemClass::V12:
      return {4.5, 15.5};
    case SystemClass::V24:
      return {9.0, 30.5};
    case SystemClass::V48:
      return {18.0, 60.5};
  }
  return {4.5, 15.5};
}

double maxCommandableAmps(const Params& p) {
  if (p.capLimitMode != 0) return p.MaxTableValue;
  double cap = 0.0;
  for (std::size_t i = 0; i < RPM_TABLE_SIZE; ++i)
    cap = std::max({cap, p.rpmCapCurrentTable[i], p.rpmCapCurrentTableLo[i]});
  return std::min(cap, p.MaxTableValue);
}

double currentAlarmHighAmps(const Params& p) {
  constexpr double kDerivedMargin = 1.10;
  return p.CurrentAlarmHigh > 0.0 ? p.CurrentAlarmHigh : maxCommandableAmps(p) * kDerivedMargin;
}

double criticalDisagreementThreshold(const Params& p) {
  switch (systemClass(p)) {
    case SystemClass::V12:
      return k::DISAGREE_CRITICAL_12V;
    case SystemClass::V24:
      return k::DISAGREE_CRITICAL_24V;
    case SystemClass::V48:
      return k::DISAGREE_CRITICAL_48V;
  }
  return k::DISAGREE_CRITICAL_12V;
}

double voltageHardwareLimit(const Params& p) {
  return p.SetupBankFromBattery ? kBankReadingBovlV : p.BulkVoltage + k::INA_OV_OFFSET_V;
}

double hardOCTripAmps(const Params& p) { return p.MaxTableValue + k::HARD_OC_OFFSET_A; }

}  // namespace xr
