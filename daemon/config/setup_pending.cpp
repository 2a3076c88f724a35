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

double setupPendingChargeCeiling(const Params& p) { return kSetupPendingChargeV12 * bankScale(p); }

Params withSetupPendingLimits(const Params& in, NameSet& capped) {
  Params p = in;
  const double k = bankScale(p);  // from BulkVoltage before it is lowered: the same class
  const double charge = kSetupPendingChargeV12 * k;
  const double flt = kSetupPendingFloatV12 * k;
  limitValue(p, "BulkVoltage", charge, false, capped);
  limitValue(p, "AbsorptionVoltage", charge, false, capped);
  limitValue(p, "FloatVoltage", flt, false, capped);
  // Every other voltage target and threshold that would sit above the
  // lowered set: a stored or old value cannot leak through them.
  limitValue(p, "TargetVoltageSetpoint", charge, false, capped);
  limitValue(p, "ChargedVoltage", charge, false, capped);
  if (p.RebulkVoltage >= p.FloatVoltage)
    limitValue(p, "RebulkVoltage", p.FloatVoltage - kSetupPendingRebulkGapV12 * k, false, capped);
  limitValue(p, "ChargeMinTempC", kSetupPendingMinTempC, true, capped);
  limitValue(p, "ChargeFullCurrentTempC", kSetupPendingMinTempC, true, capped);  // not below the minimum
  limitValue(p, "ChargeMaxTempC", kSetupPendingMaxTempC, false, capped);
  limitValue(p, "TempCompMvPerCellC", 0.0, true, capped);
  p.SetupCeilingV = charge;
  return p;
}

std::vector<ConfigError> checkSetupPendingTargets(const Params& p) {
  std::vector<ConfigError> errs;
  const double k = bankScale(p);
  const double charge = kSetupPendingChargeV12 * k;
  const double flt = std::min(p.FloatVoltage, kSetupPendingFloatV12 * k);
  const std::string why =
      " while not set up (no battery type chosen: BatteryProfile, in the file or on the set-up page)";
  auto err = [&](const char* name, std::string msg) { errs.push_back({"", 0, 0, name, std::move(msg)}); };
  if (p.TargetVoltageSetpoint > charge)
    err("TargetVoltageSetpoint", "TargetVoltageSetpoint " + formatNumber(p.TargetVoltageSetpoint) +
                                     " V is above the charge limit " + formatNumber(charge) + " V" + why);
  if (p.ChargedVoltage > charge)
    err("ChargedVoltage", "ChargedVoltage " + formatNumber(p.ChargedVoltage) +
                              " V is above the charge limit " + formatNumber(charge) + " V" + why +
                              ": a full bank would never be seen as full");
  if (p.RebulkVoltage >= flt)
    err("RebulkVoltage", "RebulkVoltage " + formatNumber(p.RebulkVoltage) +
                             " V must be below the float limit " + formatNumber(flt) + " V" + why);
  return errs;
}

std::string setupPendingLimitsText(const Params& p) {
  const double k = bankScale(p);
  return "at most " + formatNumber(kSetupPendingChargeV12 * k) + " V, float " +
         formatNumber(kSetupPendingFloatV12 * k) + " V, battery " + formatNumber(kSetupPendingMinTempC) +
         "-" + formatNumber(kSetupPendingMaxTempC) + " °C when a sensor reads it";
}

}  // namespace xr
