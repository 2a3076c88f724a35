#include "control/temp_compensation.h"

#include <algorithm>
#include <cmath>

#include "params/constants.h"
#include "params/derived.h"

namespace xr {

int compensationCells(const Params& p) {
  if (p.BatteryCells > 0) return p.BatteryCells;
  return 6 * nominalVoltage(systemClass(p)) / 12;
}

double temperatureCompensationV(const Params& p, double tempC) {
  if (!std::isfinite(tempC) || p.TempCompMvPerCellC == 0.0) return 0.0;
  const double t =
      std::clamp(tempC, std::min(p.TempCompMinC, p.TempCompMaxC), std::max(p.TempCompMinC, p.TempCompMaxC));
  return p.TempCompMvPerCellC / 1000.0 * compensationCells(p) * (t - k::TEMP_COMP_REFERENCE_C);
}

double compensationCeilingV(const Params& p) {
  return std::min(alternatorHardShutdownV(p), voltageHardwareLimit(p)) - k::TEMP_COMP_TRIP_MARGIN_V;
}

void compensateTargets(const Params& p, double offsetV, Params& out) {
  out = p;
  const double ceiling = compensationCeilingV(p);
  out.BulkVoltage = std::min(p.BulkVoltage + offsetV, ceiling);
  out.AbsorptionVoltage = std::min(p.AbsorptionVoltage + offsetV, ceiling);
  out.FloatVoltage = std::min(p.FloatVoltage + offsetV, ceiling);
}

}  // namespace xr
