#pragma once
// State of every protection, exported per tick. Owned by daemon/protection;
// fields are added here as they are implemented.
#include "core/modes.h"

namespace xr {

struct ProtectionTelemetry {
  ShutdownPhase shutdownPhase = ShutdownPhase::PHASE_NONE;
  bool nearBulk = false;
  double fastOvCurrentCap = 0.0;
  bool fastOvClampActive = false;
  bool inaOvervoltageLatched = false;
  bool lockoutActive = false;
  double lockoutRemainingS = 0.0;
  bool tempTaskAlarm = false;
  bool buzzer = false;
  Reason lastTripReason = Reason::NONE;
  double lastTripTimeS = 0.0;
};

}  // namespace xr
