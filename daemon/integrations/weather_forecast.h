#pragma once
// An Open-Meteo daily forecast (docs/integrations.md "Weather"): the three
// days weather mode looks at, their UV index and solar radiation. Parsing is
// pure so every malformed answer can be tested without a server.
#include <array>
#include <cstdint>
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
  // Where the server says the forecast is for (Open-Meteo's grid point);
  // nullopt when the answer does not say.
  std::optional<double> latitude, longitude;
};

struct ForecastParse {
  std::optional<Forecast> forecast;
  std::string error;  // why there is none: "not JSON", "no daily.time array", ...
};

// The body of GET <url>?daily=uv_index_max,shortwave_radiation_sum&forecast_days=3.
// A wrong shape (daily missing, arrays of different lengths, a string where a
// number belongs, a UV index outside 0..30) is an error, never a guess.
ForecastParse parseOpenMeteoDaily(std::string_view body);

// A forecast may differ from the place asked by the server's grid (a few
// km); more than this is another place's weather.
inline constexpr double kForecastPlaceToleranceDeg = 0.5;

// Why f is not the forecast asked for, "" when it is: its place more than
// kForecastPlaceToleranceDeg from (latitude, longitude) or not given, or its
// days not today and the next ones (today in the place's own time zone: the
// UTC date +-1 day), e.g. a cached answer from 1999 or one for 2099. Such a
// forecast could rest the alternator on another day's or place's sun.
std::string forecastMismatch(const Forecast& f, double latitude, double longitude, std::int64_t unixNowS);

}  // namespace xr::integrations
