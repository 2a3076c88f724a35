// BatteryHealth (docs/batteries.md "Measured capacity", "Internal resistance").
#include "battery/battery_health.h"

#include "battery/monitor_helpers.h"

namespace xr {

using namespace battery_detail;

bool BatteryHealth::update(const HealthInput& in) noexcept {
  const bool sample = resistance_.update(in.dt_s, in.amps, in.volts, in.tempC, in.capacityAh);
  bmsSocPct_ = in.bmsSocPct;
  return sample;
}

bool BatteryHealth::knownSoc(TimeNs now, double socPct, bool full, double capacityAh,
                             EventBatch& ev) noexcept {
  const CapacityPointResult r = capacity_.knownSoc(socPct, full, capacityAh);
  if (r != CapacityPointResult::Measured) return false;
  ev.push(makeEvent(now, EventLevel::Info, EventCode::CapacityMeasured, capacity_.lastSampleAh(),
                    capacity_.lastSwingPct(), capacity_.cycles()));
  return true;
}

}  // namespace xr
