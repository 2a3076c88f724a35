// BatteryAverages (docs/batteries.md "Energy and averages").
#include "battery/battery_averages.h"

#include "battery/monitor_helpers.h"

namespace xr {

using namespace battery_detail;

void BatteryAverages::commit(double socPct) noexcept {
  socSum_ += socPct * intSoc_s_;
  socTime_s_ += intSoc_s_;
  socSumAll_ += socPct * intSoc_s_;
  socTimeAll_s_ += intSoc_s_;
  vSumAll_ += intV_s_;
  vTimeAll_s_ += intVtime_s_;
  intSoc_s_ = intV_s_ = intVtime_s_ = 0.0;
}

void BatteryAverages::toLedger(BatteryLedger& l) const noexcept {
  l.socAccumulator_AllTime = socSumAll_;
  l.totalSocSampleTime_AllTime = socTimeAll_s_;
  l.voltageAccumulator_AllTime = vSumAll_;
  l.totalVoltageSampleTime_AllTime = vTimeAll_s_;
}

void BatteryAverages::restore(const BatteryLedger& l) noexcept {
  const double big = 1e15;
  socSumAll_ = clampFinite(l.socAccumulator_AllTime, 0.0, big, 0.0);
  socTimeAll_s_ = clampFinite(l.totalSocSampleTime_AllTime, 0.0, big, 0.0);
  vSumAll_ = clampFinite(l.voltageAccumulator_AllTime, 0.0, big, 0.0);
  vTimeAll_s_ = clampFinite(l.totalVoltageSampleTime_AllTime, 0.0, big, 0.0);
}

}  // namespace xr
