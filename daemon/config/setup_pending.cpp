#include "config/setup_pending.h"

#include <algorithm>

#include "config/format.h"
#include "params/derived.h"

namespace xr {

namespace {

// Lowers (or, with raise, raises) the value of `name` to `limit`.
void limitValue(Params& p, std::string_view name, double limit, bool raise, NameSet& capped) {
  const ParamSpec* s = findParam(name);
  const double v = s->get(p, 0);
  if (raise ? v >= limit : v <= limit) return;
  s->set(p, 0, limit);
  capped.emplace(name);
}

}  // namespace

bool batteryChosen(const NameSet& fileNames, const NameSet& dashboardNames) {
  return fileNames.count("BatteryProfile") > 0 || dashboardNames.count("BatteryProfile") > 0;
}

Params withSetupPendingLimits(const Params& in, NameSet& capped) {
  Params p = in;
  const double k = bankScale(p);  // from BulkVoltage before it is lowered: the same class
  const double charge = kSetupPendingChargeV12 * k;
  limitValue(p, "BulkVoltage", charge, false, capped);
  limitValue(p, "AbsorptionVoltage", charge, false, capped);
  limitValue(p, "FloatVoltage", kSetupPendingFloatV12 * k, false, capped);
  limitValue(p, "ChargeMinTempC", kSetupPendingMinTempC, true, capped);
  limitValue(p, "ChargeFullCurrentTempC", kSetupPendingMinTempC, true, capped);  // not below the minimum
  limitValue(p, "ChargeMaxTempC", kSetupPendingMaxTempC, false, capped);
  limitValue(p, "TempCompMvPerCellC", 0.0, true, capped);
  return p;
}

std::string setupPendingLimitsText(const Params& p) {
  const double k = bankScale(p);
  return "at most " + formatNumber(kSetupPendingChargeV12 * k) + " V, float " +
         formatNumber(kSetupPendingFloatV12 * k) + " V, battery " + formatNumber(kSetupPendingMinTempC) +
         "-" + formatNumber(kSetupPendingMaxTempC) + " °C when a sensor reads it";
}

}  // namespace xr
