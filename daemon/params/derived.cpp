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
  return spec.unit == "V" && (spec.min >= 8.0 || (spec.name == "AlternatorHardShutdownV" && value > 0.0));
}

int nominalVoltage(SystemClass c) { return static_cast<int>(c); }

VoltageRange plausibleVoltageRange(const Params& p) {
  // docs/protections.md "Protections": the seed's table, which
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

double voltageHardwareLimit(const Params& p) { return p.BulkVoltage + k::INA_OV_OFFSET_V; }

double hardOCTripAmps(const Params& p) { return p.MaxTableValue + k::HARD_OC_OFFSET_A; }

}  // namespace xr
