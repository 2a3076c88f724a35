#pragma once
// Outputs of one control tick. The runtime writes dutyPct to the PWM,
// fieldEnable to GPIO4 and buzzer to GPIO21, and asks the INA228 driver for
// the requested conversion mode and BOVL threshold. Beside the Regulator
// (not in daemon/core) because it carries the whole Telemetry.
#include "control/telemetry.h"
#include "core/events.h"

namespace xr {

struct Outputs {
  double dutyPct = 0.0;       // 0..100
  bool fieldEnable = false;   // GPIO4
  bool buzzer = false;        // GPIO21
  bool inaFastMode = false;   // request: fast conversions while the field is on
  double inaBovlVolts = 0.0;  // VoltageHardwareLimit to program into BOVL
  EventBatch events;          // what happened this tick
  Telemetry telemetry;
};

}  // namespace xr
