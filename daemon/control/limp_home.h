#pragma once
// Limp Home (docs/control.md "Limp Home"): operator-toggled emergency mode.
// handleLimpHome() ramps the duty to LIMP_HOME_DUTY (30 %) through the normal
// governor slew; mode selection has already bypassed every protection except
// the INA228 hardware ALERT latch. One log event per LIMP_HOME_LOG_MS.
#include "control/governor.h"
#include "core/events.h"
#include "core/time.h"
#include "params/constants.h"

namespace xr {

class LimpHome {
 public:
  double handleLimpHome(TimeNs now, double lastApplied, double rpmMinDuty, double dtSec,
                        const GovernorLimits& lim, EventBatch& ev) {
    if (!logged_ || now - lastLog_ >= fromMs(k::LIMP_HOME_LOG_MS)) {
      ev.push(makeEvent(now, EventLevel::Warning, EventCode::LimpHomeActive, Reason::REASON_LIMP_HOME,
                        k::LIMP_HOME_DUTY, 0.0, 0, FieldControlMode::MODE_LIMP_HOME));
      lastLog_ = now;
      logged_ = true;
    }
    return governorApply(lastApplied, k::LIMP_HOME_DUTY, GovMode::GOV_NORMAL_SLEW, rpmMinDuty, dtSec, lim);
  }
  void reset() { logged_ = false; }

 private:
  bool logged_ = false;  // the Limp Home event was told
  TimeNs lastLog_ = 0;   // when (it repeats at a slow cadence)
};

}  // namespace xr
