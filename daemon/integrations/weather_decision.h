#pragma once
// Weather mode's rule (docs/integrations.md
// "Weather"): of the next three days, two or more with a UV index above
// UVThresholdHigh mean the sun will charge the battery, and the alternator
// may rest. Pure: the client feeds it the parsed forecast and its age.
#include <string>

#include "integrations/weather_forecast.h"

namespace xr::integrations {

// A forecast older than this says nothing about today.
inline constexpr double kForecastMaxAgeS = 24.0 * 3600.0;

struct WeatherDecision {
  bool active = false;  // weather mode holds the alternator off
  int sunnyDays = 0;    // days strictly above the threshold
  std::string why;      // for the event and the dashboard
};

// A day exactly at the threshold is not sunny; a missing day or a null UV
// index counts as not sunny (the regulator charges when it cannot know).
WeatherDecision decideWeatherMode(const Forecast& f, double uvThresholdHigh, double ageS);

}  // namespace xr::integrations
