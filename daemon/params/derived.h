#pragma once
// Values derived from parameters, computed in one place.
#include <optional>
#include <string_view>

#include "params/constants.h"
#include "params/params.h"

namespace xr {

enum class SystemClass { V12 = 12, V24 = 24, V48 = 48 };

// The one rule for which bank a battery voltage belongs to, whether a
// set-point or a measurement: below 18 V a 12 V bank, up to 36 V a 24 V bank,
// above a 48 V bank. The splits lie between what two neighbouring classes can
// show: a 12 V bank equalising reaches ~16.5 V and a 24 V bank is ruined long
// before 18 V; a 24 V bank equalising reaches ~32.4 V and a 48 V bank is flat
// at ~40 V (docs/deviations.md "One bank-class rule").
SystemClass bankClassOfVoltage(double volts);
// bankClassOfVoltage(BulkVoltage) (docs/protections.md "Voltage
// Plausibility Ranges").
SystemClass systemClass(const Params& p);
// An absolute battery voltage (a set-point or an alarm: unit V, catalogue
// minimum 8 V, or AlternatorHardShutdownV when set), which must belong to
// the bank's class; `value` is the parameter's value.
bool isBankVoltage(const ParamSpec& spec, double value);
int nominalVoltage(SystemClass c);

// Not set up: the class of a measured bank voltage, or nullopt when the
// reading fits none (docs/configuration.md "Not set up"). A 12 V bank reads
// 10-16 V whatever its chemistry and state: a LiFePO4 bank at its BMS's low
// cut-off (2.5 V per cell) up to a flooded bank equalising; 20-32 V and
// 40-64 V for 24 and 48 V. 18 V, 36 V or 0 V (a cut sense wire) fit no bank:
// the caller stays at the 12 V limits and says so.
std::optional<SystemClass> bankClassOfReading(double volts);
inline constexpr double kBankReadingLowV12 = 10.0;
inline constexpr double kBankReadingHighV12 = 16.0;
// p for a bank of class c: every bank voltage set (isBankVoltage: the
// stages, the alarms, the hard shutdown...) and SetupCeilingV scaled from
// p's class to c; SetupBankFromBattery cleared. Pure, no heap.
Params withBankClass(const Params& p, SystemClass c);
// The INA228 bus limit while the bank class is still being read: above every
// class's reading window, so the chip cannot alert before the first reading
// (the field is off until then).
inline constexpr double kBankReadingBovlV = 4.0 * kBankReadingHighV12 + 1.0;

struct VoltageRange {
  double min;
  double max;
};
// 12 V: 4.5–15.5 V, 24 V: 9.0–30.5 V, 48 V: 18.0–60.5 V (0.5 V buffer included).
VoltageRange plausibleVoltageRange(const Params& p);

// The most alternator current the regulator may ask for: the RPM cap tables
// (both charge rates) clipped by MaxTableValue; MaxTableValue alone with the
// power cap (capLimitMode 1).
double maxCommandableAmps(const Params& p);
// The alternator current alarm in force: CurrentAlarmHigh, or when it is 0,
// 10 % above maxCommandableAmps (docs/deviations.md "CurrentAlarmHigh follows
// the cap").
double currentAlarmHighAmps(const Params& p);
// 1 / 2 / 4 V by system class.
double criticalDisagreementThreshold(const Params& p);
// AlternatorHardShutdownV, or BulkVoltage + 0.3 V when it is 0 (it then
// follows BulkVoltage; docs/deviations.md "AlternatorHardShutdownV").
inline double alternatorHardShutdownV(const Params& p) {
  return p.AlternatorHardShutdownV > 0.0 ? p.AlternatorHardShutdownV
                                         : p.BulkVoltage + k::HARD_SHUTDOWN_DEFAULT_OFFSET_V;
}
// Values that follow what they depend on (docs/configuration.md "Derived
// values"): each parameter's 0 (its default) means "derived"; a value the
// owner wrote is used as written (the checks keep it consistent).
// bankScale: 1 / 2 / 4 for a 12 / 24 / 48 V bank (the class of BulkVoltage).
double bankScale(const Params& p);
// VoltageAlarmHigh: 15 V per 12 V, and at least 0.5 V per 12 V above
// BulkVoltage, so it never sounds in a bulk charge.
double voltageAlarmHighV(const Params& p);
// VoltageAlarmLow: 11 V per 12 V.
double voltageAlarmLowV(const Params& p);
// ChargedVoltage: 13.8 V per 12 V, at most AbsorptionVoltage (reachable).
double chargedVoltageV(const Params& p);
// RebulkVoltage: 12.9 V per 12 V, at least 0.1 V per 12 V under FloatVoltage.
double rebulkVoltageV(const Params& p);
// TargetVoltageSetpoint: 13.6 V per 12 V, at most BulkVoltage.
double targetVoltageSetpointV(const Params& p);
// TempAlarm: TemperatureLimitF + 40 degF (the specification's 150 / 190 degF gap), so
// the buzzer follows a raised alternator limit.
double tempAlarmF(const Params& p);
inline constexpr double kTempAlarmDerivedMarginF = 40.0;
// True for the parameters whose 0 means "derived" (the six above).
bool isDerivedWhenZero(std::string_view name);

// BulkVoltage + 0.3 V: programmed into the INA228 BOVL register
// (kBankReadingBovlV while SetupBankFromBattery).
double voltageHardwareLimit(const Params& p);
// MaxTableValue + 10 A.
double hardOCTripAmps(const Params& p);

}  // namespace xr
