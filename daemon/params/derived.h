#pragma once
// Values derived from parameters, computed in one place (foundation issue).
#include "params/constants.h"
#include "params/params.h"

namespace xr {

enum class SystemClass { V12 = 12, V24 = 24, V48 = 48 };

// From BulkVoltage: < 18 V -> 12 V, 18–36 V -> 24 V, > 36 V -> 48 V
// (architecture-legacy.md "Voltage Plausibility Ranges").
SystemClass systemClass(const Params& p);
int nominalVoltage(SystemClass c);

struct VoltageRange {
  double min;
  double max;
};
// 12 V: 4.5–15.5 V, 24 V: 9.0–30.5 V, 48 V: 18.0–60.5 V (0.5 V buffer included).
VoltageRange plausibleVoltageRange(const Params& p);
// 1 / 2 / 4 V by system class.
double criticalDisagreementThreshold(const Params& p);
// AlternatorHardShutdownV, or BulkVoltage + 0.3 V when it is 0 (it then
// follows BulkVoltage; docs/deviations.md "AlternatorHardShutdownV").
inline double alternatorHardShutdownV(const Params& p) {
  return p.AlternatorHardShutdownV > 0.0 ? p.AlternatorHardShutdownV
                                         : p.BulkVoltage + k::HARD_SHUTDOWN_DEFAULT_OFFSET_V;
}
// BulkVoltage + 0.3 V: programmed into the INA228 BOVL register.
double voltageHardwareLimit(const Params& p);
// MaxTableValue + 10 A.
double hardOCTripAmps(const Params& p);

}  // namespace xr
