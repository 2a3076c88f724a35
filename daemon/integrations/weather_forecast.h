#pragma once
// An Open-Meteo daily forecast (docs/integrations.md "Weather"): the three
// days weather mode looks at, their UV index and solar radiation. Parsing is
// pure so every malformed answer can be tested without a server.
#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace xr::integrations {

struct ForecastDay {
  std::string date;                     // "2026-12-05" as the server sent it; empty when missing
  std::optional<double> uvIndexMax;     // null or missing in the answer -> nullopt
  std::optional<double> radiationMJm2;  // shortwave_radiation_sum, MJ/m²
};

struct Forecast {
  std::array<ForecastDay, 3> days;
  int dayCount = 0;  // days the server sent (at most 3 are kept)
};

struct ForecastParse {
  std::optional<Forecast> forecast;
  std::string error;  // why there is none: "not JSON", "no daily.time array", ...
};

// The body of GET <url>?daily=uv_index_max,shortwave_radiation_sum&forecast_days=3.
// A wrong shape (daily missing, arrays of different lengths, a string where a
// number belongs, a UV index outside 0..30) is an error, never a guess.
ForecastParse parseOpenMeteoDaily(std::string_view body);

}  // namespace xr::integrations
