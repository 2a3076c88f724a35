// AlternatorWear (docs/operations.md "Alternator wear").
#include "health/alternator_wear.h"

#include <algorithm>
#include <cmath>

namespace xr {

using namespace wear_k;

double AlternatorWear::windingC(double sensorF, double altAmps, const Params& p) noexcept {
  double share = std::isfinite(altAmps) && p.AltRatedCurrent_A > 0.0 ? altAmps / p.AltRatedCurrent_A : 0.0;
  share = std::clamp(share, 0.0, kMaxLoadShare);
  const double f = sensorF + p.AltWindingRiseF * share * share;
  return (f - 32.0) * 5.0 / 9.0;
}

double AlternatorWear::lifePerHour(double windingC, int insulationClass) noexcept {
  const int c = std::clamp(insulationClass, 0, 2);
  return std::exp2((windingC - kClassC[c]) / kHalvingC) / kClassLifeHours;
}

void AlternatorWear::update(double dt_s, bool running, double sensorF, double altAmps,
                            const Params& p) noexcept {
  if (!(dt_s > 0.0)) return;
  if (running) l_.RunTime_s += dt_s;
  // Heat soak after a stop ages the insulation too: temperature is counted
  // whenever it is known, running or not.
  if (!std::isfinite(sensorF)) return;
  for (std::size_t i = 0; i < kWearBandsF.size(); ++i)
    if (sensorF >= kWearBandsF[i]) l_.TimeAbove_s[i] += dt_s;
  l_.LifeUsed_pct += 100.0 * lifePerHour(windingC(sensorF, altAmps, p), p.AltInsulationClass) * dt_s / 3600.0;
}

void AlternatorWear::fillTelemetry(WearTelemetry& t) const noexcept {
  t.alt_run_hours = l_.RunTime_s / 3600.0;
  for (std::size_t i = 0; i < kWearBandsF.size(); ++i) t.alt_hours_above[i] = l_.TimeAbove_s[i] / 3600.0;
  t.alt_life_used_pct = l_.LifeUsed_pct;
  t.belt_slip_events = l_.BeltSlipEvents;
}

void AlternatorWear::restore(const AlternatorWearLedger& in) noexcept {
  auto ok = [](double v) { return std::isfinite(v) && v >= 0.0 && v < 1e12; };
  AlternatorWearLedger l;
  l.RunTime_s = ok(in.RunTime_s) ? in.RunTime_s : 0.0;
  for (std::size_t i = 0; i < kWearBandsF.size(); ++i)
    l.TimeAbove_s[i] = ok(in.TimeAbove_s[i]) ? in.TimeAbove_s[i] : 0.0;
  l.LifeUsed_pct = ok(in.LifeUsed_pct) ? in.LifeUsed_pct : 0.0;
  l.BeltSlipEvents = ok(in.BeltSlipEvents) ? in.BeltSlipEvents : 0.0;
  l_ = l;
}

}  // namespace xr
