#include "integrations/weather_decision.h"

#include <fmt/format.h>

#include <cmath>

namespace xr::integrations {

WeatherDecision decideWeatherMode(const Forecast& f, double uvThresholdHigh, double ageS) {
  WeatherDecision d;
  if (!std::isfinite(ageS) || ageS < 0.0 || ageS > kForecastMaxAgeS) {
    d.why = "forecast older than 24 h: charging as usual";
    return d;
  }
  for (int i = 0; i < f.dayCount && i < static_cast<int>(f.days.size()); ++i) {
    const auto& uv = f.days[static_cast<std::size_t>(i)].uvIndexMax;
    if (uv && std::isfinite(*uv) && *uv > uvThresholdHigh) ++d.sunnyDays;
  }
  d.active = d.sunnyDays >= 2;
  d.why = fmt::format("{} of 3 days above UV {:g}: {}", d.sunnyDays, uvThresholdHigh,
                      d.active ? "the sun charges, the alternator rests" : "charging as usual");
  return d;
}

}  // namespace xr::integrations
